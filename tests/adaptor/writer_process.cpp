#include "writer_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

extern char** environ;

namespace tetray::testing {

void without_leak_check_in_writers() {
  // The last option given wins.
  const char* asan = std::getenv("ASAN_OPTIONS");
  ::setenv("ASAN_OPTIONS", (std::string(asan ? asan : "") + ":detect_leaks=0").c_str(), 1);
}

pid_t start_writer(const std::filesystem::path& dir, long long first_step, long long steps,
                   bool movie) {
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) return -1;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDOUT_FILENO);
  const std::string dir_arg = dir.string(), first = std::to_string(first_step),
                    count = std::to_string(steps);
  char movie_arg[] = "movie";
  char* argv[] = {const_cast<char*>(TETRAY_KILLED_WRITER),
                  const_cast<char*>(dir_arg.c_str()),
                  const_cast<char*>(first.c_str()),
                  const_cast<char*>(count.c_str()),
                  movie ? movie_arg : nullptr,
                  nullptr};
  pid_t pid = -1;
  const int spawned = posix_spawn(&pid, TETRAY_KILLED_WRITER, &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fds[1]);
  char started = 0;
  const bool ready = spawned == 0 && ::read(pipe_fds[0], &started, 1) == 1;
  ::close(pipe_fds[0]);
  if (spawned == 0 && !ready) ::waitpid(pid, nullptr, 0);
  return ready ? pid : -1;
}

bool freeze(pid_t writer) {
  int status = 0;
  return ::kill(writer, SIGSTOP) == 0 && ::waitpid(writer, &status, WUNTRACED) == writer &&
         WIFSTOPPED(status);
}

bool kill_writer(pid_t writer) {
  int status = 0;
  return ::kill(writer, SIGKILL) == 0 && ::waitpid(writer, &status, 0) == writer &&
         WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}

int wait_writer(pid_t writer) {
  int status = 0;
  if (::waitpid(writer, &status, 0) != writer || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

}  // namespace tetray::testing
