// viewer.html: the page template (viewer_page_head.cpp, viewer_script.cpp) with the run embedded
// as one JSON object; the bulky columns (map cells, particles, endpoints) as base64 of arrays.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
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

// A finite number (with the stream's precision), else null.
void write_number(std::ostream& out, double v) {
  if (std::isfinite(v)) {
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

void write_map(std::ostream& out, const OccupancyGrid& map) {
  std::vector<std::uint8_t> cells(map.cell_count());
  for (std::size_t k = 0; k < cells.size(); ++k)
    cells[k] = static_cast<std::uint8_t>(map.cells()[k]);
  out << "\"map\":{\"width\":" << map.width() << ",\"height\":" << map.height()
      << ",\"resolution\":" << map.resolution() << ",\"cells\":";
  write_base64(out, cells);  // row 0 is the bottom (grid frame), CellState values
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
  write_array(out, "ess", n, [&](std::size_t k) { return u[k].effective_sample_size; });
  write_array(out, "injected", n,
              [&](std::size_t k) { return static_cast<double>(u[k].injected); });
  write_array(out, "tempering", n, [&](std::size_t k) { return u[k].tempering; });
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
  const FixedPointGrid grid(result.map);
  out << kViewerPageHead << "<script id=\"mote-data\" type=\"application/json\">{";
  out.precision(6);
  write_map(out, result.map);
  out << ",\"per_cell\":" << grid.per_cell() << ",\"threads\":" << result.threads << ",\"model\":";
  write_string(out, model_name(result.config.laser_model_type));
  out << ",\"t0\":";
  write_string(out, std::to_string(result.first_stamp));
  write_poses(out, "estimate", result.trajectory, result.map, result.first_stamp);
  write_poses(out, "reference", logs::sort_by_stamp(result.reference), result.map,
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
  out << "}</script>\n<script>\n" << kViewerScript << "</script>\n</body>\n</html>\n";
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
