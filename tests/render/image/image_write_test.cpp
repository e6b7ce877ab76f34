// EXR and PNG files read back with the libraries' own readers and compared with the framebuffer
// (EXR: half rounding, depth exact; PNG: the sRGB formula evaluated here independently), and
// failed writes that must leave no temporary file and no damaged image.
#include <Imath/half.h>
#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <tbb/task_arena.h>

#include <bit>
#include <cmath>
#include <csignal>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>

#include "render/image/image_write.hpp"
#include "support/png_read.hpp"
#include "support/scratch_dir.hpp"

namespace tetray::render {
namespace {

using testing::ScratchDir;

// Random premultiplied colors (color <= alpha, some brighter than 1 to exercise clamping),
// fully transparent background pixels with infinite depth, and a few edge values.
Framebuffer random_image(int width, int height, unsigned seed) {
  Framebuffer image(width, height);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (std::size_t p = 0; p < image.pixel_count(); ++p) {
    if (p % 5 == 0) continue;  // background
    const float alpha = p % 7 == 0 ? 1.0f : unit(rng);
    for (int c = 0; c < 3; ++c)
      image.rgba[4 * p + c] = alpha * unit(rng) * (p % 11 == 0 ? 1.5f : 1.0f);
    image.rgba[4 * p + 3] = alpha;
    image.depth[p] = 0.1f + 100.0f * unit(rng);
    image.hit[p] = static_cast<std::uint32_t>(p);
  }
  image.rgba[4] = image.rgba[5] = image.rgba[6] = image.rgba[7] = 1.0f;  // pixel 1: white
  image.rgba[8 + 3] = 1e-7f;                                             // pixel 2: faint
  image.depth[2] = 1e-30f;
  return image;
}

std::vector<char> file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::size_t entries_in(const std::filesystem::path& dir) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir), {}));
}

// ------------------------------------------------------------------------------------------ EXR

struct ExrChannels {
  int width = 0, height = 0;
  std::vector<float> r, g, b, a, z;
};

ExrChannels read_exr(const std::string& path, Imf::Header& header) {
  Imf::InputFile file(path.c_str());
  header = file.header();
  const Imath::Box2i window = file.header().dataWindow();
  ExrChannels out;
  out.width = window.max.x - window.min.x + 1;
  out.height = window.max.y - window.min.y + 1;
  const std::size_t pixels = static_cast<std::size_t>(out.width) * out.height;
  Imf::FrameBuffer slices;
  std::pair<const char*, std::vector<float>*> channels[] = {
      {"R", &out.r}, {"G", &out.g}, {"B", &out.b}, {"A", &out.a}, {"Z", &out.z}};
  for (auto& [name, values] : channels) {
    values->assign(pixels, -1.0f);
    slices.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values->data()),
                                   sizeof(float), sizeof(float) * out.width));
  }
  file.setFrameBuffer(slices);
  file.readPixels(window.min.y, window.max.y);
  return out;
}

// A half keeps 11 significant bits: relative error at most 2^-11 after rounding; below the
// smallest normal half (2^-14) the spacing is 2^-24, so absolute error at most 2^-25.
bool within_half_rounding(float original, float read) {
  const double tolerance =
      std::max(std::abs(double(original)) * std::ldexp(1.0, -11), std::ldexp(1.0, -25));
  return std::abs(double(read) - double(original)) <= tolerance;
}

