#include "render/composite/composite.hpp"

#include "render/composite/compositor.hpp"

namespace tetray::render {
namespace {

bool well_formed(const Framebuffer& image) {
  const auto pixels = static_cast<std::int64_t>(image.width) * image.height;
  return image.width >= 0 && image.height >= 0 && pixels < (std::int64_t{1} << 31) &&
         image.depth.size() == static_cast<std::size_t>(pixels) &&
         image.hit.size() == image.depth.size() && image.rgba.size() == 4 * image.depth.size();
}

}  // namespace

int composite(Framebuffer& image, MPI_Comm comm, const CompositeOptions& options,
              CompositeStats* stats, CompositeWorkspace* workspace) {
  CompositeStats local_stats;
  CompositeWorkspace local_workspace;
  return composite_image(image, well_formed(image), comm, options, stats ? *stats : local_stats,
                         workspace ? *workspace : local_workspace);
}

}  // namespace tetray::render
