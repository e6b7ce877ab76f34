# A test that fails with MESSAGE: what a missing test package registers in place of its tests,
# so that the suite says what is missing instead of passing without them.
#   cmake -DMESSAGE=... -P fail_with_message.cmake
message(FATAL_ERROR "${MESSAGE}")
