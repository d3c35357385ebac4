// A crowd put into a recorded log (see crowd.hpp).
#include "mote/sim/crowd.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <span>
#include <string>
#include <system_error>
#include <utility>

#include "mote/core/error.hpp"
#include "mote/logs/carmen_writer.hpp"

namespace mote::sim {
namespace {

void check(const CrowdOptions& o) {
  if (!(o.seconds > 0.0)) throw ConfigError("crowd: seconds must be positive");
  if (o.people < 1) throw ConfigError("crowd: people must be at least 1");
  if (!(o.near_m > 0.0 && o.near_m <= o.far_m)) {
    throw ConfigError("crowd: distances must satisfy 0 < near <= far");
  }
  if (!(o.person_radius > 0.0)) throw ConfigError("crowd: person_radius must be positive");
}

struct Window {
  std::size_t first = 0;
  std::size_t last = 0;  // inclusive
};

// The frames in [start, start + seconds].
Window window_from(std::span<const logs::ScanFrame> f, double start, double seconds) {
  Window w;
  while (w.first < f.size() && f[w.first].stamp < start) ++w.first;
  if (w.first == f.size()) throw ConfigError("crowd: the log ends before the crowd's start");
  w.last = w.first;
  while (w.last + 1 < f.size() && f[w.last + 1].stamp <= start + seconds) ++w.last;
  return w;
}

// The window turning the most while travelling at most max_travel (two pointers over the
// odometry increments); when none travels so little, the one turning the most.
Window turning_window(std::span<const logs::ScanFrame> f, const CrowdOptions& o) {
  const auto step_turn = [&](std::size_t k) {
    return std::abs(between(f[k - 1].odometry, f[k].odometry).theta);
  };
  const auto step_travel = [&](std::size_t k) {
    const Pose2 d = between(f[k - 1].odometry, f[k].odometry);
    return std::hypot(d.x, d.y);
  };
  Window best{};
  Window best_any{};
  double best_turn = -1.0;
  double best_turn_any = -1.0;
  double turn = 0.0;
  double travel = 0.0;
  std::size_t last = 0;
  for (std::size_t first = 0; first < f.size(); ++first) {
    if (first > 0 && first <= last) {
      turn -= step_turn(first);
      travel -= step_travel(first);
    }
    if (last < first) last = first;
    while (last + 1 < f.size() && f[last + 1].stamp <= f[first].stamp + o.seconds) {
      ++last;
      turn += step_turn(last);
      travel += step_travel(last);
    }
    if (turn > best_turn_any) best_turn_any = turn, best_any = {first, last};
    if (travel <= o.max_travel_m && turn > best_turn) best_turn = turn, best = {first, last};
  }
  return best_turn >= 0.0 ? best : best_any;
}

struct Person {
  double x = 0.0;  // m, odometry frame
  double y = 0.0;
};

// A uniform double in [0, 1) from 53 bits of the generator (the same on every platform,
// unlike std::uniform_real_distribution).
double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11U) * 0x1.0p-53; }

std::vector<Person> ring(const Pose2& centre, const CrowdOptions& o) {
  std::mt19937_64 rng(o.seed);
  std::vector<Person> people;
  const double spacing = 2.0 * std::numbers::pi / o.people;
  for (int k = 0; k < o.people; ++k) {
    const double bearing = (k + 0.5 * (uniform(rng) - 0.5)) * spacing;
    const double distance = o.near_m + (o.far_m - o.near_m) * uniform(rng);
    people.push_back(
        {centre.x + distance * std::cos(bearing), centre.y + distance * std::sin(bearing)});
  }
  return people;
}

// Distance along the unit ray (o, u) to the circle (c, r), or +inf when it misses
// (the smaller root of |o + t u - c| = r with t > 0).
double ray_circle(double ox, double oy, double ux, double uy, const Person& c, double r) {
  const double dx = c.x - ox;
  const double dy = c.y - oy;
  const double along = dx * ux + dy * uy;
  const double across2 = dx * dx + dy * dy - along * along;
  if (along <= 0.0 || across2 > r * r) return std::numeric_limits<double>::infinity();
  return along - std::sqrt(r * r - across2);
}

// Shortens the beams of `frame` that hit a person; returns how many.
std::size_t block(logs::ScanFrame& frame, std::span<const Person> people, double radius) {
  const Pose2 laser = compose(frame.odometry, frame.scan.sensor_pose);
  std::size_t blocked = 0;
  for (std::size_t b = 0; b < frame.scan.size(); ++b) {
    const double a = laser.theta + frame.scan.beam_angle(b);
    double hit = std::numeric_limits<double>::infinity();
    for (const Person& p : people) {
      hit = std::min(hit, ray_circle(laser.x, laser.y, std::cos(a), std::sin(a), p, radius));
    }
    float& range = frame.scan.ranges[b];
    const bool valid = std::isfinite(range) && range < frame.scan.range_max;
    if (hit < frame.scan.range_max && (!valid || hit < range)) {
      range = static_cast<float>(hit);
      ++blocked;
    }
  }
  return blocked;
}

}  // namespace

CrowdedLog make_crowded_log(std::vector<logs::ScanFrame> frames, const CrowdOptions& options) {
  check(options);
  if (frames.empty()) throw ConfigError("crowd: the log has no scans");
  const Window w = std::isnan(options.start) ? turning_window(frames, options)
                                             : window_from(frames, options.start, options.seconds);
  const std::vector<Person> people = ring(frames[w.first].odometry, options);
  std::size_t blocked = 0;
  std::size_t beams = 0;
  for (std::size_t k = w.first; k <= w.last; ++k) {
    blocked += block(frames[k], people, options.person_radius);
    beams += frames[k].scan.size();
  }
  CrowdedLog out;
  out.start = frames[w.first].stamp;
  out.end = frames[w.last].stamp;
  out.crowded_scans = w.last - w.first + 1;
  out.blocked_fraction = beams > 0 ? static_cast<double>(blocked) / static_cast<double>(beams) : 0;
  out.frames = std::move(frames);
  return out;
}

CrowdedLog make_crowd_file(logs::ScanSource& source, const std::filesystem::path& out_dir,
                           const CrowdOptions& options) {
  std::vector<logs::ScanFrame> frames;
  while (auto f = source.next()) frames.push_back(std::move(*f));
  CrowdedLog out = make_crowded_log(std::move(frames), options);
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) throw Error(out_dir.string() + ": cannot create output folder: " + ec.message());
  logs::write_carmen_log(out_dir / "crowd.clf", out.frames);
  return out;
}

}  // namespace mote::sim
