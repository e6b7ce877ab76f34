// Text files of whole lines (the Cinema table and the timing log of docs/outputs.md) that
// a run killed at any moment leaves with every line complete: a line is appended with one write()
// on an O_APPEND descriptor, a file is replaced whole through render/image's atomic write, and a
// reader drops a last line without its newline. None of them follows a symbolic link or writes
// to anything but a regular file: a link planted where the file belongs is an error naming it,
// never a way to overwrite a file elsewhere. Functions return an error message, empty on success.
#pragma once

#include <string>
#include <vector>

namespace tetray {

struct FileLines {
  bool exists = false;
  std::vector<std::string> lines;  // the complete lines, without their newlines
  bool torn = false;               // the file ended in a line without a newline (left out)
  std::string error;               // empty on success; a missing file is no error
};
FileLines read_complete_lines(const std::string& path);

// Replaces the file at `path` with `lines`, a newline after each, atomically: a reader or a
// later run sees the old file or the new one, whole.
std::string replace_lines(const std::string& path, const std::vector<std::string>& lines);

// Appends `line` and a newline to an existing file; a failed or short write is truncated back to
// the old length.
std::string append_line(const std::string& path, const std::string& line);

}  // namespace tetray
