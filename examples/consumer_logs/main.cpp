// Uses an installed mote through find_package(mote) and mote::logs alone: reads every scan of a
// recorded log or bag (CARMEN, ROS 1, rosbag2 folder, MCAP) and prints how many there are.
// `consumer_logs LOG [EXPECTED]` exits non-zero when the log cannot be read or, given EXPECTED,
// when it holds another number of scans.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include <mote/logs/scan_source.hpp>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: consumer_logs LOG [EXPECTED_SCANS]\n");
    return 2;
  }
  try {
    auto source = mote::logs::open_scan_log(argv[1]);
    std::size_t scans = 0;
    std::size_t beams = 0;
    while (auto frame = source->next()) {
      ++scans;
      beams += frame->scan.ranges.size();
    }
    std::printf("consumer_logs: %zu scans, %zu readings in %s\n", scans, beams, argv[1]);
    if (argc > 2 && scans != std::stoul(argv[2])) {
      std::fprintf(stderr, "consumer_logs: expected %s scans\n", argv[2]);
      return 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer_logs: %s\n", e.what());
    return 1;
  }
  return 0;
}
