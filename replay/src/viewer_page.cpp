// viewer.html: the page template (viewer_page_head.cpp, viewer_script.cpp) with the run embedded
// as one JSON object; the bulky columns (map cells, particles, endpoints) as base64 of arrays.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/replay/metrics.hpp"
#include "mote/replay/viewer.hpp"
#include "viewer_template.hpp"

namespace mote::replay {
namespace {

constexpr std::string_view kBase64 =
    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

// RFC 4648 base64 with padding, what the page's atob() decodes; written into a string of the
// final size (megabytes for a long log).
void write_base64(std::ostream& out, std::span<const std::uint8_t> bytes) {
  std::string text((bytes.size() + 2) / 3 * 4, '=');
  char* o = text.data();
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3, o += 4) {
    const unsigned v = (unsigned{bytes[i]} << 16U) | (unsigned{bytes[i + 1]} << 8U) | bytes[i + 2];
    o[0] = kBase64[v >> 18U];
    o[1] = kBase64[(v >> 12U) & 63U];
    o[2] = kBase64[(v >> 6U) & 63U];
    o[3] = kBase64[v & 63U];
  }
  if (i < bytes.size()) {  // one or two bytes left: "xx==" or "xxx="
    const bool two = i + 1 < bytes.size();
    const unsigned v = (unsigned{bytes[i]} << 16U) | (two ? unsigned{bytes[i + 1]} << 8U : 0U);
    o[0] = kBase64[v >> 18U];
    o[1] = kBase64[(v >> 12U) & 63U];
    if (two) o[2] = kBase64[(v >> 6U) & 63U];
  }
  out << '"' << text << '"';
}

// Unsigned integers as little-endian bytes, whatever the host's order (the page decodes them
// byte by byte).
template <typename T>
void write_le(std::ostream& out, std::span<const T> values) {
  std::vector<std::uint8_t> bytes(values.size() * sizeof(T));
  if constexpr (std::endian::native == std::endian::little) {
    if (!values.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
  } else {
    for (std::size_t k = 0; k < values.size(); ++k) {
      for (std::size_t b = 0; b < sizeof(T); ++b)
        bytes[k * sizeof(T) + b] = static_cast<std::uint8_t>((values[k] >> (8U * b)) & 0xFFU);
    }
  }
  write_base64(out, bytes);
}

// A finite number, else null: a whole number in full (a particle count of millions would lose
// digits to the stream's precision), any other with the stream's precision.
void write_number(std::ostream& out, double v) {
  constexpr double kExactInteger = 9.0e15;  // below 2^53: whole doubles are exact integers
  if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < kExactInteger) {
    out << static_cast<long long>(v);
  } else if (std::isfinite(v)) {
    out << v;
  } else {
    out << "null";
  }
}

template <typename F>
void write_array(std::ostream& out, std::string_view key, std::size_t n, F value) {
  out << ",\"" << key << "\":[";
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0) out << ',';
    write_number(out, value(k));
  }
  out << ']';
}

// JSON string contents with '<' escaped so that no "</script" can end the data block early.
void write_string(std::ostream& out, std::string_view text) {
  out << '"';
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out << '\\' << c;
    } else if (c == '<' || static_cast<unsigned char>(c) < 0x20) {
      constexpr std::string_view kHex = "0123456789abcdef";
      out << "\\u00" << kHex[(static_cast<unsigned char>(c) >> 4U) & 15U]
          << kHex[static_cast<unsigned char>(c) & 15U];
    } else {
      out << c;
    }
  }
  out << '"';
}

// Grid cells [u0, u1) x [v0, v1): the part of the map the page carries.
struct CellBox {
  int u0 = 0, v0 = 0, u1 = 0, v1 = 0;
};

// Grows a box of grid-frame cell coordinates point by point; non-finite points are left out.
class BoxGrower {
 public:
  void add(double u, double v) {
    if (!std::isfinite(u) || !std::isfinite(v)) return;
    lo_u_ = std::min(lo_u_, u);
    hi_u_ = std::max(hi_u_, u);
    lo_v_ = std::min(lo_v_, v);
    hi_v_ = std::max(hi_v_, v);
  }
  void add_fixed(std::span<const std::uint16_t> uv, std::size_t stride, double per_cell) {
    for (std::size_t k = 0; k + 1 < uv.size(); k += stride)
      add(uv[k] / per_cell, uv[k + 1] / per_cell);
  }
  // The box grown by `margin` cells, clamped to the map; the whole map when nothing was added
  // inside it.
  [[nodiscard]] CellBox cells(const OccupancyGrid& map, int margin) const {
    const CellBox whole{0, 0, map.width(), map.height()};
    if (!(lo_u_ <= hi_u_)) return whole;
    const auto clamp = [](double x, int hi) {
      return static_cast<int>(std::clamp(x, 0.0, static_cast<double>(hi)));
    };
    const CellBox b{clamp(std::floor(lo_u_) - margin, map.width()),
                    clamp(std::floor(lo_v_) - margin, map.height()),
                    clamp(std::ceil(hi_u_) + margin, map.width()),
                    clamp(std::ceil(hi_v_) + margin, map.height())};
    return b.u0 < b.u1 && b.v0 < b.v1 ? b : whole;
  }

