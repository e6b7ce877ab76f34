#include "adaptor/output/line_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <span>

#include "render/image/image_write.hpp"

namespace tetray {
namespace {

std::string errno_message(const std::string& what, const std::string& path, int error_number) {
  return what + " '" + path + "': " + std::strerror(error_number);
}

// A descriptor closed on every path out of a function.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

// Opens `path` with `flags`, refusing a symbolic link (O_NOFOLLOW) and anything but a regular
// file: O_NONBLOCK makes opening a FIFO return at once instead of waiting for a reader, and the
// fstat then refuses it. -1 with `error` set when refused or failed.
int open_regular(const std::string& path, int flags, std::string& error) {
  const int fd = ::open(path.c_str(), flags | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    struct stat link {};
    const bool is_link =
        errno == ELOOP && ::lstat(path.c_str(), &link) == 0 && S_ISLNK(link.st_mode);
    error = is_link ? "refusing to use '" + path + "': it is a symbolic link"
                    : errno_message("cannot open", path, errno);
    return -1;
  }
  struct stat file {};
  if (::fstat(fd, &file) != 0 || !S_ISREG(file.st_mode)) {
    ::close(fd);
    error = "refusing to use '" + path + "': not a regular file";
    return -1;
  }
  return fd;
}

// The whole contents of an open file; false with errno set on a read error.
bool read_all(int fd, std::string& text) {
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n == 0) return true;
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return false;
    text.append(buffer, static_cast<std::size_t>(n));
  }
}

}  // namespace

FileLines read_complete_lines(const std::string& path) {
  FileLines file;
  struct stat entry {};
  if (::lstat(path.c_str(), &entry) != 0 && errno == ENOENT) return file;
  const Descriptor fd(open_regular(path, O_RDONLY, file.error));
  if (fd.get() < 0) return file;
  file.exists = true;
  std::string text;
  if (!read_all(fd.get(), text)) {
    file.error = errno_message("cannot read", path, errno);
    return file;
  }
  std::size_t start = 0;
  for (std::size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1) {
    file.lines.push_back(text.substr(start, end - start));
  }
  file.torn = start < text.size();
  return file;
}

std::string replace_lines(const std::string& path, const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + '\n';
  // rename() replaces whatever is at `path`, a symbolic link included, without following it.
  const render::WriteResult written = render::write_file_atomically(
      path, std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size()));
  return written.ok ? std::string() : written.message;
}

// One write() of the whole line on an O_APPEND descriptor, rather than rewriting the file
// atomically per row: an append costs the same at every step, while a rewrite costs the file's
// size, which grows with the run. Measured on ext4: 11-15 us per append (open, fstat, write,
// close), 7-8 ms to rewrite the log of a 5,000-step run (1 MB), so a rewrite per row would make a
// run quadratic. A kill cannot split a write() that stays within one page of the file; Linux
// stops a write at a page boundary when a fatal signal is pending, so a line that straddles one
// can be cut if the kill lands in the instant between its two pages. read_complete_lines drops
// such a line, and the next run's start (prepare_outputs) rewrites the file without it.
std::string append_line(const std::string& path, const std::string& line) {
  std::string error;
  const Descriptor fd(open_regular(path, O_WRONLY | O_APPEND, error));
  if (fd.get() < 0) return error;
  struct stat before {};
  if (::fstat(fd.get(), &before) != 0) return errno_message("cannot append to", path, errno);
  const std::string text = line + '\n';
  const ssize_t n = ::write(fd.get(), text.data(), text.size());
  if (n == static_cast<ssize_t>(text.size())) return {};
  error = n < 0 ? errno_message("cannot append to", path, errno)
                : "cannot append to '" + path + "': short write (disk full?)";
  if (::ftruncate(fd.get(), before.st_size) != 0) error += "; and could not undo the partial line";
  return error;
}

}  // namespace tetray
