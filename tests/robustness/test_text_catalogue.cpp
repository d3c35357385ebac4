// Bad-input catalogue for TUM trajectories and LocalizerConfig YAML files.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "catalogue.hpp"
#include "mote/engine/localizer_config.hpp"
#include "mote/engine/node_params.hpp"
#include "mote/logs/tum.hpp"
#include "mote_test/data.hpp"

namespace mote::robustness {
namespace {

// ---- TUM -----------------------------------------------------------------------------------

const std::string kPose = "1.5 0.1 -0.2 0 0 0 0.247403959 0.968912422\n";
const std::string kTum = "# timestamp x y z qx qy qz qw\n" + kPose +
                         "2.0 1e-3 2E+1 0.0 0.0 0.0 -0.707106781 0.707106781\n\n"
                         "2.5 0 0 0 0 0 0 1\n";

void read_trajectory(const fs::path& file) { (void)logs::read_tum(file); }

/// kPose with field `k` replaced by `value`.
std::string pose_with(std::size_t k, const std::string& value) {
  std::string line = kPose;
  std::size_t start = 0;
  for (std::size_t i = 0; i < k; ++i) start = line.find(' ', start) + 1;
  const std::size_t end = line.find_first_of(" \n", start);
  return line.replace(start, end - start, value);
}

/// A cut line with fewer than eight fields is an error, and so is a file without a pose.
Expect tum_cut(const std::string& text, std::size_t cut) {
  const std::string kept = text.substr(0, cut);
  const std::size_t line_start = kept.rfind('\n') == std::string::npos ? 0 : kept.rfind('\n') + 1;
  const std::string last = kept.substr(line_start);
  std::size_t fields = 0;
  for (std::size_t i = 0; i < last.size(); ++i) {
    if (last[i] != ' ' && (i == 0 || last[i - 1] == ' ')) ++fields;
  }
  const bool comment = !last.empty() && last[0] == '#';
  std::size_t poses = fields == 8 ? 1 : 0;
  for (std::size_t at = 0; at < line_start; at = kept.find('\n', at) + 1) {
    if (kept[at] != '#' && kept[at] != '\n') ++poses;
  }
  return (fields > 0 && fields < 8 && !comment) || poses == 0 ? Expect::kError
                                                              : Expect::kErrorOrValid;
}

std::vector<Case> tum_cases() {
  std::vector<Case> cases{
      {"empty", ""},
      {"blank lines", "\n \n\t\n"},
      {"comments only", "# a\n# b\n"},
      {"random bytes", random_bytes(1024, 31)},
      {"a YAML file", "image: map.pgm\nresolution: 0.05\n"},
      {"seven fields", pose_with(7, "")},
      {"nine fields", pose_with(7, "1 1")},
      {"one field", "1.5\n"},
      {"stamp text", pose_with(0, "noon")},
      {"stamp NaN", pose_with(0, "nan")},
      {"x inf", pose_with(1, "inf")},
      {"y -inf", pose_with(2, "-inf")},
      {"z NaN", pose_with(3, "NaN")},
      {"qw beyond double", pose_with(7, "1e999")},
      {"qz hex", pose_with(6, "0x1p-2")},
      {"zero quaternion", "1 0 0 0 0 0 0 0\n"},
      {"tiny quaternion", "1 0 0 0 0 0 0 1e-300\n"},
      {"number with a comma", pose_with(1, "0,1")},
      {"control bytes", pose_with(1, "\x1b[2J")},
      {"good then bad", kPose + pose_with(4, "x")},
      {"a 1 MB field", pose_with(1, std::string(1 << 20, '9'))},
  };
  for (Case& c : truncations("TUM", kTum, [](std::size_t cut) { return tum_cut(kTum, cut); })) {
    cases.push_back(std::move(c));
  }
  for (Case& c : byte_flips("TUM", kTum, 80, 2, 32)) cases.push_back(std::move(c));
  return cases;
}

TEST(TumCatalogue, Cases) {
  const fs::path dir = scratch("tum");
  const std::vector<Case> cases = tum_cases();
  EXPECT_GT(run_cases(cases, dir / "ref.tum", read_trajectory), static_cast<int>(cases.size() / 2));
}

TEST(TumCatalogue, RecordedReferenceTruncated) {
  MOTE_REQUIRE_DATA(path, "intel/intel.gt.tum");
  const fs::path dir = scratch("tum_recorded");
  const std::string tum = read_file(path);
  const auto expect = [&tum](std::size_t cut) { return tum_cut(tum, cut); };
  (void)run_cases(truncations("intel.gt.tum", tum, expect, 40), dir / "ref.tum", read_trajectory);
}

// ---- configuration -------------------------------------------------------------------------

// The filter's keys and the node's, as `mote node --config` reads one file twice.
void read_config(const fs::path& file) {
  (void)load_config(file);
  (void)read_node_params(file);
}

std::vector<Case> config_cases() {
  std::vector<Case> cases{
      {"empty", ""},
      {"comments only", "# nothing set\n"},
      {"a scalar", "hello\n"},
      {"a list", "- alpha1: 0.1\n"},
      {"random bytes", random_bytes(1024, 41)},
      {"invalid YAML", "alpha1: [0.1\n"},
      {"tab indentation", "amcl:\n\tros__parameters:\n"},
      {"deep nesting", "alpha1: " + std::string(100000, '[') + "\n"},
      {"number as text", "alpha1: high\n"},
      {"number NaN", "alpha1: .nan\n"},
      {"number inf", "sigma_hit: .inf\n"},
      {"number -inf", "laser_min_range: -.inf\n"},
      {"number beyond double", "z_hit: 1e999\n"},
      {"integer with a fraction", "max_beams: 2.5\n"},
      {"integer text", "min_particles: many\n"},
      {"integer beyond int", "max_particles: 99999999999\n"},
      {"negative seed", "seed: -1\n"},
      {"negative particles", "min_particles: -5\n"},
      {"billion particles", "max_particles: 1000000000\n"},
      {"million threads", "threads: 1000000\n"},
      {"bool as a number", "kld_z_is_quantile: 7\n"},
      {"value a list", "alpha1: [0.1, 0.2]\n"},
      {"value a map", "alpha1: {a: 1}\n"},
      {"unknown model", "laser_model_type: sonar\n"},
      {"model a list", "laser_model_type: [beam]\n"},
      {"key a list", "? [a, b]\n: 1\n"},
      {"key a map", "? {a: 1}\n: 1\n"},
      {"min above max", "min_particles: 900\nmax_particles: 100\n"},
      {"all mixture weights zero", "z_hit: 0\nz_short: 0\nz_max: 0\nz_rand: 0\n"},
      {"nav2 section a scalar", "amcl:\n  ros__parameters: 5\n"},
      {"nav2 section a list", "amcl:\n  ros__parameters:\n    - 1\n"},
      {"nav2 NaN", "amcl:\n  ros__parameters:\n    alpha2: .NaN\n"},
      {"key with control bytes", "\"\\x1b[2J\": 1\nalpha1: x\n"},
      {"alias of a map as a value", "a: &a {b: 1}\nalpha1: *a\n"},
  };
  const std::string nav2 = read_file(mote::test::project_test_data() / "nav2_params.yaml");
  EXPECT_FALSE(nav2.empty());
  for (Case& c : truncations(
           "nav2", nav2, [](std::size_t) { return Expect::kErrorOrValid; }, 60)) {
    cases.push_back(std::move(c));
  }
  for (Case& c : byte_flips("nav2", nav2, 60, 2, 42)) cases.push_back(std::move(c));
  return cases;
}

TEST(ConfigCatalogue, Cases) {
  const fs::path dir = scratch("config");
  const std::vector<Case> cases = config_cases();
  EXPECT_GT(run_cases(cases, dir / "config.yaml", read_config), static_cast<int>(cases.size() / 3));
}

TEST(ConfigCatalogue, ErrorsPlaceTheKey) {
  // An out-of-range value names its line and key, not only LocalizerConfig's field.
  const fs::path file = scratch("config_place") / "config.yaml";
  write_file(file, "alpha1: 0.1\nsigma_hit: -2\n");
  try {
    (void)load_config(file);
    ADD_FAILURE() << "negative sigma_hit accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.place(), "line 2, key 'sigma_hit'");
  }
  write_file(file, "max_particles: 1000000000\n");
  EXPECT_THROW((void)load_config(file), InputError);
}

// An unknown key is an error; one with a newline in its name still gives one printable line.
TEST(ConfigCatalogue, UnknownKeyErrorsAreOneLine) {
  const fs::path file = scratch("config_warn") / "config.yaml";
  write_file(file, "\"bad\\nkey\": 1\n");
  try {
    (void)load_config(file);
    ADD_FAILURE() << "an unknown key loaded";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_TRUE(one_printable_line(message)) << message;
    EXPECT_NE(message.find("bad\\nkey"), std::string::npos) << message;
  }
}

// What stays a warning (an amcl key mote does not implement) is one line too.
TEST(ConfigCatalogue, WarningsAreOneLine) {
  const fs::path file = scratch("config_warn") / "config.yaml";
  write_file(file, "do_beamskip: true\n");
  const LoadedConfig loaded = load_config(file);
  ASSERT_EQ(loaded.warnings.size(), 1U);
  EXPECT_TRUE(one_printable_line(loaded.warnings[0])) << loaded.warnings[0];
}

}  // namespace
}  // namespace mote::robustness
