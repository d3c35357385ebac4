// report.json (JSON writer validity, keys, null for NaN), map.png rendering and the output folder.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string>

#include <unistd.h>

#include "mote/replay/map_image.hpp"
#include "mote/replay/profile.hpp"
#include "mote/replay/report.hpp"
#include "mote/replay/report_json.hpp"

namespace mote::replay {
namespace {

// A tiny JSON checker: validates the whole text and collects the top-level object's keys.
class JsonCheck {
 public:
  explicit JsonCheck(std::string text) : s_(std::move(text)) {}
  bool valid() {
    skip();
    if (!value(0)) return false;
    skip();
    return pos_ == s_.size();
  }
  std::set<std::string> keys;

 private:
  void skip() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_])) != 0) ++pos_;
  }
  bool eat(char c) {
    skip();
    if (pos_ < s_.size() && s_[pos_] == c) return ++pos_, true;
    return false;
  }
  bool literal(std::string_view w) {
    if (s_.compare(pos_, w.size(), w) != 0) return false;
    pos_ += w.size();
    return true;
  }
  bool string(std::string* out) {
    if (!eat('"')) return false;
    std::string text;
    while (pos_ < s_.size() && s_[pos_] != '"') {
      if (static_cast<unsigned char>(s_[pos_]) < 0x20U) return false;
      if (s_[pos_] == '\\') ++pos_;
      text += s_[pos_++];
    }
    if (out != nullptr) *out = text;
    return eat('"');
  }
  bool number() {
    const std::size_t start = pos_;
    while (pos_ < s_.size() &&
           std::string_view("+-0123456789.eE").find(s_[pos_]) != std::string_view::npos) {
      ++pos_;
    }
    return pos_ > start && (std::isdigit(static_cast<unsigned char>(s_[pos_ - 1])) != 0);
  }
  bool members(int depth) {
    if (eat('}')) return true;
    do {
      std::string k;
      if (!string(&k) || !eat(':') || !value(depth + 1)) return false;
      if (depth == 0) keys.insert(k);
    } while (eat(','));
    return eat('}');
  }
  bool items(int depth) {
    if (eat(']')) return true;
    do {
      if (!value(depth + 1)) return false;
    } while (eat(','));
    return eat(']');
  }
  bool value(int depth) {
    skip();
    if (eat('{')) return members(depth);
    if (eat('[')) return items(depth);
    if (pos_ < s_.size() && s_[pos_] == '"') return string(nullptr);
    if (literal("null") || literal("true") || literal("false")) return true;
    return number();
  }
  std::string s_;
  std::size_t pos_ = 0;
};

OccupancyGrid small_map() {
  // 4 x 3 cells of 1 m: bottom row free, middle row occupied except one unknown, top row free.
  std::vector<CellState> cells(12, CellState::kFree);
  for (int i = 0; i < 4; ++i) cells[4 + static_cast<std::size_t>(i)] = CellState::kOccupied;
  cells[5] = CellState::kUnknown;
  return OccupancyGrid(4, 3, 1.0, Pose2{}, cells);
}

ReplayResult fake_result(bool with_reference) {
  ReplayResult r{small_map(), LocalizerConfig{}};
  r.threads = 2;
  r.scans = 3;
  for (int k = 0; k < 2; ++k) {
    UpdateRecord u;
    u.ms = {1.0, 4.0 + k, 0.5, 2.0, 0.5, 8.0 + k};
    u.particles = 1000;
    u.weighed = 1000;
    u.beams = 60;
    r.updates.push_back(u);
    r.trajectory.push_back({static_cast<double>(k), {0.5 + k, 0.5, 0.0}});
  }
  r.outcomes[0] = 2;
  r.outcomes[2] = 1;
  if (with_reference) {
    TrajectoryErrors e;
    e.ate_rmse_m = std::numeric_limits<double>::quiet_NaN();
    e.heading_rmse_deg = 1.5;
    r.errors = e;
  }
  r.reader.first_error = "log.clf: line 3: bad \"number\"\n";
  return r;
}

TEST(JsonWriter, WritesValidNestedJsonWithEscapesAndNullForNonFinite) {
  std::ostringstream out;
  JsonWriter json(out);
  json.begin_object().member("a", 1).member("s", "q\"\\\n\x01");
  json.member("nan", std::numeric_limits<double>::quiet_NaN());
  json.member("inf", std::numeric_limits<double>::infinity());
  json.key("list").begin_array().value(0.25).value(true).null().begin_object().end_object();
  json.end_array().key("empty").begin_array().end_array().end_object();
  JsonCheck check(out.str());
  ASSERT_TRUE(check.valid()) << out.str();
  EXPECT_EQ(check.keys, (std::set<std::string>{"a", "s", "nan", "inf", "list", "empty"}));
  EXPECT_NE(out.str().find("\"nan\": null"), std::string::npos);
  EXPECT_NE(out.str().find("\"inf\": null"), std::string::npos);
  EXPECT_NE(out.str().find("\\u0001"), std::string::npos);
  EXPECT_EQ(out.str().find("nan,"), std::string::npos);
}