TEST(ExrWrite, RoundTripKeepsEveryChannel) {
  ScratchDir dir;
  const Framebuffer image = random_image(37, 23, 1);
  const std::string path = dir / "image.exr";
  const WriteResult result = write_exr(image, path);
  ASSERT_TRUE(result.ok) << result.message;

  Imf::Header header;
  const ExrChannels read = read_exr(path, header);
  EXPECT_EQ(header.compression(), Imf::RLE_COMPRESSION);
  for (const char* name : {"R", "G", "B", "A"}) {
    ASSERT_NE(header.channels().findChannel(name), nullptr) << name;
    EXPECT_EQ(header.channels().findChannel(name)->type, Imf::HALF) << name;
  }
  ASSERT_NE(header.channels().findChannel("Z"), nullptr);
  EXPECT_EQ(header.channels().findChannel("Z")->type, Imf::FLOAT);
  ASSERT_EQ(read.width, image.width);
  ASSERT_EQ(read.height, image.height);

  const std::vector<float>* rgba[] = {&read.r, &read.g, &read.b, &read.a};
  for (std::size_t p = 0; p < image.pixel_count(); ++p) {
    for (int c = 0; c < 4; ++c) {
      ASSERT_TRUE(within_half_rounding(image.rgba[4 * p + c], (*rgba[c])[p]))
          << "pixel " << p << " channel " << c << ": " << image.rgba[4 * p + c] << " -> "
          << (*rgba[c])[p];
    }
    ASSERT_EQ(read.z[p], image.depth[p]) << "pixel " << p;  // exact, including +inf
  }
  EXPECT_TRUE(std::isinf(read.z[0]));
}

// Every compression of OpenEXR 3.1, read back with OpenEXR: the lossless ones keep every half
// and every depth exactly; the lossy ones keep what exr_compressions() says they keep.
TEST(ExrWrite, EveryCompressionKeepsWhatItPromises) {
  ScratchDir dir;
  const Framebuffer image = random_image(67, 45, 4);
  for (const ExrCompressionInfo& c : exr_compressions()) {
    SCOPED_TRACE(std::string(c.name));
    const std::string path = dir / (std::string(c.name) + ".exr");
    const WriteResult result = write_exr(image, path, c.compression);
    ASSERT_TRUE(result.ok) << result.message;
    Imf::Header header;
    const ExrChannels read = read_exr(path, header);
    EXPECT_EQ(static_cast<int>(header.compression()), static_cast<int>(c.compression));
    ASSERT_EQ(read.width, image.width);
    ASSERT_EQ(read.height, image.height);
    const bool rgba_exact = c.lossless || c.compression == ExrCompression::pxr24;
    const bool depth_exact = c.lossless || c.compression != ExrCompression::pxr24;
    std::size_t rgba_changed = 0, depth_changed = 0;
    const std::vector<float>* rgba[] = {&read.r, &read.g, &read.b, &read.a};
    for (std::size_t p = 0; p < image.pixel_count(); ++p) {
      for (int c4 = 0; c4 < 4; ++c4) {
        rgba_changed += !within_half_rounding(image.rgba[4 * p + c4], (*rgba[c4])[p]);
      }
      depth_changed += !(read.z[p] == image.depth[p]);
    }
    // A lossy one is lossy on random data: the test would notice a lossless one listed lossy.
    EXPECT_EQ(rgba_changed == 0, rgba_exact) << rgba_changed << " RGBA values changed";
    EXPECT_EQ(depth_changed == 0, depth_exact) << depth_changed << " depths changed";
  }
}

TEST(ExrWrite, CompressionNamesRoundTrip) {
  for (const ExrCompressionInfo& c : exr_compressions()) {
    EXPECT_EQ(exr_compression_named(c.name), c.compression);
    EXPECT_EQ(exr_compression_info(c.compression).name, c.name);
  }
  EXPECT_EQ(exr_compression_named("ZIP"), std::nullopt);
  EXPECT_EQ(exr_compression_named("deflate"), std::nullopt);
}

