// nav_msgs/OccupancyGrid both ways: mote's encoder against Cyclone's serialization of the idlc
// type, and the decoder on maps Cyclone serialized, well formed and not.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "idl_samples.hpp"
#include "mote/core/error.hpp"
#include "mote/ros/messages.hpp"
#include "nav_msgs.h"

namespace mote::ros::test {
namespace {

using Cells = std::vector<CellState>;
constexpr CellState F = CellState::kFree;
constexpr CellState O = CellState::kOccupied;
constexpr CellState U = CellState::kUnknown;

/// An idlc map sample: 5 x 3 cells of 0.05 m, its data pointing into `data`.
struct MapSample {
  Header header{{1733540004, 5000}, "map"};
  Pose2 origin{-1.0, 2.5, 0.3};
  std::vector<std::int8_t> data = {0, 100, -1, 0, 0, 100, 100, 50, 101, -128, 127, 0, 0, 1, 99};
  nav_msgs_msg_dds__OccupancyGrid_ s{};

  MapSample() { refresh(); }
  void refresh() {
    fill(s.header_, header);
    s.info_.map_load_time_ = {header.stamp.sec, header.stamp.nanosec};
    s.info_.resolution_ = 0.05F;
    s.info_.width_ = 5;
    s.info_.height_ = 3;
    s.info_.origin_ = idl_pose(origin);
    s.data_ = idl_sequence<dds_sequence_int8>(data);
  }
};

class OccupancyGridMessage : public CycloneTest {
 protected:
  CycloneChannel channel_{domain(), nav_msgs_msg_dds__OccupancyGrid__desc};

