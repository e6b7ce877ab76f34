// Where the adaptor writes for tetray-render: a fresh folder beside the requested image (so the
// image is moved into place by a rename, atomically like every tetray image), removed with
// whatever is left in it when the run ends. The adaptor names its files after the scene and the
// step; the tool's user names one file, so the one image written is renamed to it, and the
// figures printed come from the adaptor's log row (README "Outputs": tetray_log.csv).
#pragma once

#include <cstdint>
#include <string>

namespace tetray::tools {

// What the log row of the one rendered step says.
struct StepFigures {
  double trace_ms = 0;
  double write_ms = 0;  // encoding and writing the image
  std::uint64_t hits = 0;
};

class ScratchOutput {
 public:
  ScratchOutput() = default;
  ~ScratchOutput();
  ScratchOutput(const ScratchOutput&) = delete;
  ScratchOutput& operator=(const ScratchOutput&) = delete;

  // Creates the folder beside `image_path`; false with `error` when it cannot.
  bool create(const std::string& image_path, std::string& error);
  const std::string& directory() const { return directory_; }

  // The figures of the log's one row; false with `error` when the log holds none.
  bool read_figures(StepFigures& figures, std::string& error) const;

  // Renames the scene's one image to `image_path` (whatever the case of its extension).
  bool move_image(const std::string& scene, const std::string& image_path,
                  std::string& error) const;

 private:
  std::string directory_;
};

}  // namespace tetray::tools
