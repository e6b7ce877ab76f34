// Sort-last compositing of per-pixel fragment lists (render/core/fragments.hpp): every rank's
// fragments of every pixel are gathered on the root, which merges each pixel's layers in depth
// order with the one tie rule and the over operator. Volume runs of the walk and transparent
// surface hits (zero-length fragments) go through the same merge, so a scene of both composites
// in one pass. The gather moves every fragment once to the root, with each rank's counts over
// its run of covered pixels only; the root sorts only the pixels several ranks cover
// (docs/architecture.md §8 names the cost); an image-space split of the pixels (direct send) is
// the step beyond it.
#pragma once

#include <mpi.h>

#include "render/core/fragments.hpp"
#include "render/core/framebuffer.hpp"

namespace tetray::render {

struct FragmentCompositeStats {
  std::uint64_t fragments = 0;  // on the root, from all ranks
  std::uint64_t bytes_received = 0;
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

// Collective over `comm`: on `root`, `out` becomes the merged image of all ranks' fragments
// (the same size on every rank); elsewhere it is left alone. Returns MPI_SUCCESS or the MPI
// error code (MPI_ERR_COUNT when the gathered fragments would not fit one MPI count). `merged`,
// when given, holds the merged fragments: a caller that keeps it from frame to frame reuses its
// storage.
template <typename F>
int composite_fragments(const BasicFragmentImage<F>& local, MPI_Comm comm, int root,
                        Framebuffer& out, FragmentCompositeStats* stats = nullptr,
                        BasicFragmentImage<F>* merged = nullptr);

#define TETRAY_FRAGMENT_COMPOSITE(EXTERN, F)                                              \
  EXTERN template int gather_fragments<F>(const BasicFragmentImage<F>&, MPI_Comm, int,    \
                                          std::size_t, BasicFragmentImage<F>&,            \
                                          FragmentCompositeStats*);                       \
  EXTERN template int composite_fragments<F>(const BasicFragmentImage<F>&, MPI_Comm, int, \
                                             Framebuffer&, FragmentCompositeStats*,       \
                                             BasicFragmentImage<F>*);
TETRAY_FRAGMENT_COMPOSITE(extern, Fragment)
TETRAY_FRAGMENT_COMPOSITE(extern, VolumeFragment)

}  // namespace tetray::render
