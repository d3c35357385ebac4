// Malformed map_server inputs, generated in a temporary folder: each must throw InputError whose
// message names the file and says what is wrong.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <png.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/maps/map_loader.hpp"

namespace mote {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using namespace std::string_literals;

class MapErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("mote_map_errors_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(dir_);
    write("ok.pgm", "P5\n2 2\n255\n\x00\xff\xcd\xff"s);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& bytes) {
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
    return dir_ / name;
  }
  /// A YAML file with the usual keys; `replace` swaps one whole line (by key) or adds it.
  fs::path yaml(const std::string& key, const std::string& line) {
    std::string text;
    for (const std::string l : {"image: ok.pgm", "resolution: 0.05", "origin: [1.0, 2.0, 0.0]",
                                "negate: 0", "occupied_thresh: 0.65", "free_thresh: 0.196"}) {
      text += l.rfind(key + ":", 0) == 0 ? line : l;
      text += "\n";
    }
    if (text.find(line) == std::string::npos) text += line + "\n";
    return write("map.yaml", text);
  }
  /// Expects load_map(file) to throw an InputError naming `named` and containing `problem`.
  static void expect_error(const fs::path& file, const fs::path& named,
                           const std::string& problem) {
    try {
      (void)load_map(file);
      ADD_FAILURE() << "no error for " << problem;
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(named.string()));
      EXPECT_THAT(e.what(), HasSubstr(problem));
    }
  }
  fs::path dir_;
};

TEST_F(MapErrors, ValidFilesLoad) {
  const OccupancyGrid grid = load_map(yaml("mode", "mode: trinary"));
  EXPECT_EQ(grid.at({0, 1}), CellState::kOccupied);  // top-left pixel 0 is the top row
  EXPECT_EQ(grid.at({1, 1}), CellState::kFree);
  EXPECT_EQ(grid.at({0, 0}), CellState::kUnknown);
}

TEST_F(MapErrors, YamlKeys) {
  const fs::path f = dir_ / "map.yaml";
  expect_error(yaml("resolution", "# no resolution"), f, "key 'resolution': missing required key");
  expect_error(yaml("image", "# no image"), f, "key 'image': missing");
  expect_error(yaml("resolution", "resolution: 0"), f, "resolution must be positive");
  expect_error(yaml("resolution", "resolution: -0.05"), f, "line 2, key 'resolution'");
  expect_error(yaml("resolution", "resolution: fast"), f, "expected a finite number, got 'fast'");
  expect_error(yaml("occupied_thresh", "occupied_thresh: 1.5"), f, "threshold outside [0, 1]");
  expect_error(yaml("free_thresh", "free_thresh: -0.1"), f, "threshold outside [0, 1]");
  expect_error(yaml("free_thresh", "free_thresh: 0.7"), f, "free_thresh must be below");
  expect_error(yaml("mode", "mode: fuzzy"), f, "unknown mode 'fuzzy'");
  expect_error(yaml("origin", "origin: [1.0, 2.0]"), f, "expected a list [x, y, yaw]");
  expect_error(yaml("origin", "origin: [1.0, north, 0]"), f, "got 'north'");
  expect_error(yaml("negate", "negate: 2"), f, "expected 0 or 1");
  expect_error(write("map.yaml", "image: [ok.pgm\nresolution: 0.05\n"), f, "invalid YAML");
  expect_error(dir_ / "absent.yaml", dir_ / "absent.yaml", "cannot open map YAML file");
  expect_error(yaml("resolution", "resolution: [0.05]"), f,
               "key 'resolution': expected a single value");
  expect_error(write("map.yaml", "just some text\n"), f, "line 1: expected a YAML mapping");
}

TEST_F(MapErrors, ImageFiles) {
  const fs::path y = yaml("image", "image: map.pgm");
  const fs::path img = dir_ / "map.pgm";
  expect_error(y, img, "cannot open map image");
  // Issue 48: a wrong `image:` is the YAML's mistake, so the error names the YAML and the key.
  expect_error(y, y,
               "map.yaml: key 'image': cannot open map image " + img.string() +
                   " (no such file; a relative path is taken from the YAML file's folder)");
  fs::create_directories(dir_ / "folder.pgm");
  expect_error(
      yaml("image", "image: folder.pgm"), y,
      "key 'image': cannot open map image " + (dir_ / "folder.pgm").string() + " (not a file;");
  (void)yaml("image", "image: map.pgm");
  write("map.pgm", "GIF89a");
  expect_error(y, img, "byte 0: unknown image format");
  write("map.pgm", "P7\n2 2\n255\n");
  expect_error(y, img, "byte 0: not a PGM/PPM file");
  write("map.pgm", "P5\n# comment\ntwo 2\n255\n");
  expect_error(y, img, "byte 13: expected width, found 't'");
  write("map.pgm", "P5\n2 2\n");
  expect_error(y, img, "truncated: expected maxval");
  write("map.pgm", "P5\n2 2\n70000\n");
  expect_error(y, img, "maxval exceeds 65535");
  write("map.pgm", "P5\n2 2\n255\n\x01\x02\x03");
  expect_error(y, img, "byte 14: truncated pixel data: expected 4 bytes, found 3");
  write("map.pgm", "P5\n2 2\n65535\n\x01\x02\x03\x04\x05\x06\x07");
  expect_error(y, img, "truncated pixel data: expected 8 bytes");
  write("map.pgm", "P2\n2 2\n100\n0 50 101 7\n");
  expect_error(y, img, "byte 16: a sample exceeds 100");
  write("map.pgm", "P2\n2 2\n100\n0 50\n");
  expect_error(y, img, "truncated pixel data: 4 samples cannot fit");
}

