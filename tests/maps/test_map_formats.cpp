// Valid image variants read to the stored sample values: ASCII and 16-bit PGM, PPM, PNG with
// alpha, palettes and a gAMA chunk (map_server does no colour management, so neither do we).
#include <gtest/gtest.h>
#include <png.h>
#include <zlib.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "mote/maps/map_loader.hpp"

namespace mote {
namespace {

namespace fs = std::filesystem;
using namespace std::string_literals;
using Samples = std::vector<std::uint16_t>;

class MapFormats : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("mote_map_formats_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  MapImage read(const std::string& bytes) {
    std::ofstream(dir_ / "img", std::ios::binary) << bytes;
    return read_map_image(dir_ / "img");
  }
  fs::path dir_;
};

std::string chunk(const std::string& type, const std::string& body) {
  std::string out;
  for (const std::uint32_t v : {static_cast<std::uint32_t>(body.size())}) {
    for (int k = 3; k >= 0; --k) out += static_cast<char>(v >> (8 * k));
  }
  const std::string tb = type + body;
  const auto crc = static_cast<std::uint32_t>(
      crc32(0, reinterpret_cast<const Bytef*>(tb.data()), static_cast<uInt>(tb.size())));
  out += tb;
  for (int k = 3; k >= 0; --k) out += static_cast<char>(crc >> (8 * k));
  return out;
}

/// An 8-bit gray 3 x 1 PNG, filter 0, with an optional extra chunk before IDAT.
std::string gray_png(const std::string& extra) {
  const std::string raw = "\x00\x00\x32\xcd"s;  // filter byte, then 0, 50, 205
  std::string z(compressBound(raw.size()), '\0');
  uLongf zsize = z.size();
  compress(reinterpret_cast<Bytef*>(z.data()), &zsize, reinterpret_cast<const Bytef*>(raw.data()),
           raw.size());
  z.resize(zsize);
  const std::string ihdr = "\x00\x00\x00\x03\x00\x00\x00\x01\x08\x00\x00\x00\x00"s;
  return "\x89PNG\r\n\x1a\n"s + chunk("IHDR", ihdr) + extra + chunk("IDAT", z) + chunk("IEND", "");
}

TEST_F(MapFormats, AsciiPgmWithComments) {
  const MapImage img = read("P2\n# a comment\n3 2 # inline\n15\n0 7 15\n 1 2\n3\n");
  EXPECT_EQ(img.width, 3);
  EXPECT_EQ(img.maxval, 15U);
  EXPECT_EQ(img.samples, (Samples{0, 7, 15, 1, 2, 3}));
}

TEST_F(MapFormats, SixteenBitPgmIsBigEndian) {
  const MapImage img = read("P5 2 1 65535\n\x01\x02\xff\xfe"s);
  EXPECT_EQ(img.maxval, 65535U);
  EXPECT_EQ(img.samples, (Samples{0x0102, 0xfffe}));
}

TEST_F(MapFormats, PpmGivesThreeChannels) {
  const MapImage img = read("P6\n1 2\n255\n\x01\x02\x03\x04\x05\x06"s);
  EXPECT_EQ(img.channels, 3);
  EXPECT_EQ(img.samples, (Samples{1, 2, 3, 4, 5, 6}));
}

TEST_F(MapFormats, PngGammaChunkDoesNotChangeSamples) {
  EXPECT_EQ(read(gray_png("")).samples, (Samples{0, 50, 205}));
  const std::string gamma_1 = chunk("gAMA", "\x00\x01\x86\xa0"s);  // gamma 1.0
  EXPECT_EQ(read(gray_png(gamma_1)).samples, (Samples{0, 50, 205}));
}

std::string write_png(std::uint32_t format, const std::vector<unsigned char>& pixels,
                      const std::vector<unsigned char>& colormap = {}) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = 2;
  image.height = 1;
  image.format = format;
  image.colormap_entries = static_cast<png_uint_32>(colormap.size() / 3);
  png_alloc_size_t size = 0;
  const void* cmap = colormap.empty() ? nullptr : colormap.data();
  png_image_write_get_memory_size(image, size, 0, pixels.data(), 0, cmap);
  std::string bytes(size, '\0');
  png_image_write_to_memory(&image, bytes.data(), &size, 0, pixels.data(), 0, cmap);
  bytes.resize(size);
  return bytes;
}

TEST_F(MapFormats, PngChannelsAndPalettes) {
  const MapImage ga = read(write_png(PNG_FORMAT_GA, {10, 255, 20, 0}));
  EXPECT_EQ(ga.channels, 2);
  EXPECT_EQ(ga.samples, (Samples{10, 255, 20, 0}));
  const MapImage rgba = read(write_png(PNG_FORMAT_RGBA, {1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(rgba.channels, 4);
  EXPECT_EQ(rgba.samples, (Samples{1, 2, 3, 4, 5, 6, 7, 8}));
  const MapImage pal = read(write_png(PNG_FORMAT_RGB_COLORMAP, {1, 0}, {9, 9, 9, 200, 100, 50}));
  EXPECT_EQ(pal.channels, 3);
  EXPECT_EQ(pal.samples, (Samples{200, 100, 50, 9, 9, 9}));
}

}  // namespace
}  // namespace mote
