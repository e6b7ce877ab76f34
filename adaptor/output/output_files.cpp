#include "adaptor/output/output_files.hpp"

#include <cstdio>
#include <filesystem>
#include <functional>
#include <string_view>

#include "adaptor/config/config_output.hpp"
#include "adaptor/output/line_file.hpp"
#include "adaptor/output/viewer_files.hpp"
#include "render/core/stopwatch.hpp"
#include "render/image/image_write.hpp"

namespace tetray {
namespace {

// Cinema spec D: the parameter columns, then the files of each row (FILE columns).
constexpr const char* kCinemaParameters = "time,phi,theta,scene,step";
constexpr std::size_t kCinemaParameterCount = 5;

std::string cinema_header(const config::Output& output) {
  std::string header = kCinemaParameters;
  if (output.png) header += ",FILE";
  if (output.exr) header += output.png ? ",FILE_exr" : ",FILE";
  return header;
}

std::string cinema_row(const config::Output& output, const ImageJob& job) {
  const StepRecord& r = job.record;
  std::string row = time_text(r.time) + ',' + time_text(job.phi) + ',' + time_text(job.theta) +
                    ',' + r.scene + ',' + std::to_string(r.step);
  // Files relative to the .cdb directory.
  const std::string dir = "..";
  if (output.png) row += ',' + image_path(dir, r.scene, r.step, "png", job.view);
  if (output.exr) row += ',' + image_path(dir, r.scene, r.step, "exr", job.view);
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

namespace fs = std::filesystem;

// Folders inside the output directory are created real: a symbolic link planted there is
// refused, as line_file refuses one in place of a table, so no output lands outside the tree.
std::string make_directory(const fs::path& dir) {
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(dir, ec))) {
    return "refusing to write into '" + dir.string() + "': it is a symbolic link";
  }
  fs::create_directories(dir, ec);
  return ec ? "cannot create output directory " + dir.string() + ": " + ec.message()
            : std::string();
}

// Whether `name` is `<prefix><step><suffix>`, the step as padded() writes it: the shape of the
// names image_path and rank_image_path give.
bool is_numbered_name(std::string_view name, std::string_view prefix, std::string_view suffix) {
  if (name.size() <= prefix.size() + suffix.size() || !name.starts_with(prefix) ||
      !name.ends_with(suffix)) {
    return false;
  }
  std::string_view step = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (step.front() == '-') step.remove_prefix(1);
  return !step.empty() && step.find_first_not_of("0123456789") == std::string_view::npos;
}

// Whether `name` is an image of a scene's orbit: `<prefix><step>_view<digits><extension>`.
bool is_view_image_name(std::string_view name, std::string_view prefix,
                        std::string_view extension) {
  if (!name.ends_with(extension)) return false;
  const std::string_view stem = name.substr(0, name.size() - extension.size());
  const std::size_t view = stem.rfind("_view");
  if (view == std::string_view::npos) return false;
  const std::string_view digits = stem.substr(view + 5);
  return !digits.empty() && digits.find_first_not_of("0123456789") == std::string_view::npos &&
         is_numbered_name(stem.substr(0, view), prefix, "");
}

using NamePredicate = std::function<bool(const std::string&)>;

// Temporary files of a killed earlier run, only those of the files this run writes in `dir`.
std::string remove_stale_temporaries_in(const fs::path& dir, const NamePredicate& is_target) {
  const render::WriteResult removed = render::remove_stale_temporaries(dir.string(), is_target);
  return removed.ok ? std::string() : removed.message;
}

// Accepts the file name of `path` only.
NamePredicate named_as(const std::string& path) {
  return [name = fs::path(path).filename().string()](const std::string& n) { return n == name; };
}

std::vector<std::string> split_cells(const std::string& row) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  for (std::size_t comma; (comma = row.find(',', start)) != std::string::npos; start = comma + 1) {
    cells.push_back(row.substr(start, comma - start));
  }
  cells.push_back(row.substr(start));
  return cells;
}

