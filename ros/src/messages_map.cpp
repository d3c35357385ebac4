/// \file
/// nav_msgs/OccupancyGrid both ways: encoded as nav2's map_server publishes a map, decoded as
/// nav2_amcl's convertMap reads one (amcl_node.cpp: 0 free, 100 occupied, anything else
/// unknown), with every size checked before the cells are allocated.

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstddef>

#include "cdr.hpp"
#include "message_fields.hpp"
#include "mote/core/error.hpp"
#include "mote/core/huge_pages.hpp"
#include "mote/logs/tum.hpp"

namespace mote::ros {
namespace {

using logs::detail::BagDecodeError;
using logs::detail::CdrReader;

// map_server's trinary values (nav2_map_server map_io.cpp).
constexpr std::int8_t kOccupied = 100;
constexpr std::int8_t kFree = 0;
constexpr std::int8_t kUnknown = -1;

// The largest tilt of the map plane (rad) still taken as planar: rounding in a quaternion built
// from roll = pitch = 0 stays far below it, a map meant to be tilted far above.
constexpr double kMaxTilt = 1e-3;

std::int8_t trinary(CellState s) {
  switch (s) {
    case CellState::kOccupied:
      return kOccupied;
    case CellState::kFree:
      return kFree;
    case CellState::kUnknown:
      break;
  }
  return kUnknown;
}

CellState from_trinary(char value) {
  if (value == kFree) return CellState::kFree;
  if (value == kOccupied) return CellState::kOccupied;
  return CellState::kUnknown;
}

Stamp read_stamp(CdrReader& r, const char* sec, const char* nanosec) {
  Stamp s;
  s.sec = r.i32(sec);
  s.nanosec = r.u32(nanosec);
  return s;
}

double finite_f64(CdrReader& r, const char* what) {
  const std::size_t at = r.position();
  const double v = r.f64(what);
  if (!std::isfinite(v)) throw BagDecodeError{at, std::string(what) + ": expected a finite number"};
  return v;
}

/// info.origin: a finite pose whose rotation keeps the grid in the xy plane.
Pose2 read_origin(CdrReader& r) {
  Pose2 origin;
  origin.x = finite_f64(r, "info.origin.position.x");
  origin.y = finite_f64(r, "info.origin.position.y");
  (void)finite_f64(r, "info.origin.position.z");
  const std::size_t at = r.position();
  const double qx = finite_f64(r, "info.origin.orientation.x");
  const double qy = finite_f64(r, "info.origin.orientation.y");
  const double qz = finite_f64(r, "info.origin.orientation.z");
  const double qw = finite_f64(r, "info.origin.orientation.w");
  const double norm2 = qx * qx + qy * qy + qz * qz + qw * qw;
  // Any length in between is taken as the same rotation (a quaternion is read up to scale).
  if (!(norm2 > 1e-12) || !std::isfinite(norm2)) {
    throw BagDecodeError{at,
                         "info.origin.orientation: expected a unit quaternion, got one of "
                         "length " +
                             std::to_string(std::sqrt(norm2))};
  }
  // (qx^2 + qy^2) / |q|^2 is sin^2 of half the angle between the grid's normal and z.
  const double max_tilt = std::sin(0.5 * kMaxTilt);
  if ((qx * qx + qy * qy) / norm2 > max_tilt * max_tilt) {
    throw BagDecodeError{at,
                         "info.origin.orientation: expected a rotation about z only (a 2D "
                         "map in the xy plane), got roll or pitch"};
  }
  // yaw_from_quaternion expects a unit quaternion.
  const double norm = std::sqrt(norm2);
  origin.theta = logs::yaw_from_quaternion(qx / norm, qy / norm, qz / norm, qw / norm);
  return origin;
}

struct GridSize {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  [[nodiscard]] std::uint64_t cells() const { return std::uint64_t{width} * height; }
};

GridSize read_size(CdrReader& r, std::uint64_t max_cells) {
  // OccupancyGrid indexes its cells with uint32 whatever the caller allows.
  max_cells = std::min<std::uint64_t>(max_cells, 0xFFFFFFFFULL);
  const std::size_t at = r.position();
  GridSize s;
  s.width = r.u32("info.width");
  s.height = r.u32("info.height");
  const std::string dims = std::to_string(s.width) + " x " + std::to_string(s.height);
  if (s.width == 0 || s.height == 0) {
    throw BagDecodeError{at, "info.width, info.height: expected at least one cell, got " + dims};
  }
  if (s.width > INT_MAX || s.height > INT_MAX || s.cells() > max_cells) {
    throw BagDecodeError{at, "info.width, info.height: " + dims + " = " +
                                 std::to_string(s.cells()) + " cells, more than the bound of " +
                                 std::to_string(max_cells)};
  }
  return s;
}

double read_resolution(CdrReader& r) {
  const std::size_t at = r.position();
  const float res = r.f32("info.resolution");
  if (!(std::isfinite(res) && res > 0.0F)) {
    throw BagDecodeError{at, "info.resolution: expected a finite number of metres above 0, got " +
                                 std::to_string(res)};
  }
  return static_cast<double>(res);
}

/// The cells of `data`, after checking its length against the grid.
std::vector<CellState> read_cells(CdrReader& r, std::string_view bytes, GridSize size) {
  const std::size_t at = r.position();
  const std::uint32_t n = r.sequence("data", 0);
  if (n != size.cells()) {
    throw BagDecodeError{at, "data: expected info.width * info.height = " +
                                 std::to_string(size.cells()) + " cells, got " + std::to_string(n)};
  }
  const std::size_t first = r.position();
  r.skip(n, 1, "data");
  std::vector<CellState> cells;
  huge_pages::reserve(cells, n);  // a big map's cells on 2 MB pages (huge_pages.hpp says why)
  cells.resize(n);
  for (std::size_t k = 0; k < cells.size(); ++k) cells[k] = from_trinary(bytes[first + k]);
  return cells;
}

MapMessage read_map(std::string_view bytes, std::uint64_t max_cells) {
  CdrReader r(bytes);
  Header header;
  header.stamp = read_stamp(r, "header.stamp.sec", "header.stamp.nanosec");
  header.frame_id = std::string(r.string("header.frame_id"));
  const Stamp load_time = read_stamp(r, "info.map_load_time.sec", "info.map_load_time.nanosec");
  const double resolution = read_resolution(r);
  const GridSize size = read_size(r, max_cells);
  const Pose2 origin = read_origin(r);
  std::vector<CellState> cells = read_cells(r, bytes, size);
  r.expect_end("OccupancyGrid");
  return {std::move(header), load_time,
          OccupancyGrid(static_cast<int>(size.width), static_cast<int>(size.height), resolution,
                        origin, std::move(cells))};
}

}  // namespace

std::string encode_occupancy_grid(const Header& header, const OccupancyGrid& grid) {
  detail::CdrWriter w;
  w.reserve(grid.cell_count() + 128);
  detail::write_header(w, header);
  detail::write_stamp(w, header.stamp);  // info.map_load_time
  w.f32(static_cast<float>(grid.resolution()));
  w.u32(static_cast<std::uint32_t>(grid.width()));
  w.u32(static_cast<std::uint32_t>(grid.height()));
  detail::write_planar_pose(w, grid.origin());
  const std::vector<CellState>& cells = grid.cells();
  w.i8_sequence(cells.size(), [&](std::size_t k) { return trinary(cells[k]); });
  return std::move(w).finish();
}

MapMessage decode_occupancy_grid(std::string_view bytes, std::string_view topic,
                                 std::uint64_t max_cells) {
  try {
    return read_map(bytes, max_cells);
  } catch (const BagDecodeError& e) {
    throw InputError(std::string(topic), "byte " + std::to_string(e.offset),
                     "nav_msgs/msg/OccupancyGrid: " + e.problem);
  }
}

}  // namespace mote::ros
