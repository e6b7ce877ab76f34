// The YAML config parser on arbitrary text: every input must give either a config or an error
// message naming the source; nothing may throw, crash or allocate without bound.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "adaptor/config/config_parse.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view yaml(reinterpret_cast<const char*>(data), size);
  // Three ranks: output.writer_rank 0..2 is valid, 3 is not.
  const tetray::config::ParseResult result = tetray::config::parse_config(yaml, "fuzz.yaml", 3);
  if (result.config.has_value() == !result.error.empty()) std::abort();
  if (!result.config && result.error.rfind("fuzz.yaml", 0) != 0) std::abort();
  return 0;
}