// A Cinema row with the header's column count whose every image (the columns after the
// parameters, relative to the .cdb folder) is a file on disk.
bool lists_images_on_disk(const fs::path& cdb_dir, const std::string& row, std::size_t columns) {
  const std::vector<std::string> cells = split_cells(row);
  if (cells.size() != columns) return false;
  for (std::size_t c = kCinemaParameterCount; c < cells.size(); ++c) {
    std::error_code ec;
    if (!fs::is_regular_file(fs::symlink_status(cdb_dir / cells[c], ec))) return false;
  }
  return true;
}

// Opens a table for this run's appends: the rows of an earlier run that `keep_row` accepts stay,
// after `header`; a file with another header (other formats, another version) starts afresh. The
// file is rewritten, atomically, only when that changes it: a last line torn by a killed run or a
// dropped row.
std::string reopen_table(const std::string& path, const std::string& header,
                         const NamePredicate& keep_row) {
  const FileLines old = read_complete_lines(path);
  if (!old.error.empty()) return old.error;
  std::vector<std::string> lines{header};
  if (!old.lines.empty() && old.lines.front() == header) {
    for (std::size_t k = 1; k < old.lines.size(); ++k) {
      if (keep_row(old.lines[k])) lines.push_back(old.lines[k]);
    }
  }
  if (old.exists && !old.torn && lines == old.lines) return {};
  return replace_lines(path, lines);
}

std::string prepare_scene_outputs(const config::Output& output, const std::string& scene) {
  const fs::path images = fs::path(output.directory) / scene;
  const fs::path cdb = fs::path(output.directory) / (scene + ".cdb");
  for (const fs::path& dir : {images, cdb}) {
    if (auto e = make_directory(dir); !e.empty()) return e;
  }
  const std::string prefix = scene + '_';
  // The images and the movies (a movie is never per view).
  const auto is_image_or_movie = [&](const std::string& name) {
    if (is_numbered_name(name, prefix, ".mp4")) return true;
    for (const char* extension : {".png", ".exr"}) {
      if (is_numbered_name(name, prefix, extension) ||
          is_view_image_name(name, prefix, extension)) {
        return true;
      }
    }
    return false;
  };
  const std::string table = cinema_path(output.directory, scene);
  const std::string script = cinema_script_path(output.directory, scene);
  if (auto e = remove_stale_temporaries_in(images, is_image_or_movie); !e.empty()) return e;
  const auto is_table = [&](const std::string& n) {
    return named_as(table)(n) || named_as(script)(n);
  };
  if (auto e = remove_stale_temporaries_in(cdb, is_table); !e.empty()) return e;
  if (!output.cinema) return {};
  const std::string header = cinema_header(output);
  const std::size_t columns = split_cells(header).size();
  const std::string reopened = reopen_table(table, header, [&](const std::string& row) {
    return lists_images_on_disk(cdb, row, columns);
  });
  return reopened.empty() ? write_cinema_script(output.directory, scene) : reopened;
}

// Whether an image of this step and view is already on disk: a step rendered again, by this run
// or an earlier one, whose Cinema row is to be replaced rather than listed twice.
bool rendered_before(const config::Output& output, const ImageJob& job) {
  const StepRecord& r = job.record;
  std::error_code ec;
  for (const char* format : {"exr", "png"}) {
    const bool wanted = format[0] == 'e' ? output.exr : output.png;
    const fs::path image = image_path(output.directory, r.scene, r.step, format, job.view);
    if (wanted && fs::exists(fs::symlink_status(image, ec))) return true;
  }
  return false;
}

// The table without its rows of `row`'s image (its first file), then `row`, replaced atomically.
// Costs the table's size, paid only for a step rendered again: 1-3 ms for a 5,000-row table (340
// kB) on ext4, small next to encoding the image, since the table holds one short row per image.
std::string replace_row(const std::string& path, const std::string& row) {
  const FileLines table = read_complete_lines(path);
  if (!table.error.empty()) return table.error;
  if (table.lines.empty()) return "cannot update '" + path + "': its header is missing";
  const std::string image = split_cells(row).at(kCinemaParameterCount);
  std::vector<std::string> lines{table.lines.front()};
  for (std::size_t k = 1; k < table.lines.size(); ++k) {
    const std::vector<std::string> cells = split_cells(table.lines[k]);
    if (cells.size() <= kCinemaParameterCount || cells[kCinemaParameterCount] != image) {
      lines.push_back(table.lines[k]);
    }
  }
  lines.push_back(row);
  return replace_lines(path, lines);
}

}  // namespace

