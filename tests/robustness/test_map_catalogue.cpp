// Bad-input catalogue for map_server maps: the YAML metadata and the PGM/PPM/PNG image readers.
#include <gtest/gtest.h>
#include <png.h>
#include <zlib.h>

#include <string>
#include <vector>

#include "catalogue.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote_test/data.hpp"

namespace mote::robustness {
namespace {

using namespace std::string_literals;

// ---- map YAML ------------------------------------------------------------------------------

const std::string kYaml =
    "image: map.pgm\nresolution: 0.05\norigin: [-1.0, 2.5, 0.1]\nnegate: 0\n"
    "occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n";

void read_yaml(const fs::path& file) { (void)read_map_metadata(file); }

/// kYaml with the line of `key` replaced by `line`.
std::string yaml_with(const std::string& key, const std::string& line) {
  const std::size_t at = kYaml.find(key + ":");
  return kYaml.substr(0, at) + line + kYaml.substr(kYaml.find('\n', at));
}

/// A cut is valid only after the last required key's value has begun.
Expect yaml_cut(std::size_t cut) {
  const std::size_t last_value = kYaml.find("free_thresh: ") + 13;
  return cut <= last_value ? Expect::kError : Expect::kErrorOrValid;
}

std::vector<Case> yaml_cases() {
  std::vector<Case> cases{
      {"empty", ""},
      {"only a comment", "# map\n"},
      {"a PGM instead of YAML", "P5\n2 2\n255\n\x00\xff\x10\x20"s},
      {"a list, not a mapping", "- image: map.pgm\n- resolution: 0.05\n"},
      {"unclosed flow list", yaml_with("origin", "origin: [1, 2, 3")},
      {"tab indentation", "image: map.pgm\n\tresolution: 0.05\n"},
      {"deep nesting", "image: " + std::string(100000, '[') + "\n"},
      {"resolution not a number", yaml_with("resolution", "resolution: fine")},
      {"resolution NaN", yaml_with("resolution", "resolution: .nan")},
      {"resolution inf", yaml_with("resolution", "resolution: .inf")},
      {"resolution beyond double", yaml_with("resolution", "resolution: 1e999")},
      {"resolution zero", yaml_with("resolution", "resolution: 0")},
      {"resolution a list", yaml_with("resolution", "resolution: [0.05]")},
      {"origin NaN", yaml_with("origin", "origin: [.nan, 0, 0]")},
      {"origin -inf yaw", yaml_with("origin", "origin: [0, 0, -.inf]")},
      {"origin two fields", yaml_with("origin", "origin: [1, 2]")},
      {"origin four fields", yaml_with("origin", "origin: [1, 2, 3, 4]")},
      {"origin a scalar", yaml_with("origin", "origin: 5")},
      {"origin a map", yaml_with("origin", "origin: {x: 1, y: 2, yaw: 0}")},
      {"origin text", yaml_with("origin", "origin: [0, east, 0]")},
      {"negate 2", yaml_with("negate", "negate: 2")},
      {"negate text", yaml_with("negate", "negate: perhaps")},
      {"occupied_thresh NaN", yaml_with("occupied_thresh", "occupied_thresh: .NaN")},
      {"free_thresh inf", yaml_with("free_thresh", "free_thresh: .Inf")},
      {"thresholds swapped", yaml_with("free_thresh", "free_thresh: 0.9")},
      {"unknown mode", yaml_with("mode", "mode: fuzzy")},
      {"mode a list", yaml_with("mode", "mode: [raw]")},
      {"empty image", yaml_with("image", "image: ''")},
      {"image with a NUL", yaml_with("image", "image: \"map.pgm\\0.png\"")},
      {"missing resolution", yaml_with("resolution", "# none")},
      {"missing origin", yaml_with("origin", "# none")},
      {"key with control bytes", yaml_with("mode", "mode: \"\\x01\\x1b[2J\"")},
      {"random bytes", random_bytes(512, 1)},
      {"random printable",
       [] {
         std::string s = random_bytes(512, 2);
         for (char& c : s) c = static_cast<char>(' ' + (static_cast<unsigned char>(c) % 95));
         return s;
       }()},
  };
  // Aliases of aliases: yaml-cpp shares the nodes, so this must stay small and fast.
  std::string laughs = "a: &a [x, x, x, x, x, x, x, x]\n";
  for (char n = 'b'; n <= 'j'; ++n) {
    const std::string ref = std::string("*") + static_cast<char>(n - 1);
    laughs += std::string(1, n) + ": &" + n + " [" + ref;
    for (int k = 0; k < 7; ++k) laughs += ", " + ref;
    laughs += "]\n";
  }
  cases.push_back({"alias bomb", laughs + "image: *j\n"});
  for (Case& c : truncations("YAML", kYaml, yaml_cut)) cases.push_back(std::move(c));
  for (Case& c : byte_flips("YAML", kYaml, 80, 2, 3)) cases.push_back(std::move(c));
  return cases;
}

TEST(MapCatalogue, Yaml) {
  const fs::path dir = scratch("map_yaml");
  const std::vector<Case> cases = yaml_cases();
  EXPECT_GT(run_cases(cases, dir / "map.yaml", read_yaml), static_cast<int>(cases.size() / 2));
}

TEST(MapCatalogue, RecordedYamlsTruncated) {
  MOTE_REQUIRE_DATA(maps, "maps");
  const fs::path dir = scratch("map_yaml_recorded");
  for (const char* name : {"intel/intel.yaml", "wean/wean_map.yaml", "maps/willow-full-0.05.yaml",
                           "maps/basement_fixed.map.yaml", "dis/dis_underground.yaml"}) {
    const std::string yaml = read_file(mote::test::data_dir() / name);
    ASSERT_FALSE(yaml.empty()) << name;
    (void)run_cases(truncations(name, yaml, [](std::size_t) { return Expect::kErrorOrValid; }),
                    dir / "map.yaml", read_yaml);
    EXPECT_EQ(run_cases({{"empty", ""}}, dir / "map.yaml", read_yaml), 1);
  }
}

// ---- images --------------------------------------------------------------------------------

void read_image(const fs::path& file) {
  const MapImage image = read_map_image(file);
  MapMetadata meta;
  meta.resolution = 0.05;
  const OccupancyGrid grid = grid_from_image(image, meta, file.string());
  EXPECT_EQ(grid.width(), image.width);
}

std::string png_of(int width, int height, std::uint32_t format) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width);
  image.height = static_cast<png_uint_32>(height);
  image.format = format;
  std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(image));
  for (std::size_t k = 0; k < pixels.size(); ++k) pixels[k] = static_cast<unsigned char>(k * 37);
  png_alloc_size_t size = 0;
  png_image_write_get_memory_size(image, size, 0, pixels.data(), 0, nullptr);
  std::string bytes(size, '\0');
  png_image_write_to_memory(&image, bytes.data(), &size, 0, pixels.data(), 0, nullptr);
  bytes.resize(size);
  return bytes;
}

