// Atomic file replacement (docs/architecture.md §3): the bytes go to a fresh temporary file in the
// target's directory and are renamed over the target only once completely written and closed, so a
// killed job or a full disk never leaves a torn or truncated image behind.
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

#include "render/image/image_write.hpp"

namespace tetray::render {
namespace {

// Unique per process and call, so concurrent writers (threads or ranks sharing a directory)
// never open the same temporary file.
std::string temporary_path_for(const std::string& path) {
  static std::atomic<unsigned long> counter{0};
  return path + ".tmp" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

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
