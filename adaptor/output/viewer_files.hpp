// The viewer of the output directory (adaptor/output/viewer/index.html): `<dir>/index.html`, which
// browses every scene's Cinema table, and beside each table `<scene>.cdb/data.js`, the table's
// text wrapped in a script call. A page opened from file:// may load scripts and images but not
// read other files, so the table reaches it as a script. Both are written atomically; data.js is
// rewritten whenever its table changes, so a killed run leaves a viewer of what it had listed.
#pragma once

#include <string>
#include <vector>

namespace tetray {

extern const char* const kViewerPage;  // generated from adaptor/output/viewer/index.html

std::string viewer_page_path(const std::string& directory);
std::string cinema_script_path(const std::string& directory, const std::string& scene);

// The page for these scenes, written to viewer_page_path (by the writer with the run's first
// image).
std::string write_viewer_page(const std::string& directory, const std::vector<std::string>& scenes);

// data.js of the scene from its data.csv as it is now on disk.
std::string write_cinema_script(const std::string& directory, const std::string& scene);

// Text as a JavaScript string literal in double quotes; '<' escaped so that no "</script>"
// can end the script early.
std::string js_string(const std::string& text);

}  // namespace tetray