std::string image_path(const std::string& directory, const std::string& scene, std::int64_t step,
                       const char* extension, int view) {
  const std::string name = scene + '_' + padded(step, 6);
  return directory + '/' + scene + '/' + name + (view < 0 ? "" : "_view" + padded(view, 3)) + '.' +
         extension;
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
  for (const config::Scene& s : scenes) {
    if (auto e = prepare_scene_outputs(output, s.name); !e.empty()) return e;
  }
  const std::string log = log_path(output.directory);
  const std::string page = viewer_page_path(output.directory);
  const auto is_own = [&](const std::string& n) { return named_as(log)(n) || named_as(page)(n); };
  if (auto e = remove_stale_temporaries_in(output.directory, is_own); !e.empty()) return e;
  return reopen_table(log, log_header(), [](const std::string&) { return true; });
}

std::string prepare_rank_image_directories(const config::Output& output,
                                           const std::vector<config::Scene>& scenes, int rank) {
  for (const config::Scene& s : scenes) {
    const fs::path ranks = fs::path(output.directory) / s.name / "ranks";
    if (auto e = make_directory(ranks); !e.empty()) return e;
    const std::string prefix = s.name + '_';
    const std::string suffix = "_rank" + padded(rank, 4) + ".png";
    const auto is_mine = [&](const std::string& name) {
      return is_numbered_name(name, prefix, suffix);
    };
    if (auto e = remove_stale_temporaries_in(ranks, is_mine); !e.empty()) return e;
  }
  return {};
}

std::string write_rank_image(const config::Output& output, const std::string& scene,
                             std::int64_t step, int rank, const render::Framebuffer& image) {
  const render::WriteResult written = render::write_png(
      image, rank_image_path(output.directory, scene, step, rank), output.png_compression);
  return written.ok ? std::string() : written.message;
}

std::string write_image_job(const config::Output& output, ImageJob& job) {
  StepRecord& r = job.record;
  const bool listed = output.cinema && rendered_before(output, job);
  put_background_under(job.image, job.background);
  const render::Stopwatch annotating;  // counted as encoding: it prepares the encoded pixels
  render::draw_annotations(job.image, job.annotations, job.background);
  r.encode_ms += annotating.ms();
  r.hits = count_hits(job.image);
  const render::Stopwatch encoding;
  const render::EncodedImages images =
      render::encode_images(job.image, output.exr, output.png, config::encode_options(output));
  r.encode_ms += encoding.ms();
  for (const char* format : {"exr", "png"}) {
    const bool exr = format[0] == 'e';
    if (!(exr ? output.exr : output.png)) continue;
    const render::EncodedImage& encoded = exr ? images.exr : images.png;
    if (!encoded.ok()) return encoded.error;
    const render::Stopwatch writing;
    const auto written = render::write_file_atomically(
        image_path(output.directory, r.scene, r.step, format, job.view), encoded.bytes);
    r.write_ms += writing.ms();
    if (!written.ok) return written.message;
  }
  const render::Stopwatch appending;
  if (output.cinema) {
    const std::string table = cinema_path(output.directory, r.scene);
    const std::string row = cinema_row(output, job);
    if (auto e = listed ? replace_row(table, row) : append_line(table, row); !e.empty()) {
      return e;
    }
    if (auto e = write_cinema_script(output.directory, r.scene); !e.empty()) return e;
  }
  r.write_ms += appending.ms();
  if (job.viewer_page_scenes.empty()) return {};
  return write_viewer_page(output.directory, job.viewer_page_scenes);
}

}  // namespace tetray