// What a rendered frame holds, for the line blocks tetray assembles (none, RLE, ZIPS, ZIP): rows
// of background, flat spans longer than one RLE code (128 bytes), short runs and noise, and the
// half's edges (smallest subnormal, a tie, the largest half, the first float that rounds to
// infinity, -0); 19 lines, so the last ZIP block is short.
Framebuffer rendered_like_image() {
  Framebuffer image = random_image(301, 19, 7);
  for (int y = 0; y < 5; ++y) {  // background rows
    for (int x = 0; x < image.width; ++x) {
      const std::size_t p = image.index(x, y);
      std::fill_n(&image.rgba[4 * p], 4, 0.0f);
      image.depth[p] = std::numeric_limits<float>::infinity();
    }
  }
  for (int x = 10; x < 250; ++x) {  // one flat span
    const std::size_t p = image.index(x, 8);
    image.rgba[4 * p + 0] = 0.25f, image.rgba[4 * p + 1] = 0.5f, image.rgba[4 * p + 2] = 0.125f;
    image.rgba[4 * p + 3] = 1.0f;
    image.depth[p] = 3.5f;
  }
  const float edges[] = {std::ldexp(1.0f, -24),
                         std::ldexp(3.0f, -25),
                         1.0f + std::ldexp(1.0f, -11),
                         65504.0f,
                         65520.0f,
                         -0.0f,
                         1e-9f,
                         70000.0f};
  for (std::size_t k = 0; k < std::size(edges); ++k) {
    image.rgba[4 * image.index(static_cast<int>(k), 12)] = edges[k];
  }
  return image;
}

// Read back with OpenEXR, every value is exactly Imath's half of the framebuffer's (RGBA) and
// the framebuffer's float (Z), for every compression tetray writes itself, on four threads.
TEST(ExrWrite, TetrayLineBlocksDecodeExactly) {
  ScratchDir dir;
  const Framebuffer image = rendered_like_image();
  for (ExrCompression compression :
       {ExrCompression::none, ExrCompression::rle, ExrCompression::zips, ExrCompression::zip}) {
    const std::string name(exr_compression_info(compression).name);
    SCOPED_TRACE(name);
    const std::string path = dir / (name + ".exr");
    WriteResult result;
    tbb::task_arena(4).execute([&] { result = write_exr(image, path, compression); });
    ASSERT_TRUE(result.ok) << result.message;
    Imf::Header header;
    const ExrChannels read = read_exr(path, header);
    EXPECT_EQ(static_cast<int>(header.compression()), static_cast<int>(compression));
    ASSERT_EQ(read.width, image.width);
    ASSERT_EQ(read.height, image.height);
    const std::vector<float>* rgba[] = {&read.r, &read.g, &read.b, &read.a};
    for (std::size_t p = 0; p < image.pixel_count(); ++p) {
      for (int c = 0; c < 4; ++c) {
        const float expected = Imath::half(image.rgba[4 * p + c]);
        ASSERT_EQ(std::bit_cast<std::uint32_t>((*rgba[c])[p]),
                  std::bit_cast<std::uint32_t>(expected))
            << "pixel " << p << " channel " << c << ": " << image.rgba[4 * p + c];
      }
      ASSERT_EQ(std::bit_cast<std::uint32_t>(read.z[p]),
                std::bit_cast<std::uint32_t>(image.depth[p]))
          << "pixel " << p;
    }
    if (compression != ExrCompression::none) {
      EXPECT_LT(std::filesystem::file_size(path), std::filesystem::file_size(dir / "none.exr"));
    }
  }
}

// Every float becomes the half Imath's half(float) gives (round to nearest even, overflow to
// infinity, subnormals, signs): midpoints between neighbouring halves (the ties), then random
// finite float bits of every exponent; rows of 257 pixels end in four floats, the tail that the
// conversion (eight at a time) handles apart.
TEST(ExrWrite, HalvesRoundAsImathRounds) {
  ScratchDir dir;
  Framebuffer image(257, 64);
  std::mt19937 rng(9);
  std::uniform_int_distribution<std::uint32_t> bits;
  for (std::size_t k = 0; k < image.rgba.size(); ++k) {
    float& v = image.rgba[k];
    if (k < 0x10000) {  // each half pattern's upper midpoint, in order
      Imath::half below;
      below.setBits(static_cast<std::uint16_t>(k));
      Imath::half above;
      above.setBits(static_cast<std::uint16_t>(k + 1));
      v = below.isFinite() && above.isFinite() && (k & 0x7fff) != 0x7fff
              ? (float(below) + float(above)) / 2
              : float(k);
      continue;
    }
    do v = std::bit_cast<float>(bits(rng));
    while (!std::isfinite(v));
  }
  const std::string path = dir / "halves.exr";
  ASSERT_TRUE(write_exr(image, path, ExrCompression::rle).ok);
  Imf::Header header;
  const ExrChannels read = read_exr(path, header);
  const std::vector<float>* rgba[] = {&read.r, &read.g, &read.b, &read.a};
  for (std::size_t p = 0; p < image.pixel_count(); ++p) {
    for (int c = 0; c < 4; ++c) {
      const float original = image.rgba[4 * p + c];
      ASSERT_EQ(std::bit_cast<std::uint32_t>((*rgba[c])[p]),
                std::bit_cast<std::uint32_t>(float(Imath::half(original))))
          << "value " << 4 * p + c << ": " << original;
    }
  }
}