TEST_F(MapErrors, HugePgmHeaderIsRefusedBeforeAllocating) {
  // 10^9 pixels claimed by a 30-byte file: the size check must come before any allocation
  // (a 2 GB buffer of uint16 samples would otherwise be attempted).
  const fs::path y = yaml("image", "image: map.pgm");
  write("map.pgm", "P5\n40000 25000\n255\n\x00\x00"s);
  expect_error(y, dir_ / "map.pgm", "truncated pixel data: expected 1000000000 bytes, found 2");
}

std::string small_png() {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = 4;
  image.height = 3;
  image.format = PNG_FORMAT_GRAY;
  const std::vector<unsigned char> pixels(12, 200);
  png_alloc_size_t size = 0;
  png_image_write_get_memory_size(image, size, 0, pixels.data(), 0, nullptr);
  std::string bytes(size, '\0');
  png_image_write_to_memory(&image, bytes.data(), &size, 0, pixels.data(), 0, nullptr);
  bytes.resize(size);
  return bytes;
}

TEST_F(MapErrors, PngFiles) {
  const fs::path y = yaml("image", "image: map.png");
  const fs::path img = dir_ / "map.png";
  const std::string png = small_png();
  write("map.png", png);
  EXPECT_EQ(load_map(y).width(), 4);
  write("map.png", png.substr(0, png.size() - 20));
  expect_error(y, img, "cannot decode PNG");
  write("map.png", png.substr(0, 20));
  expect_error(y, img, "cannot read PNG");
  // Patch IHDR to claim 60000 x 60000 pixels, with a correct CRC so libpng accepts the header.
  std::string huge = png;
  for (const std::size_t at : {16U, 20U}) {
    huge[at] = 0, huge[at + 1] = 0, huge[at + 2] = '\xea', huge[at + 3] = '\x60';
  }
  const uLong crc = crc32(0, reinterpret_cast<const Bytef*>(huge.data() + 12), 17);
  for (std::size_t k = 0; k < 4; ++k) huge[29 + k] = static_cast<char>(crc >> (24 - 8 * k));
  write("map.png", huge);
  expect_error(y, img, "header claims 60000 x 60000 pixels");
  // A text chunk after IHDR whose length claims 1.6 GB: refused before libpng allocates it.
  std::string lying = png;
  lying.insert(33, "\x64\x00\x00\x1atEXtSoftware\0mote"s);
  write("map.png", lying);
  expect_error(y, img, "tEXt chunk claims 1677721626 bytes, only");
}

/// Every proper prefix of a valid image must be rejected with InputError, and random byte
/// flips must give either an image or InputError: never a crash or another exception.
/// Prefixes of at least `complete` bytes may be valid (a plain PGM cut inside its last number).
void check_corruptions(const fs::path& file, const std::string& valid, std::size_t complete) {
  for (std::size_t n = 0; n < complete; ++n) {
    std::ofstream(file, std::ios::binary | std::ios::trunc) << valid.substr(0, n);
    EXPECT_THROW((void)read_map_image(file), InputError) << "prefix of " << n << " bytes";
  }
  std::mt19937 rng(17);
  std::uniform_int_distribution<std::size_t> at(0, valid.size() - 1);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int trial = 0; trial < 120; ++trial) {
    std::string bad = valid;
    bad[at(rng)] = static_cast<char>(byte(rng));
    std::ofstream(file, std::ios::binary | std::ios::trunc) << bad;
    try {
      (void)read_map_image(file);
    } catch (const InputError&) {
    }
  }
}

TEST_F(MapErrors, TruncatedOrCorruptedImages) {
  std::string pgm = "P5\n# c\n4 3\n255\n";
  pgm.append(12, '\x7f');  // appended, not `+`: GCC 12 warns on the inlined copy (-Warray-bounds)
  check_corruptions(dir_ / "c.pgm", pgm, pgm.size());
  check_corruptions(dir_ / "c.pgm", "P2\n4 1\n65535\n1 22 333 4444\n"s, 23);
  const std::string png = small_png();
  check_corruptions(dir_ / "c.png", png, png.size());
}

}  // namespace
}  // namespace mote
