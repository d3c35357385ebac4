// Bad-input catalogue for CARMEN logs, strict and lenient.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "catalogue.hpp"
#include "log_cases.hpp"
#include "mote_test/data.hpp"

namespace mote::robustness {
namespace {

const std::string kLog =
    "# CARMEN log: one message per line\n"
    "PARAM robot_frontlaser_offset 0.25\n"
    "ODOM 0.0 0.0 0.0 0.0 0.0 0.0 1.0 host 1.0\n"
    "FLASER 4 1.0 2.0 3.0 81.83 0.25 0.0 0.0 0.0 0.0 0.0 1.5 host 1.5\n"
    "SYNC 1.55 host 1.55\n"
    "RLASER 3 1.0 2.0 3.0 -0.1 0.0 3.14 0.0 0.0 0.0 1.6 host 1.6\n"
    "ROBOTLASER1 0 -1.5708 3.1416 0.0175 81.9 0.01 0 3 1.0 2.0 3.0 2 10 20 0.35 0.0 0.0 0.1 0.0 "
    "0.0 0.3 0.0 0.0 0.0 0.0 1.7 host 1.7\n";

const std::string kFlaser = "FLASER 3 1.0 2.0 3.0 0 0 0 0 0 0 1.5 host 1.5\n";

/// kFlaser with field `k` (0 = type) replaced by `value`.
std::string flaser_with(std::size_t k, const std::string& value) {
  std::string line = kFlaser;
  std::size_t start = 0;
  for (std::size_t i = 0; i < k; ++i) start = line.find(' ', start) + 1;
  const std::size_t end = line.find_first_of(" \n", start);
  return line.replace(start, end - start, value);
}

std::vector<Case> carmen_cases() {
  std::vector<Case> cases{
      {"empty", ""},
      {"blank lines", "\n\n  \n"},
      {"comments only", "# nothing\n# here\n"},
      {"odometry only", "ODOM 0 0 0 0 0 0 1.0 host 1.0\n"},
      {"a ROS bag", "#ROSBAG V2.0\n" + random_bytes(200, 11)},
      {"a PNG", "\x89PNG\r\n\x1a\n" + random_bytes(200, 12)},
      {"random bytes", random_bytes(2048, 13)},
      {"NUL bytes", std::string(64, '\0')},
      {"beam count text", flaser_with(1, "three")},
      {"beam count huge", flaser_with(1, "99999999999")},
      {"beam count 2^31", flaser_with(1, "2147483648")},
      {"beam count one", flaser_with(1, "1")},
      {"beam count negative", flaser_with(1, "-3")},
      {"range text", flaser_with(2, "far")},
      {"range NaN", flaser_with(2, "nan")},
      {"range inf", flaser_with(3, "inf")},
      {"range -inf", flaser_with(3, "-inf")},
      {"range negative", flaser_with(4, "-1")},
      {"range beyond double", flaser_with(4, "1e999")},
      {"odometry x NaN", flaser_with(8, "NaN")},
      {"odometry theta inf", flaser_with(10, "INF")},
      {"timestamp text", flaser_with(11, "noon")},
      {"timestamp inf", flaser_with(11, "inf")},
      {"logger timestamp NaN", flaser_with(13, "nan")},
      {"one field too many", flaser_with(13, "1.5 extra")},
      {"one field too few", flaser_with(13, "")},
      {"ranges missing", "FLASER 180 1 2 3\n"},
      {"ODOM short", kFlaser + "ODOM 1 2 3\n"},
      {"ODOM long", kFlaser + "ODOM 1 2 3 4 5 6 7 host 8 9\n"},
      {"ODOM NaN", kFlaser + "ODOM nan 0 0 0 0 0 1 host 1\n"},
      {"ROBOTLASER1 short", kFlaser + "ROBOTLASER1 0 -1.5 3.1 0.5 80 0.01 0 3 1 1\n"},
      {"ROBOTLASER1 huge remissions", kFlaser + "ROBOTLASER1 0 -1.5 3.1 0.5 80 0.01 0 1 1 "
                                                "99999999 0 0 0 0 0 0 0 0 0 0 0 1 h 1\n"},
      {"ROBOTLASER1 start NaN", kFlaser + "ROBOTLASER1 0 nan 3.1 0.5 80 0.01 0 1 1 0 0 0 0 0 0 "
                                          "0 0 0 0 0 0 1 h 1\n"},
      {"PARAM offset text", "PARAM robot_frontlaser_offset ahead\n" + kFlaser},
      {"PARAM offset inf", "PARAM robot_rearlaser_offset inf\n" + kFlaser},
      {"control bytes in a field", kFlaser + "FLASER 3 1\x1b[2J 2 3 0 0 0 0 0 0 1 h 1\n"},
      {"binary message type", kFlaser + "FL\x01SER 3 1 2 3 0 0 0 0 0 0 1 h 1\n"},
      {"a 1 MB line of digits", kFlaser + "ODOM " + std::string(1 << 20, '7') + "\n"},
  };
  for (Case& c : truncations("log", kLog, [](std::size_t cut) { return carmen_cut(kLog, cut); })) {
    cases.push_back(std::move(c));
  }
  for (Case& c : byte_flips("log", kLog, 100, 2, 14)) cases.push_back(std::move(c));
  return cases;
}

TEST(CarmenCatalogue, Cases) {
  const fs::path dir = scratch("carmen");
  const std::vector<Case> cases = carmen_cases();
  EXPECT_GT(run_log_cases(cases, dir / "log.clf"), static_cast<int>(cases.size() / 2));
}

TEST(CarmenCatalogue, RecordedLogsTruncated) {
  MOTE_REQUIRE_DATA(intel, "intel/intel.clf");
  const fs::path dir = scratch("carmen_recorded");
  for (const char* name : {"intel/intel.clf", "wean/robotdata1.clf"}) {
    const std::string all = read_file(mote::test::data_dir() / name);
    const std::string log = all.substr(0, all.find('\n', 200000) + 1);  // whole lines
    const auto expect = [&log](std::size_t cut) { return carmen_cut(log, cut); };
    (void)run_log_cases(truncations(name, log, expect, 24), dir / "log.clf");
    (void)run_log_cases(byte_flips(name, log, 10, 4, 15), dir / "log.clf");
  }
}

}  // namespace
}  // namespace mote::robustness
