#include "tools/vtk_io/xml_depth.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <iterator>
#include <string_view>

namespace tetray::vtkio {
namespace {

// Reads the XML markup character by character; only what the depth needs is understood:
// declarations, comments and CDATA are skipped, quoted attribute values may hold '>'.
class MarkupScanner {
 public:
  explicit MarkupScanner(std::istream& in) : in_(in) {}

  // The depth reached, or kMaxXmlDepth + 1 as soon as it is exceeded.
  int deepest() {
    int depth = 0, deepest = 0;
    while (skip_to('<')) {
      const int next = in_.peek();
      if (next == '?' || next == '!') {
        skip_special();
        continue;
      }
      if (next == '/') {
        skip_to('>');
        --depth;
        continue;
      }
      const Tag tag = read_tag();
      if (tag.self_closing) continue;
      deepest = std::max(deepest, ++depth);
      if (deepest > kMaxXmlDepth || tag.name == "AppendedData") break;
    }
    return deepest;
  }

 private:
  struct Tag {
    std::string name;
    bool self_closing = false;
  };

  bool skip_to(char wanted) {
    for (int c = in_.get(); c != EOF; c = in_.get()) {
      if (c == wanted) return true;
    }
    return false;
  }

  // After '<' of "<!-- -->", "<![CDATA[ ]]>", "<!DOCTYPE >" or "<? ?>".
  void skip_special() {
    std::string opening;
    for (int k = 0; k < 8 && in_.peek() != EOF; ++k) {
      opening += static_cast<char>(in_.get());
      if (opening == "!--" || opening == "![CDATA[") break;
    }
    const std::string_view end = opening == "!--" ? "-->" : opening == "![CDATA[" ? "]]>" : ">";
    if (opening.back() == '>' && end == ">") return;
    std::string tail;
    for (int c = in_.get(); c != EOF; c = in_.get()) {
      tail += static_cast<char>(c);
      if (tail.size() > end.size()) tail.erase(0, 1);
      if (tail == end) return;
    }
  }

  // After '<' of a start tag: its name, and whether it ends in "/>".
  Tag read_tag() {
    Tag tag;
    int c = in_.get();
    for (; c != EOF && c != '>' && c != '/' && !std::isspace(c); c = in_.get()) {
      tag.name += static_cast<char>(c);
    }
    char quote = 0, last = static_cast<char>(c);
    for (; c != EOF; c = in_.get()) {
      if (quote) {
        if (c == quote) quote = 0;
      } else if (c == '"' || c == '\'') {
        quote = static_cast<char>(c);
      } else if (c == '>') {
        break;
      }
      if (!std::isspace(c)) last = static_cast<char>(c);
    }
    tag.self_closing = last == '/';
    return tag;
  }

  std::istream& in_;
};

}  // namespace

std::string xml_depth_problem(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};  // the reader names a file it cannot open
  const int depth = MarkupScanner(in).deepest();
  if (depth <= kMaxXmlDepth) return {};
  return "XML elements nest deeper than " + std::to_string(kMaxXmlDepth) +
         " levels; this is no VTK file";
}

}  // namespace tetray::vtkio
