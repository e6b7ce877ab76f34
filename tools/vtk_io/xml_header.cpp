#include "tools/vtk_io/xml_header.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

namespace tetray::vtkio {
namespace {

struct Tag {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;
  bool self_closing = false;
};

// Reads the XML markup character by character; only what the checks need is understood:
// declarations, comments and CDATA are skipped, quoted attribute values may hold '>'.
class MarkupScanner {
 public:
  explicit MarkupScanner(std::istream& in) : in_(in) {}

  // The next start tag, and the nesting depth below it; nothing at the end of the markup.
  std::optional<Tag> next_start_tag(int& depth) {
    while (skip_to('<')) {
      const int next = in_.peek();
      if (next == '?' || next == '!') {
        skip_special();
      } else if (next == '/') {
        skip_to('>');
        --depth;
      } else {
        Tag tag = read_tag();
        if (!tag.self_closing) ++depth;
        return tag;
      }
    }
    return std::nullopt;
  }

 private:
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

  // After '<' of a start tag: its name, its attributes, and whether it ends in "/>".
  Tag read_tag() {
    Tag tag;
    int c = in_.get();
    for (; c != EOF && c != '>' && c != '/' && !std::isspace(c); c = in_.get()) {
      tag.name += static_cast<char>(c);
    }
    std::string word;
    char quote = 0, last = static_cast<char>(c);
    for (; c != EOF; c = in_.get()) {
      if (quote) {
        if (c == quote) {
          quote = 0;
        } else {
          tag.attributes.back().second += static_cast<char>(c);
        }
      } else if (c == '"' || c == '\'') {
        quote = static_cast<char>(c);
        tag.attributes.emplace_back(std::exchange(word, {}), "");
      } else if (c == '>') {
        break;
      } else if (!std::isspace(c) && c != '=' && c != '/') {
        word += static_cast<char>(c);
      }
      if (!std::isspace(c)) last = static_cast<char>(c);
    }
    tag.self_closing = last == '/';
    return tag;
  }

  std::istream& in_;
};

// The attributes that size what VTK allocates for an element.
constexpr std::array<std::string_view, 7> kCountAttributes = {
    "NumberOfPoints", "NumberOfCells",  "NumberOfTuples", "NumberOfVerts",
    "NumberOfLines",  "NumberOfStrips", "NumberOfPolys"};

bool is_count_attribute(std::string_view name) {
  return std::find(kCountAttributes.begin(), kCountAttributes.end(), name) !=
         kCountAttributes.end();
}

// The integer an attribute value starts with, as VTK reads it (leading blanks skipped); a number
// beyond 64 bits counts as the largest (or, negative, the smallest). Nothing when it starts with
// no digit: VTK reports that.
std::optional<std::int64_t> leading_integer(std::string_view text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) {
    text.remove_prefix(1);
  }
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  std::int64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error == std::errc::result_out_of_range) return text.front() == '-' ? INT64_MIN : INT64_MAX;
  if (error != std::errc()) return std::nullopt;
  return value;
}

// Integer attributes that VTK reads as an offset into the file or a level: never negative.
constexpr std::array<std::string_view, 3> kNonNegativeAttributes = {"offset", "GhostLevel",
                                                                    "TimeStep"};

// Every NumberOf... attribute is a count (points, cells, pieces, components, tuples, ...).
bool is_count_like(std::string_view name) {
  return name.starts_with("NumberOf") ||
         std::find(kNonNegativeAttributes.begin(), kNonNegativeAttributes.end(), name) !=
             kNonNegativeAttributes.end();
}

// What is wrong with one size attribute of a tag, or nothing. A negative count is refused
// before VTK sees it: VTK 9.1's vtkXMLUnstructuredGridReader sizes a memset by
// NumberOfCells="-5" and takes the process down.
std::string size_problem(const Tag& tag, const std::string& name, const std::string& value,
                         std::int64_t most_values, std::int64_t file_bytes) {
  const std::optional<std::int64_t> number = leading_integer(value);
  if (!number) return {};
  const std::string declares = "<" + tag.name + "> declares " + name + "=\"" + value + "\"";
  if (is_count_like(name) && *number < 0) return declares + ", a negative number";
  if (name == "NumberOfComponents" && *number > kMaxComponents) {
    return declares + ", more than " + std::to_string(kMaxComponents);
  }
  if (is_count_attribute(name) && *number > most_values) {
    return declares + ", more values than the file's bytes can hold (at most " +
           std::to_string(most_values) + ")";
  }
  if (name == "offset" && *number > file_bytes) {
    return declares + ", beyond the end of the file's " + std::to_string(file_bytes) + " bytes";
  }
  return {};
}

// The value of a tag's attribute, or nothing.
std::optional<std::string> attribute(const Tag& tag, std::string_view name) {
  for (const auto& [key, value] : tag.attributes) {
    if (key == name) return value;
  }
  return std::nullopt;
}

// Where a <Points> element is open: its level, so that a tag below it is known to be inside.
class PointsScope {
 public:
  // `tag` was just read with the scanner's depth now `depth`.
  void enter(const Tag& tag, int depth) {
    const int parent = tag.self_closing ? depth : depth - 1;
    if (parent < level_) level_ = kNone;  // the <Points> element has closed
    inside_ = level_ != kNone && parent >= level_;
    if (tag.name == "Points" && !tag.self_closing) level_ = depth;
  }
  bool inside() const { return inside_; }

 private:
  static constexpr int kNone = 1 << 30;
  int level_ = kNone;
  bool inside_ = false;
};

// Point coordinates of other than 3 components: vtkPoints refuses the array, VTK 9.1's reader then
// reads the file's values into the points' default array and abandons an iterator on it
// (vtkXMLReader::ReadArrayValues), a leak; refused here first.
std::string points_problem(const Tag& tag) {
  const std::string components = attribute(tag, "NumberOfComponents").value_or("1");
  if (tag.name != "DataArray" || leading_integer(components) == std::optional<std::int64_t>(3)) {
    return {};
  }
  return "the point coordinates (<Points><DataArray>) have NumberOfComponents=\"" + components +
         "\", not 3";
}

std::string header_problem(MarkupScanner& scanner, std::int64_t file_bytes) {
  std::int64_t most_values = file_bytes;
  int depth = 0;
  PointsScope points;
  while (std::optional<Tag> tag = scanner.next_start_tag(depth)) {
    if (depth > kMaxXmlDepth) {
      return "XML elements nest deeper than " + std::to_string(kMaxXmlDepth) +
             " levels; this is no VTK file";
    }
    points.enter(*tag, depth);
    for (const auto& [name, value] : tag->attributes) {
      if (name == "compressor" && !value.empty()) {
        most_values = file_bytes * kMaxValuesPerCompressedByte;
      }
      if (std::string problem = size_problem(*tag, name, value, most_values, file_bytes);
          !problem.empty()) {
        return problem;
      }
    }
    if (points.inside()) {
      if (std::string problem = points_problem(*tag); !problem.empty()) return problem;
    }
    if (tag->name == "AppendedData") break;
  }
  return {};
}

}  // namespace

std::string xml_header_problem(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  if (!in || ec) return {};  // the reader names a file it cannot open
  MarkupScanner scanner(in);
  return header_problem(scanner, static_cast<std::int64_t>(bytes));
}

}  // namespace tetray::vtkio
