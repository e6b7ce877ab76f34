// Editing a file's text in tests that break one attribute of a valid file.
#pragma once

#include <string>

namespace tetray::testing {

// `text` with its first `from` replaced by `to`; unchanged when `from` does not occur.
inline std::string replaced_once(const std::string& text, const std::string& from,
                                 const std::string& to) {
  const std::size_t at = text.find(from);
  if (at == std::string::npos) return text;
  // Concatenated rather than std::string::replace, which GCC 12 warns of (-Wrestrict) when
  // inlined with a position it cannot bound.
  return text.substr(0, at) + to + text.substr(at + from.size());
}

}  // namespace tetray::testing
