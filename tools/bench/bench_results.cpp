#include "bench_results.hpp"

#include <algorithm>
#include <stdexcept>

namespace tetray::bench {

const PacketFigures& SceneFigures::packet(render::PacketSize size) const {
  const auto it = std::find_if(tetray.packets.begin(), tetray.packets.end(),
                               [size](const PacketFigures& p) { return p.packet == size; });
  if (it == tetray.packets.end()) throw std::logic_error("packet size not measured");
  return *it;
}

}  // namespace tetray::bench