TEST(JsonWriter, DoublesRoundTrip) {
  std::ostringstream out;
  JsonWriter(out).begin_array().value(0.1).value(-12345.678901234).value(1e-300).end_array();
  JsonCheck check(out.str());
  EXPECT_TRUE(check.valid());
  EXPECT_NE(out.str().find("0.1"), std::string::npos);
  EXPECT_NE(out.str().find("-12345.678901234"), std::string::npos);
}

TEST(Report, HasTheRequiredKeysAndFigures) {
  std::ostringstream out;
  write_report_json(out, fake_result(true));
  JsonCheck check(out.str());
  ASSERT_TRUE(check.valid()) << out.str();
  for (const char* key :
       {"updates", "scans", "threads", "isa", "isa_detail", "model", "particles_mean", "update_ms",
        "phase_ms", "particle_beams_per_s", "outcomes", "reader", "ate_rmse_m", "heading_rmse_deg",
        "converged_at_s"}) {
    EXPECT_TRUE(check.keys.contains(key)) << key;
  }
  EXPECT_NE(out.str().find("\"ate_rmse_m\": null"), std::string::npos);
  EXPECT_NE(out.str().find("\"converged_at_s\": null"), std::string::npos);
  const RunFigures f = run_figures(fake_result(false));
  EXPECT_DOUBLE_EQ(f.update_ms.mean, 8.5);
  EXPECT_DOUBLE_EQ(f.update_ms.max, 9.0);
  EXPECT_DOUBLE_EQ(f.phase_mean_ms.sensor, 4.5);
  // 2 updates x 1000 particles x 60 beams over 17 ms of update time (bench_e2e's definition).
  EXPECT_NEAR(f.particle_beams_per_s, 120000.0 / 17e-3, 1e-3);
}

