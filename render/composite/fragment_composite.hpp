// Sort-last compositing of per-pixel fragment lists (render/core/fragments.hpp): every pixel's
// fragments of all ranks merged in depth order with the one tie rule and the over operator.
// Volume runs of the walk and transparent surface hits (zero-length fragments) go through the
// same merge, so a scene of both composites in one pass.
//
// composite_fragments splits the image (direct send, image-space): each rank owns a stripe of
// consecutive pixels, receives every other rank's fragments of its stripe (each rank's counts
// over its run of covered pixels only, sent from where they lie), merges and blends them, and
// the blended stripes go to the root. The merge's work and the fragments' bytes are spread over
// the ranks instead of all arriving at the root; the root receives only flat pixels.
// gather_fragments brings every fragment to the root instead, for a caller that needs the
// merged layers themselves there (the shadows of transparent layers).
#pragma once

#include <mpi.h>

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "render/core/fragments.hpp"
#include "render/core/framebuffer.hpp"
#include "render/core/large_array.hpp"

namespace tetray::render {

struct FragmentCompositeStats {
  std::uint64_t fragments = 0;   // merged by this rank: its stripe's (the root's: all) of all ranks
  std::uint64_t bytes_sent = 0;  // by this rank
  std::uint64_t bytes_received = 0;  // by this rank
};

// Collective over `comm`: on `root`, `merged` becomes every pixel's kept fragments of all ranks
// together (kept_layers: front to back, up to the first opaque one, at most max_layers);
// elsewhere it is left alone. Returns MPI_SUCCESS or the MPI error code (MPI_ERR_COUNT when the
// gathered fragments would not fit one MPI count).
// For surface hits (FragmentImage) and volume runs (VolumeFragmentImage).
template <typename F>
int gather_fragments(const BasicFragmentImage<F>& local, MPI_Comm comm, int root,
                     std::size_t max_layers, BasicFragmentImage<F>& merged,
                     FragmentCompositeStats* stats = nullptr);

struct FragmentCompositeOptions {
  // The most layers a pixel keeps (kept_layers): the nearest of all ranks' together.
  std::size_t max_layers = kAllLayers;
  // Called on each rank with its stripe's depths (each pixel's nearest kept fragment's
  // depth_in, +infinity where it has none) before they go to the root, `first` being the
  // stripe's first pixel: turns, say, distances along the rays into view depths where the work
  // is spread over the ranks. Unset: the depths stay as the fragments hold them.
  std::function<void(std::size_t first, std::span<float> depth)> stripe_depths;
};

// What a caller that composites every frame keeps between calls: the stripe's incoming
// fragments and offsets per sending rank and the stripe's blended pixels, whose pages fresh
// allocations would fault in again each frame. Grown, never shrunk; on huge pages where the
// system grants them (on 4 KiB pages a megapixel stripe took 1.8 times as long to blend).
template <typename F>
struct FragmentWorkspace {
  std::vector<LargeArray<std::uint32_t>> offsets;  // per sending rank
  std::vector<LargeArray<F>> fragments;            // per sending rank
  LargeArray<float> rgba, depth;                   // the stripe (ranks but the root)
  LargeArray<std::uint32_t> hit;
};

// Collective over `comm`: on `root`, `out` becomes the merged image of all ranks' fragments
// (the same size on every rank; its storage is reused when it has that size); elsewhere it is
// left alone. Returns the same on every rank: MPI_SUCCESS, MPI_ERR_ROOT when a rank names a
// root out of range or another than the others, MPI_ERR_SIZE when the ranks' images differ in
// size or are malformed, MPI_ERR_NO_MEM when a rank could not allocate its buffers or ran out of
// memory blending its stripe, MPI_ERR_COUNT when one rank's fragments of one stripe would not
// fit one MPI count, MPI_ERR_OTHER when options.stripe_depths threw on a rank, or the MPI error
// code. After an error `out` holds no image to use (on the root it may be partly blended).
template <typename F>
int composite_fragments(const BasicFragmentImage<F>& local, MPI_Comm comm, int root,
                        Framebuffer& out, const FragmentCompositeOptions& options = {},
                        FragmentCompositeStats* stats = nullptr,
                        FragmentWorkspace<F>* workspace = nullptr);

// Instantiated in fragment_composite.cpp and fragment_stripes.cpp for these two.
#define TETRAY_EXTERN_FRAGMENT_COMPOSITE(F)                                                 \
  extern template int gather_fragments<F>(const BasicFragmentImage<F>&, MPI_Comm, int,      \
                                          std::size_t, BasicFragmentImage<F>&,              \
                                          FragmentCompositeStats*);                         \
  extern template int composite_fragments<F>(const BasicFragmentImage<F>&, MPI_Comm, int,   \
                                             Framebuffer&, const FragmentCompositeOptions&, \
                                             FragmentCompositeStats*, FragmentWorkspace<F>*);
TETRAY_EXTERN_FRAGMENT_COMPOSITE(Fragment)
TETRAY_EXTERN_FRAGMENT_COMPOSITE(VolumeFragment)

}  // namespace tetray::render
