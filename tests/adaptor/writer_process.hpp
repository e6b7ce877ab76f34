// The writer process of killed_writer_main.cpp, for the tests that kill it at random moments:
// started, frozen for inspection, killed and reaped.
#pragma once

#include <sys/types.h>

#include <filesystem>

namespace tetray::testing {

// Lets the writers exit without LeakSanitizer's report: they start MPI, whose own allocations it
// would report (tests/support/lsan_options.cpp). Call before the first start_writer.
void without_leak_check_in_writers();

// Starts the writer on steps [first_step, first_step + steps) into `dir` (with `movie`, PNG and
// the movie, else PNG and EXR); returns its pid once it has written its start byte (-1 if it
// died first).
pid_t start_writer(const std::filesystem::path& dir, long long first_step, long long steps,
                   bool movie = false);

// Stops the writer (every thread: waitpid reports the stop once the whole group is stopped).
bool freeze(pid_t writer);

// SIGKILL, then reaped: false when the writer had ended on its own before the kill.
bool kill_writer(pid_t writer);

// Waits for the writer to exit; its exit code, or -1 when it did not exit normally.
int wait_writer(pid_t writer);

}  // namespace tetray::testing
