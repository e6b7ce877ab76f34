// Atomic file replacement (docs/architecture.md §3): the bytes go to a fresh temporary file in the
// target's directory and are renamed over the target only once completely written and closed, so a
// killed job or a full disk never leaves a torn or truncated image behind. What a killed writer
// does leave, its temporary file, is recognised by name and removed by a later run.
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <limits>

#include "render/image/image_write.hpp"

namespace tetray::render {
namespace {

constexpr std::string_view kTemporaryMark = ".tmp";

// `<path>.tmp<pid>-<counter>`: unique per process and call, so concurrent writers (threads or
// ranks sharing a directory) never open the same temporary file, and the pid tells a later run
// whether the writer still lives (parse_temporary_name).
std::string temporary_path_for(const std::string& path) {
  static std::atomic<unsigned long> counter{0};
  return path + std::string(kTemporaryMark) + std::to_string(::getpid()) + "-" +
         std::to_string(counter++);
}

// The decimal number that is all of `digits` (no sign, no spaces); nullopt otherwise.
std::optional<long> whole_number(std::string_view digits) {
  long value = 0;
  const char* end = digits.data() + digits.size();
  const auto [stop, error] = std::from_chars(digits.data(), end, value);
  if (digits.empty() || digits.front() == '-' || error != std::errc() || stop != end) {
    return std::nullopt;
  }
  return value;
}

// kill(pid, 0) probes without sending a signal; EPERM means it exists under another user. Only
// ESRCH proves the process gone, so anything else keeps its temporary file.
bool process_gone(long pid) { return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH; }

WriteResult failure(const std::string& what, const std::string& path, int error_number) {
  return {false, what + " '" + path + "': " + std::strerror(error_number)};
}

// Opens a new temporary file (O_EXCL: never an existing one); -1 with errno set on failure.
int create_temporary(const std::string& path, std::string& temporary) {
  constexpr int kAttempts = 8;  // a name left by an earlier, killed process with our pid
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    temporary = temporary_path_for(path);
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0 || errno != EEXIST) return fd;
  }
  return -1;
}

// Writes everything, retrying short writes and interrupted calls; 0 or an errno value.
int write_all(int fd, std::span<const unsigned char> bytes) {
  while (!bytes.empty()) {
    const ssize_t written = ::write(fd, bytes.data(), bytes.size());
    if (written < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    bytes = bytes.subspan(static_cast<std::size_t>(written));
  }
  return 0;
}

}  // namespace

std::optional<TemporaryName> parse_temporary_name(const std::string& file_name) {
  const std::size_t mark = file_name.rfind(kTemporaryMark);
  if (mark == std::string::npos || mark == 0) return std::nullopt;
  const std::string_view rest = std::string_view(file_name).substr(mark + kTemporaryMark.size());
  const std::size_t dash = rest.find('-');
  if (dash == std::string_view::npos) return std::nullopt;
  const std::optional<long> pid = whole_number(rest.substr(0, dash));
  if (!pid || *pid <= 0 || *pid > std::numeric_limits<pid_t>::max() ||
      !whole_number(rest.substr(dash + 1))) {
    return std::nullopt;
  }
  return TemporaryName{file_name.substr(0, mark), *pid};
}

WriteResult remove_stale_temporaries(const std::string& directory,
                                     const std::function<bool(const std::string&)>& is_target) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::directory_iterator entries(directory, ec);
  if (ec == std::errc::no_such_file_or_directory) return {};
  for (; !ec && entries != fs::directory_iterator(); entries.increment(ec)) {
    const std::string name = entries->path().filename().string();
    const std::optional<TemporaryName> temporary = parse_temporary_name(name);
    // symlink_status: a link with a temporary's name is not one this code created.
    std::error_code status_error;
    if (!temporary || !is_target(temporary->target) || !process_gone(temporary->pid) ||
        !fs::is_regular_file(entries->symlink_status(status_error))) {
      continue;
    }
    if (::unlink(entries->path().c_str()) != 0 && errno != ENOENT) {
      return failure("cannot remove the stale temporary file", entries->path().string(), errno);
    }
  }
  if (ec) return {false, "cannot list '" + directory + "': " + ec.message()};
  return {};
}

std::string create_temporary_file(const std::string& path, std::string& error) {
  std::string temporary;
  const int fd = create_temporary(path, temporary);
  if (fd < 0) {
    error = failure("cannot create a temporary file for", path, errno).message;
    return {};
  }
  ::close(fd);
  return temporary;
}

WriteResult write_file_atomically(const std::string& path, std::span<const unsigned char> bytes) {
  std::string temporary;
  const int fd = create_temporary(path, temporary);
  if (fd < 0) return failure("cannot create a temporary file for", path, errno);

  int error_number = write_all(fd, bytes);
  // close() reports deferred write errors (e.g. ENOSPC on network file systems).
  if (::close(fd) != 0 && error_number == 0) error_number = errno;
  if (error_number == 0 && ::rename(temporary.c_str(), path.c_str()) != 0) {
    error_number = errno;
  }
  if (error_number != 0) {
    ::unlink(temporary.c_str());
    return failure("cannot write", path, error_number);
  }
  return {};
}

}  // namespace tetray::render