TEST(Report, CountsTheUpdatesMoreThanOneMetreOffAndTheFlaggedAmongThem) {
  ReplayResult r = fake_result(true);
  r.off_updates = OffUpdates{.off = 5, .flagged = 3};
  std::ostringstream out;
  write_report_json(out, r);
  ASSERT_TRUE(JsonCheck(out.str()).valid()) << out.str();
  EXPECT_NE(out.str().find("\"updates_over_1m\": 5"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("\"updates_over_1m_flagged\": 3"), std::string::npos);
  EXPECT_NE(out.str().find("\"updates_over_1m_tracking\": 2"), std::string::npos);
  std::ostringstream summary;
  print_summary(summary, r);
  EXPECT_NE(summary.str().find("updates > 1 m off"), std::string::npos) << summary.str();
  EXPECT_NE(summary.str().find(" 5 (3 flagged uncertain or lost, 2 while tracking)\n"),
            std::string::npos)
      << summary.str();
  r.off_updates = OffUpdates{};
  std::ostringstream none;
  print_summary(none, r);
  EXPECT_NE(none.str().find("updates > 1 m off     0\n"), std::string::npos) << none.str();
}

TEST(Report, CountsTheHeldUpdatesTheHandOversAndTheLocalSearches) {
  ReplayResult r = fake_result(false);
  r.updates[0].relocalized = 400;
  r.updates[0].relocalized_locally = true;
  r.updates[0].held = true;
  r.updates[1].held = true;
  r.updates[1].switched = false;
  std::ostringstream out;
  write_report_json(out, r);
  ASSERT_TRUE(JsonCheck(out.str()).valid()) << out.str();
  EXPECT_NE(out.str().find("\"relocalizations_local\": 1"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("\"updates_held\": 2"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("\"held_place_handed_over\": 0"), std::string::npos) << out.str();
  std::ostringstream summary;
  print_summary(summary, r);
  EXPECT_NE(summary.str().find("the tracked place held on 2 updates"), std::string::npos)
      << summary.str();
  r.updates[0].held = r.updates[1].held = false;
  std::ostringstream none;
  print_summary(none, r);
  EXPECT_EQ(none.str().find("held on"), std::string::npos) << none.str();
}

// A run that ends uncertain among several places says how many (a global start on a map of
// look-alike copies); one that ends tracking, or uncertain on one place, does not.
TEST(Report, SaysHowManyPlacesAnUncertainEndCovers) {
  ReplayResult r = fake_result(false);
  r.updates.back().state = LocalizationState::kUncertain;
  r.updates.back().places = 3;
  std::ostringstream three;
  print_summary(three, r);
  EXPECT_NE(three.str().find(", ends uncertain between 3 places,"), std::string::npos)
      << three.str();
  std::ostringstream json;
  write_report_json(json, r);
  EXPECT_NE(json.str().find("\"final_places\": 3"), std::string::npos) << json.str();
  r.updates.back().places = 1;
  std::ostringstream one;
  print_summary(one, r);
  EXPECT_EQ(one.str().find(" places,"), std::string::npos) << one.str();
  r.updates.back().state = LocalizationState::kTracking;
  r.updates.back().places = 3;
  std::ostringstream tracking;
  print_summary(tracking, r);
  EXPECT_EQ(tracking.str().find("between"), std::string::npos) << tracking.str();
}

TEST(Report, WithoutReferenceHasNoAccuracyKeys) {
  std::ostringstream out;
  write_report_json(out, fake_result(false));
  JsonCheck check(out.str());
  ASSERT_TRUE(check.valid());
  EXPECT_FALSE(check.keys.contains("ate_rmse_m"));
}

MapRenderOptions scale_ten() {
  MapRenderOptions options;
  options.target_pixels = 40;  // scale 10 for a 4-cell extent
  options.max_scale = 10;
  return options;
}

// The pixel at (x, y) of the map area.
const std::uint8_t* map_pixel(MapFigure& f, int x, int y) {
  return f.image.at(f.map_area.x + x, f.map_area.y + y);
}

TEST(MapImage, CellsAreColouredAndTheEstimateIsDrawn) {
  const OccupancyGrid map = small_map();
  MapFigure plain = render_map(map, {}, scale_ten());
  ASSERT_EQ(plain.scale, 10);
  ASSERT_EQ(plain.map_area.width, 40);
  ASSERT_EQ(plain.map_area.height, 30);
  EXPECT_EQ(map_pixel(plain, 35, 25)[0], 255);  // bottom row: free
  EXPECT_EQ(map_pixel(plain, 35, 15)[0], 0);    // middle row: occupied
  EXPECT_EQ(map_pixel(plain, 15, 15)[0], 200);  // cell (1, 1): unknown
  const std::vector<logs::StampedPose> path{{0.0, {0.5, 2.5, 0.0}}, {1.0, {3.5, 2.5, 0.0}}};
  MapFigure drawn = render_map(map, {{}, path, {}, {}}, scale_ten());
  const std::uint8_t* mid = map_pixel(drawn, 20, 5);  // the path runs along the top row's centre
  EXPECT_GT(mid[0], 200);
  EXPECT_LT(mid[1], 50);
}

TEST(MapImage, TheReferenceShowsBesideTheEstimateOverIt) {
  const OccupancyGrid map = small_map();
  const std::vector<logs::StampedPose> path{{0.0, {0.5, 2.5, 0.0}}, {1.0, {3.5, 2.5, 0.0}}};
  MapFigure f = render_map(map, {path, path, {}, {}}, scale_ten());
  const std::uint8_t* on = map_pixel(f, 20, 5);
  EXPECT_GT(on[0], 200);  // the estimate on top
  EXPECT_LT(on[1], 50);
  const std::uint8_t* beside = map_pixel(f, 20, 9);  // 4 px off the line: the wider reference
  EXPECT_LT(beside[0], 150);
  EXPECT_GT(beside[1], 180);
}

TEST(MapImage, LostStretchesAreOrange) {
  const OccupancyGrid map = small_map();
  const std::vector<logs::StampedPose> path{
      {0.0, {0.5, 2.5, 0.0}}, {1.0, {2.0, 2.5, 0.0}}, {2.0, {3.5, 2.5, 0.0}}};
  const std::vector<LocalizationState> states{
      LocalizationState::kTracking, LocalizationState::kTracking, LocalizationState::kLost};
  MapFigure f = render_map(map, {{}, path, {}, states}, scale_ten());
  const std::uint8_t* tracked = map_pixel(f, 10, 5);
  const std::uint8_t* lost = map_pixel(f, 30, 5);
  EXPECT_LT(tracked[1], 50);  // red
  EXPECT_GT(lost[0], 200);    // orange
  EXPECT_GT(lost[1], 100);
  EXPECT_LT(lost[2], 50);
}

TEST(MapImage, AxesAndLegendSurroundTheMap) {
  const OccupancyGrid map = small_map();
  const std::vector<logs::StampedPose> path{{0.0, {0.5, 0.5, 0.0}}, {1.0, {3.5, 0.5, 0.0}}};
  const std::vector<Pose2> particles{{3.5, 0.5, 0.0}};
  MapFigure f = render_map(map, {path, path, particles, {}}, scale_ten());
  const auto dark = [&](int x0, int y0, int x1, int y1) {
    int n = 0;
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) n += f.image.at(x, y)[0] < 100;
    }
    return n;
  };
  const figure::PlotArea& a = f.map_area;
  EXPECT_GT(dark(0, a.y, a.x - 1, a.y + a.height), 30);  // y tick labels and title
  const int below = a.y + a.height + figure::bottom_margin(1);
  EXPECT_GT(dark(a.x, a.y + a.height + 1, a.x + a.width, below), 30);  // x ticks, title
  // Legend rows: reference, estimate, final particles, start, end and the scale bar, each
  // labelled (the labels need more rows than a 4 x 3 map's width).
  EXPECT_GT(f.image.height - below, 5 * figure::text_height(1));
  EXPECT_GT(dark(0, below, f.image.width, f.image.height), 200);
}

TEST(Report, OutputFolderHoldsTheThreeFiles) {
  const auto dir = std::filesystem::temp_directory_path() / "mote_test_report_out" / "nested";
  std::filesystem::remove_all(dir.parent_path());
  write_replay_outputs(dir, fake_result(true));
  for (const char* name : {"report.json", "trajectory.tum", "map.png"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / name)) << name;
  }
  std::ifstream png(dir / "map.png", std::ios::binary);
  std::string magic(8, '\0');
  png.read(magic.data(), 8);
  EXPECT_EQ(magic, std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(logs::read_tum(dir / "trajectory.tum").size(), 2U);
  std::filesystem::remove_all(dir.parent_path());
}

TEST(Profile, HistogramBinsAreLogSpacedFromOneMicrosecond) {
  DurationHistogram h;
  for (const double ms : {0.0, 0.0009, 0.001, 0.0019, 0.002, 1.0, 1e9}) h.add(ms);
  EXPECT_EQ(h.counts[0], 2U);   // below 1 us
  EXPECT_EQ(h.counts[1], 2U);   // [1 us, 2 us)
  EXPECT_EQ(h.counts[2], 1U);   // [2 us, 4 us)
  EXPECT_EQ(h.counts[10], 1U);  // 1 ms is in [0.512, 1.024)
  EXPECT_EQ(h.counts.back(), 1U);
  EXPECT_DOUBLE_EQ(DurationHistogram::upper_edge_ms(10), 1.024);
  EXPECT_TRUE(std::isinf(DurationHistogram::upper_edge_ms(DurationHistogram::kBins - 1)));
}

TEST(Profile, PhasesAddUpAndCostPerParticleIsExact) {
  ReplayResult r = fake_result(false);
  r.updates[1].ms.total = 12.0;  // 3 ms outside the five phases: "other"
  const RunProfile p = profile_run(r);
  ASSERT_EQ(p.phases.size(), 6U);
  double share = 0.0;
  for (const PhaseProfile& phase : p.phases) {
    std::uint64_t counted = 0;
    for (const std::uint64_t c : phase.histogram.counts) counted += c;
    EXPECT_EQ(counted, 2U) << phase.name;
    share += phase.share;
  }
  EXPECT_NEAR(share, 1.0, 1e-12);
  EXPECT_EQ(p.phases[1].name, "sensor");
  EXPECT_DOUBLE_EQ(p.phases[1].total_ms, 9.0);
  EXPECT_DOUBLE_EQ(p.phases[1].ns_per_particle, 9e6 / 2000);  // 9 ms over 2 x 1000 particles
  EXPECT_DOUBLE_EQ(p.ns_per_particle_beam, 9e6 / 120000);
  EXPECT_EQ(p.phases[5].name, "other");
  EXPECT_DOUBLE_EQ(p.phases[5].total_ms, 3.0);
  std::ostringstream folded;
  write_folded_stacks(folded, p);
  EXPECT_NE(folded.str().find("mote;update;sensor 9000\n"), std::string::npos) << folded.str();
  EXPECT_NE(folded.str().find("mote;update;other 3000\n"), std::string::npos);
}

TEST(Profile, ReportGainsTheProfileOnlyWhenAsked) {
  std::ostringstream plain;
  write_report_json(plain, fake_result(true));
  EXPECT_EQ(plain.str().find("\"profile\""), std::string::npos);
  std::ostringstream profiled;
  write_report_json(profiled, fake_result(true), ReportOptions{.profile = true});
  JsonCheck check(profiled.str());
  ASSERT_TRUE(check.valid()) << profiled.str();
  EXPECT_TRUE(check.keys.contains("profile"));
  EXPECT_NE(profiled.str().find("\"upper_edge_ms\""), std::string::npos);
  const auto dir =
      std::filesystem::temp_directory_path() / ("mote_test_profile_" + std::to_string(::getpid()));
  write_replay_outputs(dir, fake_result(true), ReportOptions{.profile = true});
  EXPECT_TRUE(std::filesystem::exists(dir / "profile.folded"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace mote::replay