/// `png` with IHDR claiming width x height, its CRC recomputed so libpng reads the header.
std::string png_claiming(std::string png, std::uint32_t width, std::uint32_t height) {
  for (std::size_t k = 0; k < 4; ++k) {
    png[16 + k] = static_cast<char>(width >> (24 - 8 * k));
    png[20 + k] = static_cast<char>(height >> (24 - 8 * k));
  }
  const uLong crc = crc32(0, reinterpret_cast<const Bytef*>(png.data() + 12), 17);
  for (std::size_t k = 0; k < 4; ++k) png[29 + k] = static_cast<char>(crc >> (24 - 8 * k));
  return png;
}

const std::string kP5 =
    "P5\n# map\n4 3\n255\n"s + "\x00\x10\x20\x30\x40\x50\x60\x70\x80\x90\xa0\xff"s;
const std::string kP6 = "P6\n2 1\n65535\n"s + std::string(12, '\x7f');
const std::string kP2 = "P2\n3 2\n100\n0 10 20\n30 40 100\n";

/// An ASCII PGM cut inside or after its last sample's first digit is still complete.
Expect p2_cut(std::size_t cut) {
  return cut <= kP2.rfind("100") ? Expect::kError : Expect::kErrorOrValid;
}

std::vector<Case> image_cases() {
  const std::string png = png_of(5, 4, PNG_FORMAT_GRAY);
  std::string png_bad_magic = png;
  png_bad_magic[1] = 'Q';
  std::vector<Case> cases{
      {"empty", ""},
      {"one byte P", "P"},
      {"magic P7", "P7\n2 2\n255\n\x00\x00\x00\x00"s},
      {"magic PX", "PX\n2 2\n255\n"},
      {"GIF", "GIF89a\x01\x00\x01\x00"s},
      {"PNG magic flipped", png_bad_magic},
      {"width text", "P5\nwide 2\n255\n\x00\x00"s},
      {"width NaN", "P2\nnan 2\n255\n0 0\n"},
      {"width inf", "P2\ninf 2\n255\n0 0\n"},
      {"negative width", "P5\n-2 2\n255\n\x00\x00\x00\x00"s},
      {"zero width", "P5\n0 2\n255\n"},
      {"maxval zero", "P5\n1 1\n0\n\x00"s},
      {"maxval 70000", "P5\n1 1\n70000\n\x00\x00"s},
      {"no maxval", "P5\n1 1\n"},
      {"no whitespace after maxval", "P5\n1 1\n255"},
      {"sample above maxval", "P2\n2 1\n10\n3 11\n"},
      {"sample text", "P2\n2 1\n10\n3 x\n"},
      {"sample NaN", "P2\n2 1\n10\n3 nan\n"},
      {"too few ASCII samples", "P2\n3 1\n10\n3 4\n"},
      {"too few RGB samples", "P3\n1 1\n255\n1 2\n"},
      {"1e9 pixels in 20 bytes", "P5\n40000 25000\n255\n\x00\x00"s},
      {"1e9 ASCII samples", "P2\n40000 25000\n255\n0 0 0\n"},
      {"2^32 pixels", "P5\n65536 65536\n255\n\x00"s},
      {"width beyond int", "P5\n99999999999 1\n255\n\x00"s},
      {"16-bit data cut", "P5\n2 2\n65535\n\x01\x02\x03"s},
      {"PNG claiming 60000 x 60000", png_claiming(png, 60000, 60000)},
      {"PNG claiming 2^31-1 x 1", png_claiming(png, 0x7FFFFFFF, 1)},
      {"PNG claiming zero width", png_claiming(png, 0, 4)},
      {"random bytes", random_bytes(4096, 4)},
      {"random bytes after P5", "P5" + random_bytes(4096, 5)},
      {"random bytes after the PNG magic", png.substr(0, 8) + random_bytes(4096, 6)},
  };
  const auto all = [](std::size_t) { return Expect::kError; };
  for (Case& c : truncations("P5", kP5, all)) cases.push_back(std::move(c));
  for (Case& c : truncations("P6", kP6, all)) cases.push_back(std::move(c));
  for (Case& c : truncations("P2", kP2, p2_cut)) cases.push_back(std::move(c));
  for (const std::uint32_t format : {std::uint32_t{PNG_FORMAT_GRAY}, std::uint32_t{PNG_FORMAT_RGBA},
                                     std::uint32_t{PNG_FORMAT_GA}}) {
    const std::string p = png_of(5, 4, format);
    for (Case& c : truncations("PNG", p, all)) cases.push_back(std::move(c));
    for (Case& c : byte_flips("PNG", p, 60, 1, format)) cases.push_back(std::move(c));
  }
  for (Case& c : byte_flips("P5", kP5, 60, 2, 7)) cases.push_back(std::move(c));
  for (Case& c : byte_flips("P2", kP2, 60, 2, 8)) cases.push_back(std::move(c));
  return cases;
}

TEST(MapCatalogue, Images) {
  const fs::path dir = scratch("map_image");
  const std::vector<Case> cases = image_cases();
  EXPECT_GT(run_cases(cases, dir / "map.img", read_image), static_cast<int>(cases.size() / 2));
}

TEST(MapCatalogue, RecordedImagesTruncated) {
  MOTE_REQUIRE_DATA(pgm, "maps/turtlebot3_world.pgm");
  const fs::path dir = scratch("map_image_recorded");
  const auto all = [](std::size_t) { return Expect::kError; };
  for (const char* name : {"maps/turtlebot3_world.pgm", "intel/intel.png", "wean/wean_map.png"}) {
    const std::string image = read_file(mote::test::data_dir() / name);
    ASSERT_FALSE(image.empty()) << name;
    const std::vector<Case> cases = truncations(name, image, all, 24);
    EXPECT_EQ(run_cases(cases, dir / "map.img", read_image), static_cast<int>(cases.size()));
  }
}

}  // namespace
}  // namespace mote::robustness