  /// The InputError decoding the Cyclone-serialized `sample` throws (fails when none).
  InputError rejection(MapSample& sample, std::uint64_t max_cells = kDefaultMaxMapCells) {
    const std::string bytes = channel_.serialize(&sample.s);
    try {
      (void)decode_occupancy_grid(bytes, "/map", max_cells);
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "/map");
      EXPECT_EQ(e.place().rfind("byte ", 0), 0U) << e.place();
      return e;
    }
    ADD_FAILURE() << "the map was accepted";
    return InputError("", "", "");
  }
};

TEST_F(OccupancyGridMessage, EncodesAsMapServerPublishes) {
  const OccupancyGrid grid(5, 3, 0.05, {-1.0, 2.5, 0.3},
                           Cells{F, O, U, F, F, O, O, U, U, U, U, F, F, U, U});
  MapSample sample;
  sample.data = {0, 100, -1, 0, 0, 100, 100, -1, -1, -1, -1, 0, 0, -1, -1};
  sample.refresh();
  const std::string ours = encode_occupancy_grid(sample.header, grid);
  expect_same_bytes(ours, channel_.serialize(&sample.s));
  channel_.decode(ours, [&](const void* p) {
    const auto& d = *static_cast<const nav_msgs_msg_dds__OccupancyGrid_*>(p);
    EXPECT_EQ(d.info_.width_, 5U);
    EXPECT_EQ(d.info_.resolution_, 0.05F);
    ASSERT_EQ(d.data_._length, 15U);
    EXPECT_EQ(std::vector<std::int8_t>(d.data_._buffer, d.data_._buffer + 15), sample.data);
  });
}

TEST_F(OccupancyGridMessage, DecodesAsAmclConvertsMaps) {
  MapSample sample;
  const auto map = decode_occupancy_grid(channel_.serialize(&sample.s), "/map");
  EXPECT_EQ(map.header.frame_id, "map");
  EXPECT_EQ(map.header.stamp, sample.header.stamp);
  EXPECT_EQ(map.map_load_time, sample.header.stamp);
  EXPECT_EQ(map.grid.width(), 5);
  EXPECT_EQ(map.grid.height(), 3);
  EXPECT_EQ(map.grid.resolution(), static_cast<double>(0.05F));
  EXPECT_EQ(map.grid.origin().x, -1.0);
  EXPECT_EQ(map.grid.origin().y, 2.5);
  EXPECT_NEAR(map.grid.origin().theta, 0.3, 1e-12);
  // 0 free, 100 occupied, everything else (scaled values, out of range) unknown; row 0 first.
  EXPECT_EQ(map.grid.cells(), (Cells{F, O, U, F, F, O, O, U, U, U, U, F, F, U, U}));
  EXPECT_EQ(map.grid.at({1, 0}), O);
  EXPECT_EQ(map.grid.at({1, 2}), F);
}

TEST_F(OccupancyGridMessage, RoundTripsThroughTheEncoder) {
  const OccupancyGrid grid(4, 2, 0.1, {3.0, -4.0, -2.5}, Cells{U, F, O, F, F, F, O, U});
  const auto map = decode_occupancy_grid(encode_occupancy_grid({{7, 8}, "world"}, grid), "/map");
  EXPECT_EQ(map.header.frame_id, "world");
  EXPECT_EQ(map.grid.cells(), grid.cells());
  EXPECT_EQ(map.grid.resolution(), static_cast<double>(0.1F));
  EXPECT_NEAR(map.grid.origin().theta, -2.5, 1e-12);
}

TEST_F(OccupancyGridMessage, RefusesEmptyGrids) {
  MapSample sample;
  sample.data.clear();
  sample.refresh();
  sample.s.info_.width_ = 0;
  // 4 + 8 (stamp) + 8 (frame id "map") + 8 (map_load_time) + 4 (resolution): width at 32.
  InputError e = rejection(sample);
  EXPECT_EQ(e.place(), "byte 32");
  EXPECT_NE(std::string(e.what()).find("0 x 3"), std::string::npos) << e.what();
  sample.s.info_.width_ = 5;
  sample.s.info_.height_ = 0;
  EXPECT_NE(std::string(rejection(sample).what()).find("at least one cell"), std::string::npos);
}

TEST_F(OccupancyGridMessage, RefusesBadResolutions) {
  for (const float res : {0.0F, -0.05F, NAN, INFINITY}) {
    MapSample sample;
    sample.s.info_.resolution_ = res;
    const InputError e = rejection(sample);
    EXPECT_EQ(e.place(), "byte 28");
    EXPECT_NE(std::string(e.what()).find("info.resolution"), std::string::npos) << e.what();
  }
}

TEST_F(OccupancyGridMessage, RefusesNonFiniteOrTiltedOrigins) {
  const std::vector<std::pair<std::function<void(geometry_msgs_msg_dds__Pose_&)>, const char*>>
      cases = {
          {[](auto& o) { o.position_.x_ = INFINITY; }, "info.origin.position.x"},
          {[](auto& o) { o.position_.z_ = NAN; }, "info.origin.position.z"},
          {[](auto& o) { o.orientation_.w_ = NAN; }, "info.origin.orientation.w"},
          {[](auto& o) {
             o.orientation_ = {0.0, 0.0, 0.0, 0.0};
           },
           "length 0"},
          {[](auto& o) {
             o.orientation_ = {0.0, 0.0, 1e300, 1e300};
           },
           "length inf"},
          // A roll of 0.1 rad: the grid would not lie in the xy plane.
          {[](auto& o) {
             o.orientation_ = {std::sin(0.05), 0.0, 0.0, std::cos(0.05)};
           },
           "roll"},
      };
  for (const auto& [change, expected] : cases) {
    MapSample sample;
    change(sample.s.info_.origin_);
    const InputError e = rejection(sample);
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
  MapSample rounded;  // a roll of 1e-9 rad, what rounding leaves in a quaternion from RPY
  rounded.s.info_.origin_.orientation_.x_ = 5e-10;
  EXPECT_NO_THROW((void)decode_occupancy_grid(channel_.serialize(&rounded.s), "/map"));
  MapSample unnormalized;  // a quaternion of another length is still a rotation about z
  for (double* c : {&unnormalized.s.info_.origin_.orientation_.z_,
                    &unnormalized.s.info_.origin_.orientation_.w_}) {
    *c *= 3.0;
  }
  const auto map = decode_occupancy_grid(channel_.serialize(&unnormalized.s), "/map");
  EXPECT_NEAR(map.grid.origin().theta, 0.3, 1e-12);
}

TEST_F(OccupancyGridMessage, RefusesDataOfTheWrongLength) {
  MapSample sample;
  sample.data.pop_back();
  sample.refresh();
  const InputError e = rejection(sample);
  EXPECT_NE(std::string(e.what()).find("expected info.width * info.height = 15 cells, got 14"),
            std::string::npos)
      << e.what();
}

TEST_F(OccupancyGridMessage, RefusesGridsAboveTheCellBoundBeforeReadingTheData) {
  MapSample sample;
  sample.data.clear();
  sample.refresh();
  sample.s.info_.width_ = 70000;
  sample.s.info_.height_ = 70000;  // 4.9e9 cells announced, none sent
  EXPECT_NE(std::string(rejection(sample).what()).find("more than the bound of 2147483648"),
            std::string::npos);
  // At the bound the size passes and the (missing) data is what is wrong.
  sample.s.info_.width_ = 65536;
  sample.s.info_.height_ = 32768;
  EXPECT_NE(std::string(rejection(sample).what()).find("got 0"), std::string::npos);
  // The bound is the caller's.
  MapSample small;
  EXPECT_NE(std::string(rejection(small, 14).what()).find("bound of 14"), std::string::npos);
  EXPECT_NO_THROW((void)decode_occupancy_grid(channel_.serialize(&small.s), "/map", 15));
}

TEST_F(OccupancyGridMessage, RefusesMalformedCdr) {
  MapSample sample;
  const std::string bytes = channel_.serialize(&sample.s);
  for (const std::string& bad :
       {bytes.substr(0, bytes.size() - 5), bytes.substr(0, 3), bytes + std::string(8, '\0'),
        std::string("\x00\x07\x00\x00", 4) + bytes.substr(4)}) {
    EXPECT_THROW((void)decode_occupancy_grid(bad, "/map"), InputError) << bad.size();
  }
}

}  // namespace
}  // namespace mote::ros::test
