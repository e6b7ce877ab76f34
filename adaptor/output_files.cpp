#include "output_files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "render/core/stopwatch.hpp"
#include "render/image/image_write.hpp"

namespace tetray {
namespace {

std::string errno_message(const std::string& what, const std::string& path) {
  return what + " " + path + ": " + std::strerror(errno);
}

std::string create_with_header(const std::string& path, const std::string& header) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) return errno_message("cannot create", path);
  const bool written = std::fputs((header + '\n').c_str(), f) >= 0;
  const bool closed = std::fclose(f) == 0;
  return written && closed ? std::string() : errno_message("cannot write", path);
}

std::string cinema_header(const config::Output& output) {
  std::string header = "step,time";
  if (output.png) header += ",FILE";
  if (output.exr) header += output.png ? ",FILE_exr" : ",FILE";
  return header;
}

std::string cinema_row(const config::Output& output, const StepRecord& r) {
  std::string row = std::to_string(r.step) + ',' + time_text(r.time);
  // Files relative to the .cdb directory.
  const std::string dir = "..";
  if (output.png) row += ',' + image_path(dir, r.scene, r.step, "png");
  if (output.exr) row += ',' + image_path(dir, r.scene, r.step, "exr");
  return row;
}

// "Under" operator with premultiplied colors: what the image leaves uncovered shows the
// background.
void put_background_under(render::Framebuffer& image, const float background[4]) {
  if (background[3] == 0) return;
  for (std::size_t p = 0; p < image.pixel_count(); ++p) {
    float* px = &image.rgba[4 * p];
    const float uncovered = 1.0f - px[3];
    for (int c = 0; c < 3; ++c) px[c] += uncovered * background[3] * background[c];
    px[3] += uncovered * background[3];
  }
}

std::uint64_t count_hits(const render::Framebuffer& image) {
  std::uint64_t hits = 0;
  for (std::uint32_t key : image.hit) hits += key != render::kNoHit;
  return hits;
}

// `number` zero-padded to `digits` (more digits when it needs them).
std::string padded(long long number, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%0*lld", digits, number);
  return text;
}

std::string make_directory(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  return ec ? "cannot create output directory " + dir.string() + ": " + ec.message()
            : std::string();
}

}  // namespace

std::string image_path(const std::string& directory, const std::string& scene, std::int64_t step,
                       const char* extension) {
  return directory + '/' + scene + '/' + scene + '_' + padded(step, 6) + '.' + extension;
}

std::string rank_image_path(const std::string& directory, const std::string& scene,
                            std::int64_t step, int rank) {
  return directory + '/' + scene + "/ranks/" + scene + '_' + padded(step, 6) + "_rank" +
         padded(rank, 4) + ".png";
}

std::string log_path(const std::string& directory) { return directory + "/tetray_log.csv"; }

std::string cinema_path(const std::string& directory, const std::string& scene) {
  return directory + '/' + scene + ".cdb/data.csv";
}

std::string prepare_outputs(const config::Output& output,
                            const std::vector<config::Scene>& scenes) {
  namespace fs = std::filesystem;
  for (const config::Scene& s : scenes) {
    for (const fs::path& dir :
         {fs::path(output.directory) / s.name, fs::path(output.directory) / (s.name + ".cdb")}) {
      if (auto e = make_directory(dir); !e.empty()) return e;
    }
    if (output.cinema) {
      if (auto e = create_with_header(cinema_path(output.directory, s.name), cinema_header(output));
          !e.empty()) {
        return e;
      }
    }
  }
  return create_with_header(log_path(output.directory), log_header());
}

std::string prepare_rank_image_directories(const config::Output& output,
                                           const std::vector<config::Scene>& scenes) {
  for (const config::Scene& s : scenes) {
    if (auto e = make_directory(std::filesystem::path(output.directory) / s.name / "ranks");
        !e.empty()) {
      return e;
    }
  }
  return {};
}

std::string write_rank_image(const config::Output& output, const std::string& scene,
                             std::int64_t step, int rank, const render::Framebuffer& image) {
  const render::WriteResult written = render::write_png(
      image, rank_image_path(output.directory, scene, step, rank), output.png_compression);
  return written.ok ? std::string() : written.message;
}

std::string append_line(const std::string& path, const std::string& line) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd < 0) return errno_message("cannot open", path);
  struct stat before {};
  ::fstat(fd, &before);
  const std::string text = line + '\n';
  const ssize_t n = ::write(fd, text.data(), text.size());
  std::string error;
  if (n != static_cast<ssize_t>(text.size())) {
    error = n < 0 ? errno_message("cannot append to", path)
                  : "cannot append to " + path + ": short write (disk full?)";
    if (::ftruncate(fd, before.st_size) != 0) error += "; and could not undo the partial line";
  }
  ::close(fd);
  return error;
}

std::string write_image_job(const config::Output& output, ImageJob& job) {
  StepRecord& r = job.record;
  put_background_under(job.image, job.background);
  r.hits = count_hits(job.image);
  for (const char* format : {"exr", "png"}) {
    const bool exr = format[0] == 'e';
    if (!(exr ? output.exr : output.png)) continue;
    const render::Stopwatch encoding;
    const render::EncodedImage encoded =
        exr ? render::encode_exr(job.image) : render::encode_png(job.image, output.png_compression);
    r.encode_ms += encoding.ms();
    if (!encoded.ok()) return encoded.error;
    const render::Stopwatch writing;
    const auto written = render::write_file_atomically(
        image_path(output.directory, r.scene, r.step, format), encoded.bytes);
    r.write_ms += writing.ms();
    if (!written.ok) return written.message;
  }
  const render::Stopwatch appending;
  if (output.cinema) {
    if (auto e = append_line(cinema_path(output.directory, r.scene), cinema_row(output, r));
        !e.empty()) {
      return e;
    }
  }
  r.write_ms += appending.ms();
  return append_line(log_path(output.directory), log_row(r));
}

}  // namespace tetray
