// The viewer's recording (fixed point, decimation, weights, endpoints) and page assembly; the
// page in a browser is tests/replay/test_viewer.py.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/replay/viewer.hpp"

namespace mote::replay {
namespace {

// A 10 m x 6 m room of 0.1 m cells: walls on the border, free inside.
OccupancyGrid room(Pose2 origin = {}) {
  const int w = 100, h = 60;
  std::vector<CellState> cells(static_cast<std::size_t>(w * h), CellState::kFree);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      if (i == 0 || j == 0 || i == w - 1 || j == h - 1)
        cells[static_cast<std::size_t>(j * w + i)] = CellState::kOccupied;
    }
  }
  return {w, h, 0.1, origin, std::move(cells)};
}

// 90 beams over 180 degrees, 2 m each, the last one "no return".
logs::ScanFrame frame_at_start() {
  logs::ScanFrame f;
  f.scan.angle_min = static_cast<float>(-std::numbers::pi / 2);
  f.scan.angle_increment = static_cast<float>(std::numbers::pi / 90);
  f.scan.range_min = 0.1F;
  f.scan.range_max = 30.0F;
  f.scan.ranges.assign(90, 2.0F);
  f.scan.ranges.back() = 30.0F;
  return f;
}

// The "map" object of the page's data block: size, offset in the whole map, decoded cells.
struct EmbeddedMap {
  int width = 0, height = 0, u0 = 0, v0 = 0;
  std::vector<std::uint8_t> cells;
};

std::vector<std::uint8_t> decode_base64(std::string_view text) {
  constexpr std::string_view kAlphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<std::uint8_t> out;
  unsigned bits = 0, value = 0;
  for (const char c : text) {
    if (c == '=') break;
    value = (value << 6U) | static_cast<unsigned>(kAlphabet.find(c));
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<std::uint8_t>((value >> bits) & 0xFFU));
    }
  }
  return out;
}

EmbeddedMap embedded_map(const std::string& block) {
  EmbeddedMap m;
  const std::size_t at = block.find("\"map\":{");
  EXPECT_NE(at, std::string::npos);
  if (at == std::string::npos) return m;
  double resolution = 0;
  EXPECT_EQ(
      std::sscanf(block.c_str() + at,
                  "\"map\":{\"width\":%d,\"height\":%d,\"u0\":%d,\"v0\":%d,\"resolution\":%lf",
                  &m.width, &m.height, &m.u0, &m.v0, &resolution),
      5);
  const std::size_t begin = block.find("\"cells\":\"", at) + 9;
  m.cells = decode_base64(std::string_view(block).substr(begin, block.find('"', begin) - begin));
  return m;
}

TEST(ViewerFixedPoint, MapCornersSpanTheRangeAlongTheLongerSide) {
  const OccupancyGrid map = room({-2.0, 1.0, 0.0});
  const FixedPointGrid grid(map);
  EXPECT_DOUBLE_EQ(grid.per_cell(), 65535.0 / 100);
  EXPECT_EQ(grid.fixed({-2.0, 1.0}), (std::array<std::uint16_t, 2>{0, 0}));
  EXPECT_EQ(grid.fixed({8.0, 7.0})[0], 65535);
  EXPECT_EQ(grid.fixed({8.0, 7.0})[1], std::lround(60 * 655.35));
  EXPECT_TRUE(grid.inside({3.0, 4.0}));
  EXPECT_FALSE(grid.inside({8.5, 4.0}));
  EXPECT_EQ(grid.fixed({1e9, 0.0})[0], 65535);  // clamped, not wrapped
  EXPECT_EQ(grid.fixed({std::nan(""), 0.0})[0], 0);
}

TEST(ViewerFixedPoint, FollowsARotatedOrigin) {
  // Origin yaw 90 degrees: the grid's u axis is the map's y axis.
  const OccupancyGrid map = room({0.0, 0.0, std::numbers::pi / 2});
  const FixedPointGrid grid(map);
  EXPECT_NEAR(grid.cells({-1.0, 2.0}).x, 20.0, 1e-9);
  EXPECT_NEAR(grid.cells({-1.0, 2.0}).y, 10.0, 1e-9);
}

TEST(ViewerRecorder, DecimatesToTheCapAndScalesWeightsToTheHeaviest) {
  const OccupancyGrid map = room();
  LocalizerConfig config;
  config.min_particles = config.max_particles = 5000;
  config.threads = 1;
  Localizer filter(map, config);
  filter.initialize_global();
  const logs::ScanFrame frame = frame_at_start();
  ASSERT_TRUE(filter.update(frame.odometry, frame.scan));
  ViewerRecorder recorder(map);
  recorder.record(filter, frame);
  const ViewerRecording& r = recorder.recording();
  ASSERT_EQ(r.particle_end.size(), 1U);
  EXPECT_EQ(r.particle_end[0],
            3 * std::min<std::size_t>(filter.particles().size(), kViewerParticles));
  std::uint16_t heaviest = 0;
  for (std::size_t i = 2; i < r.particles.size(); i += 3)
    heaviest = std::max(heaviest, r.particles[i]);
  EXPECT_EQ(heaviest, 65535);
  // 89 valid beams of 2 m, each endpoint inside the map or left out; the no-return beam never.
  ASSERT_EQ(r.endpoint_end.size(), 1U);
  EXPECT_LE(r.endpoint_end[0], 2U * 89U);
  EXPECT_EQ(r.endpoint_end[0], r.endpoints.size());
  EXPECT_EQ(r.clusters.size(), 1U);
  EXPECT_GE(r.clusters[0], 1);
  EXPECT_EQ(r.heavy_cluster_end[0] % 3, 0U);
  EXPECT_GE(r.heavy_cluster_end[0], 3U);
}

