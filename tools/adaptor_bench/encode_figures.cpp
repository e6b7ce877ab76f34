#include "tools/adaptor_bench/encode_figures.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <exception>
#include <filesystem>
#include <functional>
#include <limits>

#include "render/core/stopwatch.hpp"
#include "render/image/image_write.hpp"
#include "render/image/movie_writer.hpp"

namespace tetray::bench {
namespace {

// The best of `runs` timings of `work`, which returns the bytes it produced.
std::pair<double, std::size_t> best_of(int runs, const std::function<std::size_t()>& work) {
  double best = std::numeric_limits<double>::infinity();
  std::size_t bytes = 0;
  for (int k = 0; k < runs; ++k) {
    const render::Stopwatch watch;
    bytes = work();
    best = std::min(best, watch.ms());
  }
  return {best, bytes};
}

EncodeFigure movie_figure(const render::Framebuffer& image, int runs,
                          const std::string& scratch_dir) {
  const render::MovieOptions options;
  EncodeFigure figure{"mp4",
                      render::movie_codec_name() + " quality " + std::to_string(options.quality),
                      false, "lossy: video, 4:2:0 chroma, no alpha, no depth"};
  std::string error;
  auto movie = render::MovieWriter::create(scratch_dir + "/encode_figures.mp4", image.width,
                                           image.height, options, error);
  if (!movie) {
    figure.note = error;
    return figure;
  }
  // The first frame is a key frame; the later ones, which the movie mostly holds, are not.
  movie->append(image);
  figure.ms = best_of(runs, [&] { return movie->append(image).ok ? std::size_t{1} : 0; }).first;
  movie->close();
  std::error_code ec;
  figure.bytes = std::filesystem::file_size(movie->path(), ec) / (runs + 1);
  return figure;
}

}  // namespace

std::optional<render::Framebuffer> read_exr_image(const std::string& path, std::string& error) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    render::Framebuffer image(window.max.x - window.min.x + 1, window.max.y - window.min.y + 1);
    const std::size_t row = sizeof(float) * static_cast<std::size_t>(image.width);
    Imf::FrameBuffer slices;
    const char* names[] = {"R", "G", "B", "A"};
    for (int c = 0; c < 4; ++c) {
      slices.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(&image.rgba[c]),
                                         4 * sizeof(float), 4 * row));
    }
    slices.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(image.depth.data()),
                                  sizeof(float), row));
    file.setFrameBuffer(slices);
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const std::exception& e) {
    error = "cannot read '" + path + "': " + e.what();
    return std::nullopt;
  }
}

std::vector<EncodeFigure> encode_figures(const render::Framebuffer& image,
                                         const std::vector<int>& png_levels, int runs,
                                         const std::string& scratch_dir) {
  tbb::task_arena one_thread(1);
  std::vector<EncodeFigure> figures;
  one_thread.execute([&] {
    for (int level : png_levels) {
      EncodeFigure f{"png", "level " + std::to_string(level), true, ""};
      std::tie(f.ms, f.bytes) =
          best_of(runs, [&] { return render::encode_png(image, level).bytes.size(); });
      figures.push_back(f);
    }
    for (const render::ExrCompressionInfo& c : render::exr_compressions()) {
      EncodeFigure f{"exr", std::string(c.name), c.lossless, c.lossless ? "" : std::string(c.what)};
      std::tie(f.ms, f.bytes) =
          best_of(runs, [&] { return render::encode_exr(image, c.compression).bytes.size(); });
      figures.push_back(f);
    }
    figures.push_back(movie_figure(image, runs, scratch_dir));
  });
  return figures;
}

}  // namespace tetray::bench
