// `mote kidnap`: a kidnapped-robot log spliced from a recorded log with reference poses.
#include <array>
#include <charconv>
#include <iomanip>
#include <iostream>

#include "args.hpp"
#include "commands.hpp"
#include "mote/logs/tum.hpp"
#include "mote/sim/kidnap.hpp"

namespace mote::tool {
namespace {

constexpr std::array<FlagSpec, 6> kFlags{{
    {"log", "LOG", "recorded log: CARMEN .clf/.log or ROS 1 .bag (required)"},
    {"reference", "REF.tum", "reference poses of the log's scans (required)"},
    {"out", "DIR", "output folder for kidnap.clf and kidnap.tum, created if missing (required)"},
    {"keep-first", "F", "fraction of the scans kept from the start (default 0.4)"},
    {"keep-last", "F", "fraction of the scans kept from the end (default 0.3)"},
    {"lenient", "", "skip malformed log records instead of failing"},
}};

constexpr std::string_view kUsage =
    "mote kidnap --log LOG --reference REF.tum --out DIR [--keep-first F] [--keep-last F]";
constexpr std::string_view kAbout =
    "Writes a kidnapped-robot test: the first part of the log, then its last part with the\n"
    "odometry rewritten to continue smoothly from the end of the first (same increments, no\n"
    "jump), scans and reference poses as recorded. DIR/kidnap.clf (CARMEN) and DIR/kidnap.tum\n"
    "are ready for `mote replay --reference DIR/kidnap.tum --kidnapped-at STAMP`, STAMP being\n"
    "the splice stamp printed here.";

sim::KidnapOptions kidnap_options(const ParsedArgs& args) {
  sim::KidnapOptions o;
  if (auto f = args.real("keep-first", 0.0, 1.0)) o.keep_first = *f;
  if (auto f = args.real("keep-last", 0.0, 1.0)) o.keep_last = *f;
  return o;
}

// Shortest text that parses back to `stamp`, so it can be pasted into --kidnapped-at.
std::string exact(double stamp) {
  std::array<char, 32> buf{};
  const auto result = std::to_chars(buf.data(), buf.data() + buf.size(), stamp);
  return {buf.data(), result.ptr};
}

}  // namespace

int kidnap_command(std::span<char* const> words) {
  const ParsedArgs args = parse_args("kidnap", words, kFlags);
  if (args.has("help")) {
    print_help(std::cout, kUsage, kAbout, kFlags);
    return 0;
  }
  const std::filesystem::path log = args.required("log");
  const std::filesystem::path ref = args.required("reference");
  const std::filesystem::path out = args.required("out");
  const sim::KidnapOptions options = kidnap_options(args);
  const std::vector<logs::StampedPose> reference = logs::read_tum(ref);
  logs::ReaderOptions reader;
  reader.lenient = args.has("lenient");
  auto source = logs::open_scan_log(log, reader);
  const sim::KidnapFiles files = sim::make_kidnap_files(*source, reference, out, options);
  const sim::KidnappedLog& k = files.spliced;
  std::cout << "kidnapped " << k.frames.size() << " scans: " << k.splice_index << " + "
            << k.frames.size() - k.splice_index << ", carried " << std::fixed
            << std::setprecision(2) << k.carried_m << " m at the splice\n"
            << "  splice stamp " << exact(k.splice_stamp) << "\n  log          "
            << files.log.string() << "\n  reference    " << files.reference.string() << '\n';
  return 0;
}

}  // namespace mote::tool