// Lines that do not get smaller (random bits in every half and every depth, no NaN or infinity)
// are stored uncompressed, as OpenEXR's reader expects of such a block: the RLE and ZIPS files are
// the size of the uncompressed one.
TEST(ExrWrite, IncompressibleLinesAreStoredAsTheyAre) {
  ScratchDir dir;
  Framebuffer image(64, 20);
  std::mt19937 rng(8);
  std::uniform_int_distribution<std::uint32_t> bits;
  for (float& v : image.rgba) {
    Imath::half h;
    do h.setBits(static_cast<std::uint16_t>(bits(rng)));
    while (!h.isFinite());
    v = h;
  }
  for (float& v : image.depth) {
    do v = std::bit_cast<float>(bits(rng));
    while (!std::isfinite(v));
  }
  for (ExrCompression compression :
       {ExrCompression::none, ExrCompression::rle, ExrCompression::zips, ExrCompression::zip}) {
    const std::string name(exr_compression_info(compression).name);
    SCOPED_TRACE(name);
    const std::string path = dir / (name + ".exr");
    ASSERT_TRUE(write_exr(image, path, compression).ok);
    Imf::Header header;
    const ExrChannels read = read_exr(path, header);
    const std::vector<float>* rgba[] = {&read.r, &read.g, &read.b, &read.a};
    for (std::size_t p = 0; p < image.pixel_count(); ++p) {
      for (int c = 0; c < 4; ++c) ASSERT_EQ((*rgba[c])[p], image.rgba[4 * p + c]) << "pixel " << p;
      ASSERT_EQ(std::bit_cast<std::uint32_t>(read.z[p]),
                std::bit_cast<std::uint32_t>(image.depth[p]))
          << "pixel " << p;
    }
    // ZIP's 16-line blocks of these bytes (NaN and infinity left out) can shrink a little.
    const std::uintmax_t uncompressed = std::filesystem::file_size(dir / "none.exr");
    if (compression == ExrCompression::zip) {
      EXPECT_LE(std::filesystem::file_size(path), uncompressed);
    } else {
      EXPECT_EQ(std::filesystem::file_size(path), uncompressed);
    }
  }
}

// Both formats encoded at once, in an arena of several threads, give the same bytes as each
// encoded alone on one thread: the parallel loops change no pixel.
TEST(EncodeImages, TogetherAndInParallelTheSameBytes) {
  const Framebuffer image = random_image(301, 257, 5);
  const EncodeOptions options{.exr_compression = ExrCompression::rle, .png_compression = 4};
  EncodedImage exr, png;
  tbb::task_arena(1).execute([&] {
    exr = encode_exr(image, options.exr_compression);
    png = encode_png(image, options.png_compression);
  });
  EncodedImages both;
  tbb::task_arena(4).execute([&] { both = encode_images(image, true, true, options); });
  ASSERT_TRUE(both.exr.ok() && both.png.ok() && exr.ok() && png.ok());
  EXPECT_EQ(both.exr.bytes, exr.bytes);
  EXPECT_EQ(both.png.bytes, png.bytes);
  const EncodedImages png_only = encode_images(image, false, true, options);
  EXPECT_TRUE(png_only.exr.bytes.empty());
  EXPECT_EQ(png_only.png.bytes, png.bytes);
}

