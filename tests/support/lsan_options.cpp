// Tests that start MPI: Open MPI's own allocations (partly in MCA components unloaded before
// the report, so no suppression can name them) would be reported as leaks. These tests keep
// AddressSanitizer's memory-error checks and UBSan but not the leak check (scripts/test.sh keeps
// it for the unit tests that do not start MPI). Only read by sanitizer builds.
extern "C" const char* __lsan_default_options() { return "detect_leaks=0"; }