TEST(ViewerPage, RefusesARecordingOfAnotherRun) {
  ReplayResult result(room(), LocalizerConfig{});
  result.updates.resize(2);
  result.trajectory.resize(2);
  ViewerRecording recording;  // no updates
  std::ostringstream out;
  EXPECT_THROW(write_viewer_page(out, result, recording), Error);
}

TEST(ViewerPage, EmbedsTheDataInOneScriptBlock) {
  const OccupancyGrid map = room();
  LocalizerConfig config;
  config.min_particles = config.max_particles = 100;
  config.threads = 1;
  Localizer filter(map, config);
  filter.initialize({5.0, 3.0, 0.0}, Eigen::Matrix3d::Identity() * 0.01);
  const logs::ScanFrame frame = frame_at_start();
  ASSERT_TRUE(filter.update(frame.odometry, frame.scan));
  ReplayResult result(map, config);
  result.trajectory.push_back({frame.stamp, filter.estimate().best().mean});
  UpdateRecord update;
  update.stamp = frame.stamp;
  update.ms = filter.last_update().ms;
  result.updates.push_back(update);
  ViewerRecorder recorder(map);
  recorder.record(filter, frame);
  std::ostringstream out;
  write_viewer_page(out, result, recorder.recording());
  const std::string page = out.str();
  const std::size_t data = page.find("<script id=\"mote-data\"");
  ASSERT_NE(data, std::string::npos);
  const std::size_t data_end = page.find("</script>", data);
  ASSERT_NE(data_end, std::string::npos);
  const std::string block = page.substr(data, data_end - data);
  for (const char* key : {"\"total_ms\":[", "\"particle_uvw\":\"", "\"endpoint_uv\":\"",
                          "\"error_m\":[null]", "\"reference\":[]", "\"map\":{\"width\":"})
    EXPECT_NE(block.find(key), std::string::npos) << key;
  EXPECT_EQ(page.find("http"), std::string::npos);  // nothing fetched from the network
  EXPECT_EQ(page.substr(page.size() - 8), "</html>\n");

  // The map is cut to what the run visits: the robot at (5, 3) sees 2 m to its sides and ahead,
  // plus kViewerMarginM, so the 10 m wide room loses columns on both sides; the cells kept are
  // the map's own at their offset, and the estimate (given in cells of the whole map) is in them.
  const EmbeddedMap embedded = embedded_map(block);
  EXPECT_GT(embedded.u0, 0);
  EXPECT_LT(embedded.u0 + embedded.width, map.width());
  EXPECT_LE(embedded.width, 2 * (20 + 10 + 2));  // 2 m each side, 1 m margin, rounding
  ASSERT_EQ(embedded.cells.size(), static_cast<std::size_t>(embedded.width * embedded.height));
  for (int v = 0; v < embedded.height; ++v) {
    for (int u = 0; u < embedded.width; ++u) {
      ASSERT_EQ(embedded.cells[static_cast<std::size_t>(v * embedded.width + u)],
                static_cast<std::uint8_t>(map.at({embedded.u0 + u, embedded.v0 + v})))
          << "cell " << u << ", " << v << " of the embedded map";
    }
  }
  const Point2 estimate =
      FixedPointGrid(map).cells({result.trajectory[0].pose.x, result.trajectory[0].pose.y});
  EXPECT_GE(estimate.x, embedded.u0);
  EXPECT_LT(estimate.x, embedded.u0 + embedded.width);
  EXPECT_GE(estimate.y, embedded.v0);
  EXPECT_LT(estimate.y, embedded.v0 + embedded.height);
}

// What the page's state band, trajectory colours, misfit timeline and re-localization marks are
// drawn from: the state as the page's code (0 tracking, 1 uncertain, 2 lost), the misfit and the
// particles a re-localization added, apart from augmented MCL's injected ones, counts in full.
TEST(ViewerPage, CarriesStatesMisfitsAndReLocalizedCounts) {
  const OccupancyGrid map = room({-2.0, 1.0, 0.0});
  LocalizerConfig config;
  config.min_particles = config.max_particles = 100;
  config.threads = 1;
  config.lost_misfit = 0.7;
  Localizer filter(map, config);
  filter.initialize({3.0, 4.0, 0.0}, Eigen::Matrix3d::Identity() * 0.01);
  const logs::ScanFrame frame = frame_at_start();
  ASSERT_TRUE(filter.update(frame.odometry, frame.scan));
  ReplayResult result(map, config);
  ViewerRecorder recorder(map);
  const std::array states{LocalizationState::kLost, LocalizationState::kUncertain,
                          LocalizationState::kTracking};
  for (std::size_t k = 0; k < states.size(); ++k) {
    UpdateRecord update;
    update.stamp = static_cast<double>(k);
    update.state = states[k];
    update.misfit = 0.25 * static_cast<double>(k + 1);
    update.relocalized = k == 1 ? 1234567 : 0;  // more digits than the stream's precision
    update.injected = k == 2 ? 7 : 0;
    result.updates.push_back(update);
    result.trajectory.push_back({update.stamp, filter.estimate().best().mean});
    recorder.record(filter, frame);
  }
  std::ostringstream out;
  write_viewer_page(out, result, recorder.recording());
  const std::string page = out.str();
  for (const char* key :
       {"\"state\":[2,1,0]", "\"misfit\":[0.25,0.5,0.75]", "\"relocalized\":[0,1234567,0]",
        "\"injected\":[0,0,7]", "\"lost_misfit\":0.7,",
        "\"origin_x\":-2,\"origin_y\":1,\"origin_yaw\":0,"})
    EXPECT_NE(page.find(key), std::string::npos) << key;
}

}  // namespace
}  // namespace mote::replay
