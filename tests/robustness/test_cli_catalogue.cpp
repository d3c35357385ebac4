// `mote replay` given a bad map, log, bag, reference or configuration: exit status 1 and one line
// on stderr naming the bad file, whatever is wrong with it.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include "bag_builder.hpp"
#include "catalogue.hpp"

namespace mote::robustness {
namespace {

struct Exit {
  int status = -1;
  std::string err;
};

/// Runs `mote ARGS` with stdout discarded and stderr captured in a file.
Exit mote(const std::string& args, const fs::path& dir) {
  const fs::path err = dir / "stderr.txt";
  const std::string cmd =
      std::string("'") + MOTE_EXE + "' " + args + " >/dev/null 2>'" + err.string() + "'";
  const int raw = std::system(cmd.c_str());
  Exit r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.err = read_file(err);
  return r;
}

std::string quoted(const fs::path& p) {
  std::string out = "'";
  out += p.string();
  out += '\'';
  return out;
}

/// A CARMEN log the filter can run: three 181-beam scans while driving 0.5 m steps.
std::string good_log() {
  std::string log;
  for (int k = 0; k < 3; ++k) {
    const std::string x = std::to_string(0.5 * k);
    log += "FLASER 181";
    for (int b = 0; b < 181; ++b) log += " 3.0";
    log += " " + x + " 0 0 " + x + " 0 0 " + std::to_string(k) + " host " + std::to_string(k);
    log += "\n";
  }
  return log;
}

std::string good_bag() {
  mote::test::BagBuilder b;
  b.connection(0, "/scan", "sensor_msgs/LaserScan");
  b.connection(1, "/odom", "nav_msgs/Odometry");
  b.message(1, 1, 0, mote::test::odom_message(1, 0, 0.0, 0.0, 0.0));
  b.message(0, 1, 0, mote::test::scan_message(1, 0, "", {1.0F, 2.0F}));
  b.message(1, 2, 0, mote::test::odom_message(2, 0, 1.0, 0.0, 0.0));
  return b.finish("lz4");
}

/// One bad file: which flag takes it, its name and its bytes.
struct BadFile {
  std::string flag;
  std::string name;
  std::string bytes;
  std::string named;  ///< the file the message must name, when not this one (a map's image)
};

std::vector<BadFile> bad_files() {
  const std::string yaml_head =
      "resolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n"
      "occupied_thresh: 0.65\nfree_thresh: 0.196\n";
  const std::string log = good_log();
  const std::string bag = good_bag();
  return {
      {"map", "empty.yaml", "", ""},
      {"map", "random.yaml", random_bytes(300, 51), ""},
      {"map", "nan.yaml",
       "image: floor.pgm\nresolution: .nan\norigin: [0, 0, 0]\nnegate: 0\n"
       "occupied_thresh: 0.65\nfree_thresh: 0.196\n",
       ""},
      {"map", "cut_image.yaml", "image: cut.pgm\n" + yaml_head, "cut.pgm"},
      {"map", "huge_image.yaml", "image: huge.pgm\n" + yaml_head, "huge.pgm"},
      {"log", "empty.clf", "", ""},
      {"log", "random.clf", random_bytes(3000, 52), ""},
      {"log", "cut.clf", log.substr(0, log.size() / 2), ""},
      {"log", "nan.clf", log + "FLASER 3 1 nan 3 0 0 0 0 0 0 9 host 9\n", ""},
      {"log", "empty.bag", "", ""},
      {"log", "random.bag", random_bytes(3000, 53), ""},
      {"log", "cut.bag", bag.substr(0, bag.size() / 2), ""},
      {"log", "binary_line.clf", log + "FLA\x01SER\n", ""},
      {"log", "empty.mcap", "", ""},
      {"log", "random.mcap", random_bytes(3000, 54), ""},
      {"log", "magic_then_random.mcap", std::string("\x89MCAP0\r\n", 8) + random_bytes(300, 55),
       ""},
      {"log", "empty.db3", "", ""},
      {"log", "random.db3", random_bytes(3000, 56), ""},
      {"reference", "empty.tum", "", ""},
      {"reference", "nan.tum", "0 nan 0 0 0 0 0 1\n", ""},
      {"reference", "short.tum", "0 0 0 0 0 0 1\n", ""},
      {"config", "empty_config.yaml", "", ""},
      {"config", "nan_config.yaml", "alpha1: .nan\n", ""},
      {"config", "scalar_config.yaml", "hello\n", ""},
      {"config", "key_config.yaml", "? [a, b]\n: 1\n", ""},
      {"config", "huge_config.yaml", "max_particles: 1000000000\n", ""},
      {"config", "newline_config.yaml", "sigma_hit: \"a\\nb\"\n", ""},
      {"config", "typo_config.yaml", "sigma_hitt: 0.1\n", ""},
      {"config", "unknown_config.yaml", "frobnicate: 1\n", ""},
  };
}

TEST(CliCatalogue, EveryBadFileExitsWithOneLineNamingIt) {
  const fs::path dir = scratch("cli");
  write_file(dir / "floor.pgm", "P5\n8 8\n255\n" + std::string(64, '\xfe'));
  write_file(dir / "cut.pgm", "P5\n8 8\n255\n" + std::string(40, '\xfe'));
  write_file(dir / "huge.pgm", "P5\n40000 25000\n255\n" + std::string(64, '\xfe'));
  write_file(dir / "map.yaml",
             "image: floor.pgm\nresolution: 0.5\norigin: [-2, -2, 0]\n"
             "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n");
  write_file(dir / "log.clf", good_log());
  write_file(dir / "ref.tum", "0 0 0 0 0 0 0 1\n1 0.5 0 0 0 0 0 1\n2 1 0 0 0 0 0 1\n");
  write_file(dir / "config.yaml", "alpha1: 0.1\n");
  // The good files replay: each bad file below is the only cause of failure.
  const std::string good = "--map " + quoted(dir / "map.yaml") + " --log " +
                           quoted(dir / "log.clf") + " --reference " + quoted(dir / "ref.tum") +
                           " --config " + quoted(dir / "config.yaml");
  // Status 3: they replay to the end, on an 8 x 8 map where no scan fits (the run ends lost).
  ASSERT_EQ(mote("replay --quiet " + good + " --out " + quoted(dir / "out"), dir).status, 3);
  for (const BadFile& bad : bad_files()) {
    write_file(dir / bad.name, bad.bytes);
    std::string args = good;
    const std::string from = "--" + bad.flag + " '";
    const std::size_t at = args.find(from) + from.size();
    args.replace(at, args.find('\'', at) - at, (dir / bad.name).string());
    const Exit r = mote("replay --quiet " + args + " --out " + quoted(dir / "out"), dir);
    const std::string named = (dir / (bad.named.empty() ? bad.name : bad.named)).string();
    EXPECT_EQ(r.status, 1) << bad.name << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << bad.name << ": " << r.err;
    EXPECT_EQ(r.err.rfind("mote replay: " + named + ": ", 0), 0U) << bad.name << ": " << r.err;
    EXPECT_TRUE(one_printable_line(r.err.substr(0, r.err.size() - 1))) << r.err;
  }
}

// Mistakes a user makes with good files: the message says what the file is and what to give.
TEST(CliCatalogue, AnImageOrAStorageFolderSaysWhatToGiveInstead) {
  const fs::path dir = scratch("cli_mistakes");
  write_file(dir / "floor.pgm", "P5\n8 8\n255\n" + std::string(64, '\xfe'));
  write_file(dir / "plan.png", std::string("\x89PNG\r\n\x1a\n", 8) + random_bytes(100, 57));
  write_file(dir / "floor.yaml",
             "image: floor.pgm\nresolution: 0.5\norigin: [-2, -2, 0]\n"
             "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n");
  write_file(dir / "log.clf", good_log());
  fs::create_directories(dir / "bag");
  write_file(dir / "bag" / "rec_0.db3", random_bytes(100, 58));
  const std::string log = " --log " + quoted(dir / "log.clf") + " --out " + quoted(dir / "out");
  const std::string map = " --map " + quoted(dir / "floor.yaml");
  struct Case {
    std::string args;
    std::string starts;  // the message's start: the prefix and the file
    std::string says;    // what it must say
  };
  const std::vector<Case> cases{
      {"replay --map " + quoted(dir / "plan.png") + log,
       "mote replay: " + (dir / "plan.png").string() + ": byte 0: ",
       "is a PNG image, not a map: a map is a map_server YAML file"},
      {"replay --map " + quoted(dir / "floor.pgm") + log,
       "mote replay: " + (dir / "floor.pgm").string() + ": byte 0: ",
       "PGM image, not a map: a map is a map_server YAML file (image, resolution, origin, "
       "thresholds); did you mean " +
           (dir / "floor.yaml").string() + "?"},
      {"replay" + map + " --log " + quoted(dir / "bag") + " --out " + quoted(dir / "out"),
       "mote replay: " + (dir / "bag").string() + ": ",
       "no metadata.yaml); it holds the storage file rec_0.db3, which mote reads alone: give " +
           (dir / "bag" / "rec_0.db3").string()},
      {"info " + quoted(dir / "bag"), "mote info: " + (dir / "bag").string() + ": ", "rec_0.db3"},
      {"calibrate --map " + quoted(dir / "plan.png") + log,
       "mote calibrate: " + (dir / "plan.png").string() + ": ", "PNG image, not a map"},
  };
  for (const Case& c : cases) {
    const Exit r = mote(c.args, dir);
    EXPECT_EQ(r.status, 1) << c.args << ": " << r.err;
    EXPECT_EQ(r.err.rfind(c.starts, 0), 0U) << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

}  // namespace
}  // namespace mote::robustness