 private:
  double lo_u_ = std::numeric_limits<double>::infinity(), lo_v_ = lo_u_;
  double hi_u_ = -lo_u_, hi_v_ = -lo_u_;
};

// The area the run visits: everything the page draws (estimate, reference, particles, scan
// endpoints, cluster means) with kViewerMarginM around it, at least the page's own 10-cell
// margin. A log covers a small part of a large map, whose every cell the page would otherwise
// carry (a 4000 x 4000 grid is 21 MB of base64).
CellBox visited_cells(const ReplayResult& result, const ViewerRecording& recording) {
  const FixedPointGrid grid(result.map());
  BoxGrower box;
  for (const auto* poses : {&result.trajectory, &result.reference}) {
    for (const logs::StampedPose& p : *poses) {
      const Point2 c = grid.cells({p.pose.x, p.pose.y});
      box.add(c.x, c.y);
    }
  }
  box.add_fixed(recording.particles, 3, grid.per_cell());
  box.add_fixed(recording.endpoints, 2, grid.per_cell());
  box.add_fixed(recording.heavy_clusters, 3, grid.per_cell());
  const int margin =
      std::max(10, static_cast<int>(std::ceil(kViewerMarginM / result.map().resolution())));
  return box.cells(result.map(), margin);
}

// The cells of `box`, row 0 its bottom row (grid frame), as CellState values; u0 and v0 place
// it in the map, in whose cells every position on the page is given.
void write_map(std::ostream& out, const OccupancyGrid& map, const CellBox& box) {
  const int width = box.u1 - box.u0, height = box.v1 - box.v0;
  std::vector<std::uint8_t> cells;
  cells.reserve(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (int v = box.v0; v < box.v1; ++v) {
    for (int u = box.u0; u < box.u1; ++u)
      cells.push_back(static_cast<std::uint8_t>(map.at({u, v})));
  }
  out << "\"map\":{\"width\":" << width << ",\"height\":" << height << ",\"u0\":" << box.u0
      << ",\"v0\":" << box.v0 << ",\"resolution\":" << map.resolution()
      << ",\"origin_x\":" << map.origin().x << ",\"origin_y\":" << map.origin().y
      << ",\"origin_yaw\":" << map.origin().theta << ",\"cells\":";
  write_base64(out, cells);
  out << '}';
}

// Poses as u, v in grid cells and the heading in the grid frame; stamps in s after t0.
void write_poses(std::ostream& out, std::string_view key, std::span<const logs::StampedPose> poses,
                 const OccupancyGrid& map, double t0) {
  const FixedPointGrid grid(map);
  out << ",\"" << key << "\":[";
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const Point2 c = grid.cells({poses[k].pose.x, poses[k].pose.y});
    out << (k > 0 ? "," : "");
    write_number(out, std::round(c.x * 100) / 100);
    out << ',';
    write_number(out, std::round(c.y * 100) / 100);
    out << ',';
    write_number(out, std::round((poses[k].pose.theta - map.origin().theta) * 1000) / 1000);
  }
  out << ']';
  const auto precision = out.precision(9);
  write_array(out, std::string(key) + "_t", poses.size(),
              [&](std::size_t k) { return poses[k].stamp - t0; });
  out.precision(precision);
}

// Position error of each update against the reference pose matched to its stamp (NaN: none).
std::vector<double> position_errors(const ReplayResult& result) {
  const std::vector<logs::StampedPose> reference = logs::sort_by_stamp(result.reference);
  std::vector<double> errors(result.trajectory.size(), std::nan(""));
  if (reference.empty()) return errors;
  const double tolerance = MetricOptions{}.match_tolerance_s;
  for (std::size_t k = 0; k < errors.size(); ++k) {
    const logs::StampedPose& e = result.trajectory[k];
    if (const auto match = logs::match_reference(reference, e.stamp, tolerance))
      errors[k] = std::hypot(e.pose.x - match->pose.x, e.pose.y - match->pose.y);
  }
  return errors;
}

// The page's code of a state: the index into its STATES table (viewer_script.cpp).
double state_code(LocalizationState state) {
  switch (state) {
    case LocalizationState::kTracking:
      return 0.0;
    case LocalizationState::kUncertain:
      return 1.0;
    case LocalizationState::kLost:
      return 2.0;
  }
  return 1.0;
}

