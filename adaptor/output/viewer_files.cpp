#include "adaptor/output/viewer_files.hpp"

#include <cstdio>
#include <span>
#include <string_view>

#include "adaptor/output/line_file.hpp"
#include "adaptor/output/output_files.hpp"
#include "render/image/image_write.hpp"

namespace tetray {
namespace {

std::string write_text(const std::string& path, const std::string& text) {
  const auto bytes = std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size());
  const render::WriteResult written = render::write_file_atomically(path, bytes);
  return written.ok ? std::string() : written.message;
}

}  // namespace

std::string viewer_page_path(const std::string& directory) { return directory + "/index.html"; }

std::string cinema_script_path(const std::string& directory, const std::string& scene) {
  return directory + '/' + scene + ".cdb/data.js";
}

std::string js_string(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '<':
        out += "\\u003c";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char escaped[8];
          std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned>(c));
          out += escaped;
        } else {
          out += c;
        }
    }
  }
  return out + '"';
}

std::string write_viewer_page(const std::string& directory,
                              const std::vector<std::string>& scenes) {
  std::string list = "[";
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    if (k > 0) list += ',';
    list += js_string(scenes[k]);
  }
  list += "]";
  std::string page = kViewerPage;
  const std::string_view marker = "/*TETRAY_SCENES*/[]";
  const std::size_t at = page.find(marker);
  if (at == std::string::npos) return "the viewer page has no scene list marker";
  page.replace(at, marker.size(), list);
  return write_text(viewer_page_path(directory), page);
}

std::string write_cinema_script(const std::string& directory, const std::string& scene) {
  const FileLines table = read_complete_lines(cinema_path(directory, scene));
  if (!table.error.empty()) return table.error;
  std::string csv;
  for (const std::string& line : table.lines) csv += line + '\n';
  return write_text(cinema_script_path(directory, scene),
                    "tetrayCinema(" + js_string(scene) + ", " + js_string(csv) + ");\n");
}

}  // namespace tetray