// ------------------------------------------------------------------------------------------ PNG

double srgb_encode(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

// The expected file content of one pixel: un-premultiply, clamp, sRGB, round; straight alpha.
std::array<int, 4> expected_png_pixel(const float* rgba) {
  const double alpha = std::clamp(double(rgba[3]), 0.0, 1.0);
  if (alpha <= 0.0) return {0, 0, 0, 0};
  std::array<int, 4> out{};
  for (int c = 0; c < 3; ++c) {
    const double straight = std::clamp(double(rgba[c]) / alpha, 0.0, 1.0);
    out[c] = static_cast<int>(std::lround(255.0 * srgb_encode(straight)));
  }
  out[3] = static_cast<int>(std::lround(255.0 * alpha));
  return out;
}

TEST(PngWrite, RoundTripMatchesTheSrgbFormula) {
  ScratchDir dir;
  const Framebuffer image = random_image(41, 29, 2);
  for (int level : {0, 1, 6, kMaxPngCompression}) {
    const std::string path = dir / ("image" + std::to_string(level) + ".png");
    const WriteResult result = write_png(image, path, level);
    ASSERT_TRUE(result.ok) << result.message;
    const testing::PngPixels read = testing::read_png_rgba8(path);
    ASSERT_TRUE(read.error.empty()) << read.error;
    EXPECT_TRUE(read.srgb);
    ASSERT_EQ(read.width, image.width);
    ASSERT_EQ(read.height, image.height);
    for (std::size_t p = 0; p < image.pixel_count(); ++p) {
      const std::array<int, 4> expected = expected_png_pixel(&image.rgba[4 * p]);
      for (int c = 0; c < 4; ++c) {
        ASSERT_EQ(read.rgba[4 * p + c], expected[c]) << "pixel " << p << " channel " << c;
      }
    }
    EXPECT_EQ(read.rgba[4 * 1 + 0], 255);  // the white pixel
    EXPECT_EQ(read.rgba[4 * 0 + 3], 0);    // background stays transparent
  }
}

// An image of many row blocks, converted and filtered by four threads: libpng decodes every
// pixel as the sRGB formula gives it.
TEST(PngWrite, ParallelRowsDecodeExactly) {
  ScratchDir dir;
  const Framebuffer image = random_image(203, 389, 6);
  const std::string path = dir / "rows.png";
  WriteResult result;
  tbb::task_arena(4).execute([&] { result = write_png(image, path, 1); });
  ASSERT_TRUE(result.ok) << result.message;
  const testing::PngPixels read = testing::read_png_rgba8(path);
  ASSERT_TRUE(read.error.empty()) << read.error;
  ASSERT_EQ(read.width, image.width);
  ASSERT_EQ(read.height, image.height);
  for (std::size_t p = 0; p < image.pixel_count(); ++p) {
    const std::array<int, 4> expected = expected_png_pixel(&image.rgba[4 * p]);
    for (int c = 0; c < 4; ++c) ASSERT_EQ(read.rgba[4 * p + c], expected[c]) << "pixel " << p;
  }
}

TEST(PngWrite, RejectsABadCompressionLevel) {
  ScratchDir dir;
  const WriteResult result = write_png(random_image(4, 4, 3), dir / "x.png", 13);
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.message.find("compression level 13"), std::string::npos) << result.message;
  EXPECT_EQ(entries_in(dir.path()), 0u);
}

// --------------------------------------------------------------------------------------- Errors

// Both formats, through the extension dispatch as the adaptor and tetray-render use them.
void expect_failed_write(const std::string& path, const std::string& cause) {
  for (const std::string extension : {".png", ".exr"}) {
    const WriteResult result = write_image(random_image(8, 8, 4), path + extension);
    EXPECT_FALSE(result.ok) << path + extension;
    EXPECT_NE(result.message.find(path + extension), std::string::npos) << result.message;
    EXPECT_NE(result.message.find(cause), std::string::npos) << result.message;
  }
}