void write_statistics(std::ostream& out, const ReplayResult& result) {
  const std::vector<UpdateRecord>& u = result.updates;
  const std::size_t n = u.size();
  write_array(out, "motion_ms", n, [&](std::size_t k) { return u[k].ms.motion; });
  write_array(out, "sensor_ms", n, [&](std::size_t k) { return u[k].ms.sensor; });
  write_array(out, "normalize_ms", n, [&](std::size_t k) { return u[k].ms.normalize; });
  write_array(out, "resample_ms", n, [&](std::size_t k) { return u[k].ms.resample; });
  write_array(out, "estimate_ms", n, [&](std::size_t k) { return u[k].ms.estimate; });
  write_array(out, "total_ms", n, [&](std::size_t k) { return u[k].ms.total; });
  write_array(out, "particles", n,
              [&](std::size_t k) { return static_cast<double>(u[k].particles); });
  write_array(out, "weighed", n, [&](std::size_t k) { return static_cast<double>(u[k].weighed); });
  write_array(out, "resampled", n, [&](std::size_t k) { return u[k].resampled ? 1.0 : 0.0; });
  write_array(out, "ess", n, [&](std::size_t k) { return u[k].effective_sample_size; });
  write_array(out, "injected", n,
              [&](std::size_t k) { return static_cast<double>(u[k].injected); });
  write_array(out, "relocalized", n,
              [&](std::size_t k) { return static_cast<double>(u[k].relocalized); });
  write_array(out, "tempering", n, [&](std::size_t k) { return u[k].tempering; });
  write_array(out, "state", n, [&](std::size_t k) { return state_code(u[k].state); });
  write_array(out, "misfit", n, [&](std::size_t k) { return u[k].misfit; });
  write_array(out, "lost_bound", n, [&](std::size_t k) { return u[k].lost_bound; });
  const std::vector<double> errors = position_errors(result);
  write_array(out, "error_m", n, [&](std::size_t k) { return errors[k]; });
}

void check_recording(const ReplayResult& result, const ViewerRecording& recording) {
  const std::size_t n = result.updates.size();
  if (result.trajectory.size() != n || recording.particle_end.size() != n ||
      recording.endpoint_end.size() != n || recording.clusters.size() != n ||
      recording.heavy_cluster_end.size() != n) {
    throw Error("viewer: the recording holds " + std::to_string(recording.particle_end.size()) +
                " updates, the run " + std::to_string(n) + "; expected one entry per update");
  }
}

}  // namespace

void write_viewer_page(std::ostream& out, const ReplayResult& result,
                       const ViewerRecording& recording) {
  check_recording(result, recording);
  const FixedPointGrid grid(result.map());
  out << kViewerPageHead << "<script id=\"mote-data\" type=\"application/json\">{";
  out.precision(6);
  write_map(out, result.map(), visited_cells(result, recording));
  out << ",\"per_cell\":" << grid.per_cell() << ",\"threads\":" << result.threads
      << ",\"lost_misfit\":" << result.config.lost_misfit << ",\"model\":";
  write_string(out, model_name(result.config.laser_model_type));
  out << ",\"t0\":";
  write_string(out, std::to_string(result.first_stamp));
  write_poses(out, "estimate", result.trajectory, result.map(), result.first_stamp);
  write_poses(out, "reference", logs::sort_by_stamp(result.reference), result.map(),
              result.first_stamp);
  write_statistics(out, result);
  write_array(out, "clusters", recording.clusters.size(),
              [&](std::size_t k) { return static_cast<double>(recording.clusters[k]); });
  out << ",\"particle_end\":";
  write_le<std::uint32_t>(out, recording.particle_end);
  out << ",\"particle_uvw\":";
  write_le<std::uint16_t>(out, recording.particles);
  out << ",\"endpoint_end\":";
  write_le<std::uint32_t>(out, recording.endpoint_end);
  out << ",\"endpoint_uv\":";
  write_le<std::uint16_t>(out, recording.endpoints);
  out << ",\"cluster_end\":";
  write_le<std::uint32_t>(out, recording.heavy_cluster_end);
  out << ",\"cluster_uvw\":";
  write_le<std::uint16_t>(out, recording.heavy_clusters);
  out << "}</script>\n<script>\n";
  for (const std::string_view part : viewer_script_parts()) out << part;
  out << "</script>\n</body>\n</html>\n";
}

void write_viewer_html(const std::filesystem::path& path, const ReplayResult& result,
                       const ViewerRecording& recording) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw Error(path.string() + ": cannot open for writing");
  write_viewer_page(out, result, recording);
  out.close();
  if (!out) throw Error(path.string() + ": cannot write the viewer page");
}

}  // namespace mote::replay
