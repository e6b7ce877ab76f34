#include "tools/render/scratch_output.hpp"

#include <stdlib.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace tetray::tools {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream text(line);
  for (std::string cell; std::getline(text, cell, ',');) cells.push_back(cell);
  return cells;
}

}  // namespace

ScratchOutput::~ScratchOutput() {
  if (directory_.empty()) return;
  std::error_code ignored;
  fs::remove_all(directory_, ignored);
}

bool ScratchOutput::create(const std::string& image_path, std::string& error) {
  fs::path parent = fs::path(image_path).parent_path();
  if (parent.empty()) parent = ".";
  std::string pattern = (parent / ".tetray-render-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    error = "cannot write '" + image_path +
            "': cannot create a scratch folder beside it: " + std::strerror(errno);
    return false;
  }
  directory_ = pattern;
  return true;
}

bool ScratchOutput::read_figures(StepFigures& figures, std::string& error) const {
  const std::string path = (fs::path(directory_) / "tetray_log.csv").string();
  std::ifstream log(path);
  std::string header, row;
  if (!std::getline(log, header) || !std::getline(log, row)) {
    error = "the adaptor wrote no log row in '" + path + "'";
    return false;
  }
  const std::vector<std::string> names = split_csv_line(header);
  const std::vector<std::string> cells = split_csv_line(row);
  const auto cell = [&](const std::string& name) -> std::string {
    for (std::size_t k = 0; k < names.size() && k < cells.size(); ++k)
      if (names[k] == name) return cells[k];
    return "0";
  };
  figures.trace_ms = std::stod(cell("trace_ms"));
  figures.write_ms = std::stod(cell("encode_ms")) + std::stod(cell("write_ms"));
  figures.hits = std::stoull(cell("hits"));
  return true;
}

bool ScratchOutput::move_image(const std::string& scene, const std::string& image_path,
                               std::string& error) const {
  // The config asks for one format, so the scene's folder holds one finished image (an image is
  // written under a temporary name and renamed, so nothing else is left after a success).
  std::error_code failed;
  for (const fs::directory_entry& entry :
       fs::directory_iterator(fs::path(directory_) / scene, failed)) {
    if (!entry.is_regular_file()) continue;
    fs::rename(entry.path(), image_path, failed);
    if (!failed) return true;
    break;
  }
  error = "cannot write '" + image_path + "'" + (failed ? ": " + failed.message() : "");
  return false;
}

}  // namespace tetray::tools