TEST(ImageWriteErrors, MissingDirectory) {
  ScratchDir dir;
  expect_failed_write(dir / "no_such_dir/image", "No such file or directory");
  EXPECT_EQ(entries_in(dir.path()), 0u);
}

TEST(ImageWriteErrors, PathBelowARegularFile) {
  // Root ignores directory permissions, so a read-only directory would not fail here; a path
  // through a regular file fails for every user.
  ScratchDir dir;
  std::ofstream(dir / "plain_file") << "x";
  expect_failed_write(dir / "plain_file/image", "Not a directory");
  EXPECT_EQ(entries_in(dir.path()), 1u);
}

TEST(ImageWriteErrors, UnknownExtension) {
  ScratchDir dir;
  const WriteResult result = write_image(random_image(4, 4, 5), dir / "image.jpg");
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.message.find("image.jpg"), std::string::npos) << result.message;
}

TEST(ImageWriteErrors, BadFramebufferLeavesExistingFileUntouched) {
  ScratchDir dir;
  const std::string path = dir / "image.png";
  ASSERT_TRUE(write_png(random_image(16, 16, 6), path).ok);
  const std::vector<char> before = file_bytes(path);
  Framebuffer broken(16, 16);
  broken.rgba.resize(10);
  for (const WriteResult& result : {write_png(broken, path), write_png(Framebuffer(), path)}) {
    EXPECT_FALSE(result.ok);
    EXPECT_NE(result.message.find(path), std::string::npos) << result.message;
  }
  EXPECT_EQ(file_bytes(path), before);
  EXPECT_EQ(entries_in(dir.path()), 1u);
}

// A disk that fills up mid-write, simulated with the file size limit (write() then fails with
// EFBIG instead of killing the process, since SIGXFSZ is ignored): the earlier image survives
// byte for byte and the temporary file is gone.
TEST(ImageWriteErrors, FullDiskKeepsEarlierImage) {
  ScratchDir dir;
  const Framebuffer small = random_image(8, 8, 7);
  const Framebuffer large = random_image(256, 256, 8);
  for (const std::string name : {"image.png", "image.exr"}) {
    const std::string path = dir / name;
    ASSERT_TRUE(write_image(small, path).ok);
    const std::vector<char> before = file_bytes(path);
    ASSERT_LT(before.size(), 4096u);

    rlimit saved{};
    ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
    const auto previous_handler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limited = saved;
    limited.rlim_cur = 4096;
    ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &limited), 0);
    const WriteResult result = write_image(large, path);
    setrlimit(RLIMIT_FSIZE, &saved);
    std::signal(SIGXFSZ, previous_handler);

    EXPECT_FALSE(result.ok);
    EXPECT_NE(result.message.find(path), std::string::npos) << result.message;
    EXPECT_NE(result.message.find("File too large"), std::string::npos) << result.message;
    EXPECT_EQ(file_bytes(path), before);
  }
  EXPECT_EQ(entries_in(dir.path()), 2u);
}

// The same on a real full file system where one can be mounted (root on Linux).
TEST(ImageWriteErrors, FullTmpfsKeepsEarlierImage) {
  ScratchDir dir;
  const std::string mount_point = dir / "tiny";
  std::filesystem::create_directory(mount_point);
  if (::mount("tmpfs", mount_point.c_str(), "tmpfs", 0, "size=16k") != 0) {
    GTEST_SKIP() << "cannot mount a tmpfs here (not root)";
  }
  const std::string path = mount_point + "/image.png";
  const bool small_written = write_png(random_image(8, 8, 9), path).ok;
  const std::vector<char> before = file_bytes(path);
  const WriteResult result = write_png(random_image(256, 256, 10), path, 0);
  const std::vector<char> after = file_bytes(path);
  const std::size_t entries = entries_in(mount_point);
  ::umount(mount_point.c_str());

  EXPECT_TRUE(small_written);
  EXPECT_FALSE(before.empty());
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.message.find(path), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("No space left on device"), std::string::npos) << result.message;
  EXPECT_EQ(after, before);
  EXPECT_EQ(entries, 1u);
}

}  // namespace
}  // namespace tetray::render
