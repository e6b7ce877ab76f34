// A libdeflate compressor that frees itself, shared by the PNG encoder and the EXR line blocks
// (both compress zlib streams with libdeflate).
#pragma once

#include <libdeflate.h>

#include <memory>
#include <new>

namespace tetray::render {

struct DeflateCompressorDeleter {
  void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};
using DeflateCompressor = std::unique_ptr<libdeflate_compressor, DeflateCompressorDeleter>;

// A compressor at `level` (libdeflate's 0..12); std::bad_alloc where libdeflate has no memory.
inline DeflateCompressor make_deflate_compressor(int level) {
  DeflateCompressor compressor(libdeflate_alloc_compressor(level));
  if (!compressor) throw std::bad_alloc();
  return compressor;
}

}  // namespace tetray::render
