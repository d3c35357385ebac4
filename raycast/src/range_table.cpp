#include "mote/raycast/range_table.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "embree_packets.hpp"
#include "grid_walk.hpp"
#include "mote/core/error.hpp"
#include "mote/core/parallel.hpp"
#include "range_table_certify.hpp"
#include "range_table_layout.hpp"
#include "range_table_sweep.hpp"
#include "ray_setup.hpp"
#include "wall_scene.hpp"

namespace mote {

namespace {

constexpr int kAngleGroup = 32;  // uint16 entries per 64-byte line: one build task's directions
constexpr int kMaxLattice = 32;
constexpr double kMaxUnitsPerCell = 16.0;
/// Certified entries vouch for their rays to about this many cells (second differences and
/// neighbour disagreements up to it): 2 was the largest that kept 99 % of the rays of the Intel,
/// Willow and Stata basement maps within one cell of exact casting (BENCHMARKS.md).
constexpr double kCertifyTolerance = 2.0;

void check_options(const RangeTableOptions& o) {
  if (o.angles < kAngleGroup || o.angles % kAngleGroup != 0) {
    throw ConfigError("range table: angles must be a positive multiple of 32, got " +
                      std::to_string(o.angles));
  }
}

std::string megabytes(std::size_t bytes) {
  return std::to_string((bytes + (std::size_t{1} << 20U) - 1) >> 20U) + " MB";
}

/// The finest lattice whose table, with `fixed` bytes beside it, fits the budget; ConfigError
/// naming the coarsest's size.
int choose_lattice(const detail::CellMask& mask, const RangeTableOptions& o, std::size_t fixed) {
  std::size_t needed = 0;
  const std::size_t cells =
      static_cast<std::size_t>(mask.width) * static_cast<std::size_t>(mask.height);
  for (int lattice = 1; lattice <= kMaxLattice; ++lattice) {
    const auto blocks = static_cast<std::size_t>((mask.width + lattice - 1) / lattice) *
                        static_cast<std::size_t>((mask.height + lattice - 1) / lattice);
    // Every block holding a point is an upper bound; count exactly only when it matters.
    if (detail::table_bytes(blocks, blocks, cells, o.angles) + fixed <= o.memory_budget_bytes) {
      return lattice;
    }
    needed = fixed + detail::table_bytes(detail::count_lattice_points(mask, lattice), blocks, cells,
                                         o.angles);
    if (needed <= o.memory_budget_bytes) return lattice;
  }
  throw ConfigError("range table: a memory budget of " + megabytes(o.memory_budget_bytes) +
                    " holds no table of this map at " + std::to_string(o.angles) +
                    " angles; the coarsest lattice (" + std::to_string(kMaxLattice) +
                    " cells) needs " + megabytes(needed));
}

/// Fixed-point units per cell: as fine as 16 bits allow for the map's diagonal, at most 1/16.
double units_for(int width, int height) {
  const double diagonal = std::hypot(double(width), double(height)) + 2.0;
  const double units =
      std::min(kMaxUnitsPerCell, std::floor(double(detail::kNoHit - 1) / diagonal));
  if (units < 1.0) {
    throw ConfigError("range table: the map is too large for 16-bit ranges (diagonal " +
                      std::to_string(diagonal) + " cells, at most 65534)");
  }
  return units;
}

/// Lattice points near a sensor and their offsets from it (cells). Always nine entries, so the
/// choice among them is a fixed, branch-free loop; entry 0 is the sensor's own block and
/// missing neighbours carry a mask of all ones below the sign bit that keeps them from being
/// chosen (and keeps every key below 2^31, where signed and unsigned minima agree).
inline constexpr std::uint32_t kMissing = 0x7FFFFFFFU;

/// What RangeTable::Impl::read gives for an uncertified entry: no range, cast the ray exactly.
inline constexpr float kCastExactly = -1.0F;
/// What RangeTable::Impl::units_at gives for a ray that leaves the map without a hit.
inline constexpr float kLeavesMap = std::numeric_limits<float>::infinity();

struct Candidates {
  static constexpr std::size_t kCount = 9;
  std::array<std::uint32_t, kCount> slot{};
  std::array<float, kCount> wx{};
  std::array<float, kCount> wy{};
  std::array<std::uint32_t, kCount> missing{};
};

/// The entries a lookup reads: the entry of the chosen lattice point and the sensor's own, and
/// the offset along the ray (cells) from the sensor to each point. Chosen for all the beams of
/// a sensor before any is read, so that the choice (the lookup's cost) runs on vector lanes.
struct Choice {
  std::size_t entry = 0;      ///< at the table angle below the ray's
  std::size_t own_entry = 0;  ///< the sensor's own point, same angle
  float along = 0.0F;
  float own_along = 0.0F;
  float frac = 0.0F;        ///< where the ray's angle lies between entry's angle and the next (0-1)
  std::ptrdiff_t next = 1;  ///< entry + next: the next table angle (wraps at the row's end)
};

/// Per-beam working arrays of RangeTable::Impl::choose, reused across the sensors of one task.
struct BeamScratch {
  explicit BeamScratch(std::size_t beams)
      : angle(beams), frac(beams), dx(beams), dy(beams), key(beams) {}
  std::vector<std::uint32_t> angle;  ///< table angle below the ray's
  std::vector<float> frac;           ///< the ray's angle past it, in steps (0-1)
  std::vector<float> dx;             ///< its direction
  std::vector<float> dy;
  std::vector<std::int32_t> key;  ///< the running minimum of the candidates' keys
};

}  // namespace

struct RangeTable::Impl {
  int width = 0;
  int height = 0;
  float resolution = 1.0F;
  Pose2 origin;
  RangeTableOptions options;
  std::vector<std::uint8_t> blocking;
  /// The exact caster's scene, for the rays of uncertified entries.
  std::unique_ptr<detail::WallScene> walls;
  detail::TableLayout layout;
  std::vector<std::uint16_t> ranges;  ///< ranges[slot * angles + a]
  std::vector<float> cos_a;           ///< direction of table angle a in the grid frame
  std::vector<float> sin_a;
  std::vector<float> point_x;  ///< lattice point of each slot, in cells
  std::vector<float> point_y;
  RangeTableStats stats;

  [[nodiscard]] detail::CellMask mask() const noexcept {
    return {width, height, resolution, blocking.data()};
  }
  void build();
  /// The lattice points of the sensor's block and its 8 neighbours, for a sensor at grid frame
  /// point (gx, gy) m in on-map cell (i, j).
  [[nodiscard]] Candidates candidates(int i, int j, double gx, double gy) const noexcept;
  /// Which entries answer for each beam of one sensor, at table angle index
  /// heading + beam_index[b] (fractional, in [0, 2 * angles)).
  void choose(const Candidates& c, double heading, std::span<const double> beam_index,
              BeamScratch& scratch, std::span<Choice> choices) const noexcept;
  /// The range (table units) entry reads at choice's angle, kLeavesMap or kCastExactly.
  [[nodiscard]] [[gnu::always_inline]] inline float units_at(std::size_t entry,
                                                             const Choice& choice) const noexcept;
  /// The range (m) that choice reads, or kCastExactly.
  [[nodiscard]] [[gnu::always_inline]] inline float read(const Choice& choice,
                                                         float max_range) const noexcept;
  [[nodiscard]] float cast_ray(const detail::GridRay& ray, double angle, float max_range) const;
  /// Casts particles [begin, end) of a batch; rays of uncertified entries go to `exact` (a
  /// Packet16), or nowhere when the table is not certified.
  template <class Wrap, class Exact>
  void cast_chunk(const detail::BatchRays& rays, const detail::CellMask& m,
                  std::span<const double> beam_index, const Wrap& wrap, std::size_t begin,
                  std::size_t end, std::span<float> out_ranges, Exact* exact) const;
  /// cast_chunk with the exact caster: rays of uncertified entries, queued in particle order
  /// within the chunk, so which rays share a packet depends on the grain only (design.md 3).
  template <class Wrap>
  void cast_chunk_certified(const detail::BatchRays& rays, const detail::CellMask& m,
                            std::span<const double> beam_index, const Wrap& wrap, std::size_t begin,
                            std::size_t end, std::span<float> out_ranges) const {
    const detail::FlushDenormals denormals_off;
    detail::Packet16 exact(walls->scene(), rays.max_range(), out_ranges);
    cast_chunk(rays, m, beam_index, wrap, begin, end, out_ranges, &exact);
    exact.flush();
    detail::check_embree_thread("casting rays");
  }
};

void RangeTable::Impl::build() {
  const auto start = std::chrono::steady_clock::now();
  const detail::CellMask m = mask();
  if (options.certify) walls = std::make_unique<detail::WallScene>(m);
  const std::size_t scene_bytes = walls ? walls->bytes() : 0;
  layout = detail::make_layout(m, choose_lattice(m, options, scene_bytes));
  const std::size_t points = layout.points();
  const auto angles = static_cast<std::size_t>(options.angles);
  const double units = units_for(width, height);
  for (std::size_t a = 0; a < angles; ++a) {
    const double phi =
        2.0 * std::numbers::pi * static_cast<double>(a) / static_cast<double>(angles);
    cos_a.push_back(static_cast<float>(detail::snap_direction(std::cos(phi))));
    sin_a.push_back(static_cast<float>(detail::snap_direction(std::sin(phi))));
  }
  for (const std::uint32_t cell : layout.cell_of_slot) {
    point_x.push_back(static_cast<float>(cell % static_cast<std::uint32_t>(width)) + 0.5F);
    point_y.push_back(static_cast<float>(cell / static_cast<std::uint32_t>(width)) + 0.5F);
  }
  ranges.assign(points * angles, detail::kNoHit);
  // One task per 32 directions: each fills a column per direction, then writes its own run of
  // 32 entries (64 bytes) in every point's row, so tasks write disjoint entries, share at most
  // the cache lines where their runs meet, and the result is the same for any thread count.
  par::for_each_chunk(angles, kAngleGroup, [&](std::size_t begin, std::size_t end) {
    std::vector<std::uint16_t> columns((end - begin) * points);
    detail::SweepScratch scratch;
    for (std::size_t a = begin; a < end; ++a) {
      detail::sweep_direction(m, point_x, point_y, layout.lattice, cos_a[a], sin_a[a], units,
                              scratch, {columns.data() + (a - begin) * points, points});
    }
    for (std::size_t p = 0; p < points; ++p) {
      for (std::size_t a = begin; a < end; ++a) {
        ranges[p * angles + a] = columns[(a - begin) * points + p];
      }
    }
  });
  std::size_t uncertified = 0;
  if (options.certify) {
    detail::certify({layout, point_x, point_y, cos_a, sin_a, units, kCertifyTolerance}, ranges);
    uncertified =
        static_cast<std::size_t>(std::count_if(ranges.begin(), ranges.end(), [](std::uint16_t v) {
          return (v & detail::kUncertified) != 0;
        }));
  }
  stats = {.angles = options.angles,
           .lattice = layout.lattice,
           .points = points,
           .bytes = detail::table_bytes(points, layout.slot_of_block.size(), blocking.size(),
                                        options.angles) +
                    scene_bytes,
           .build_seconds =
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
           .units_per_cell = units,
           .uncertified =
               points == 0 ? 0.0
                           : static_cast<double>(uncertified) / static_cast<double>(ranges.size())};
}

Candidates RangeTable::Impl::candidates(int i, int j, double gx, double gy) const noexcept {
  Candidates c;
  c.missing.fill(kMissing);
  const int bi = i / layout.lattice;
  const int bj = j / layout.lattice;
  const auto ox = static_cast<float>(gx / resolution);
  const auto oy = static_cast<float>(gy / resolution);
  std::size_t k = 1;
  for (int nj = bj - 1; nj <= bj + 1; ++nj) {
    for (int ni = bi - 1; ni <= bi + 1; ++ni) {
      if (ni < 0 || nj < 0 || ni >= layout.blocks_w || nj >= layout.blocks_h) continue;
      const std::uint32_t slot =
          layout.slot_of_block[static_cast<std::size_t>(nj) *
                                   static_cast<std::size_t>(layout.blocks_w) +
                               static_cast<std::size_t>(ni)];
      if (slot == detail::kNoSlot) continue;
      const std::size_t at = ni == bi && nj == bj ? 0 : k++;
      c.slot[at] = slot;
      c.wx[at] = point_x[slot] - ox;
      c.wy[at] = point_y[slot] - oy;
      c.missing[at] = 0;
    }
  }
  return c;
}

/// The table angle nearest to index a_real, which callers keep in [0, 2 * n); anything else
/// finite (an index wrapped with a rounding error, or a huge angle whose wrap lost precision)
/// is reduced first, so the cast below never sees a value out of int's range.
inline std::size_t nearest_angle(double a_real, int n) noexcept {
  if (!(a_real >= 0.0 && a_real < 2.0 * n)) {
    a_real = std::fmod(a_real, static_cast<double>(n));
    if (a_real < 0.0) a_real += n;
    if (!(a_real >= 0.0 && a_real < n)) a_real = 0.0;  // NaN: callers never pass one
  }
  int a = static_cast<int>(a_real + 0.5);
  if (a >= n) a -= n;
  if (a >= n) a -= n;
  return static_cast<std::size_t>(a);
}

/// The table angle at or below index a_real, and a_real's distance past it (steps, in [0, 1)).
/// Callers keep a_real in [0, 2 * n); anything else finite (an index wrapped with a rounding
/// error, or a huge angle whose wrap lost precision) is reduced first, so the cast below never
/// sees a value out of int's range.
inline std::size_t angle_below(double a_real, int n, float& frac) noexcept {
  if (!(a_real >= 0.0 && a_real < 2.0 * n)) {
    a_real = std::fmod(a_real, static_cast<double>(n));
    if (a_real < 0.0) a_real += n;
    if (!(a_real >= 0.0 && a_real < n)) a_real = 0.0;  // NaN: callers never pass one
  }
  int a = static_cast<int>(a_real);
  frac = std::clamp(static_cast<float>(a_real - a), 0.0F, 1.0F);
  if (a >= n) a -= n;
  if (a >= n) a -= n;
  return static_cast<std::size_t>(a);
}

void RangeTable::Impl::choose(const Candidates& c, double heading,
                              std::span<const double> beam_index, BeamScratch& scratch,
                              std::span<Choice> choices) const noexcept {
  const std::size_t beams = beam_index.size();
  const int n = options.angles;
  std::uint32_t* angle = scratch.angle.data();
  float* frac = scratch.frac.data();
  float* dx = scratch.dx.data();
  float* dy = scratch.dy.data();
  std::int32_t* key = scratch.key.data();
  // Without certification the nearest direction alone answers (frac 0): interpolating across a
  // jump between two directions gives a range neither holds (measured: 90.5 % within a cell on
  // Intel against 91.5 %); certified entries have no jump to either neighbour.
  for (std::size_t b = 0; b < beams; ++b) {
    if (options.certify) {
      angle[b] = static_cast<std::uint32_t>(angle_below(heading + beam_index[b], n, frac[b]));
    } else {
      angle[b] = static_cast<std::uint32_t>(nearest_angle(heading + beam_index[b], n));
      frac[b] = 0.0F;
    }
    // The nearer of the two table directions chooses the lattice point.
    const std::uint32_t near =
        frac[b] < 0.5F ? angle[b] : (angle[b] + 1 == unsigned(n) ? 0 : angle[b] + 1);
    dx[b] = cos_a[near];
    dy[b] = sin_a[near];
    key[b] = static_cast<std::int32_t>(kMissing);
  }
  // The lattice point whose ray along this direction passes closest to the sensor stands for it:
  // its range, moved along the ray by its offset, is the sensor's (sideways offsets are what a
  // table cannot correct: they change which wall corner a ray grazes).
  // The argmin as a min over keys: the lateral offset's bits (a non-negative float orders as
  // its bits) with the index in the 4 lowest; ties within 2^-19 of each other go to the lower
  // index, the sensor's own point first. Candidate by candidate, so that the inner loop over
  // beams has no dependence between iterations and runs on vector lanes (signed minima: every
  // key is below 2^31).
  for (std::size_t k = 0; k < Candidates::kCount; ++k) {
    const float wx = c.wx[k];
    const float wy = c.wy[k];
    const auto tag = static_cast<std::int32_t>(static_cast<std::uint32_t>(k) | c.missing[k]);
    for (std::size_t b = 0; b < beams; ++b) {
      const float lateral = std::abs(dx[b] * wy - dy[b] * wx);
      key[b] = std::min(key[b], (std::bit_cast<std::int32_t>(lateral) & ~0xF) | tag);
    }
  }
  for (std::size_t b = 0; b < beams; ++b) {
    const auto best = static_cast<std::size_t>(key[b] & 0xF);
    const std::size_t row = static_cast<std::size_t>(n);
    choices[b] = {static_cast<std::size_t>(c.slot[best]) * row + angle[b],
                  static_cast<std::size_t>(c.slot[0]) * row + angle[b],
                  dx[b] * c.wx[best] + dy[b] * c.wy[best],
                  dx[b] * c.wx[0] + dy[b] * c.wy[0],
                  frac[b],
                  angle[b] + 1 == static_cast<std::uint32_t>(n) ? 1 - n : 1};
  }
}

inline float RangeTable::Impl::units_at(std::size_t entry, const Choice& choice) const noexcept {
  const std::uint16_t raw = ranges[entry];
  if ((raw & detail::kUncertified) != 0) return kCastExactly;
  const auto v0 = static_cast<std::uint16_t>(raw & detail::kNoHit);
  const auto v1 = static_cast<std::uint16_t>(
      ranges[static_cast<std::size_t>(static_cast<std::ptrdiff_t>(entry) + choice.next)] &
      detail::kNoHit);
  // Linear in angle between the two table directions around the ray (a slanted wall's range
  // changes smoothly); a ray that leaves the map at either reads the nearer one.
  if (v0 != detail::kNoHit && v1 != detail::kNoHit) {
    return static_cast<float>(v0) + choice.frac * (static_cast<float>(v1) - static_cast<float>(v0));
  }
  const std::uint16_t nearer = choice.frac < 0.5F ? v0 : v1;
  return nearer == detail::kNoHit ? kLeavesMap : static_cast<float>(nearer);
}

inline float RangeTable::Impl::read(const Choice& choice, float max_range) const noexcept {
  const float inv_units = 1.0F / static_cast<float>(stats.units_per_cell);
  if (!options.certify) {
    // The nearest direction's entry alone (frac is 0): one read, as fast as it was.
    std::uint16_t v = ranges[choice.entry];
    float along = choice.along;
    if (v != detail::kNoHit && static_cast<float>(v) * inv_units + along < 0.0F) {
      // The neighbour's wall lies behind the sensor: fall back to the sensor's own point.
      v = ranges[choice.own_entry];
      along = choice.own_along;
    }
    if (v == detail::kNoHit) return max_range;
    return std::clamp((static_cast<float>(v) * inv_units + along) * resolution, 0.0F, max_range);
  }
  float v = units_at(choice.entry, choice);
  float along = choice.along;
  if (v >= 0.0F && v != kLeavesMap && v * inv_units + along < 0.0F) {
    // The neighbour's wall lies behind the sensor: fall back to the sensor's own point.
    v = units_at(choice.own_entry, choice);
    along = choice.own_along;
  }
  if (v == kCastExactly) return kCastExactly;
  if (v == kLeavesMap) return max_range;
  return std::clamp((v * inv_units + along) * resolution, 0.0F, max_range);
}

float RangeTable::Impl::cast_ray(const detail::GridRay& grid_ray, double angle,
                                 float max_range) const {
  const detail::CellMask m = mask();
  const detail::GridRay ray = m.prepare(grid_ray);
  if (m.blocks_start(ray.ox, ray.oy)) return 0.0F;
  const int i = m.cell_of(ray.ox, width);
  const int j = m.cell_of(ray.oy, height);
  if (i < 0 || j < 0 || i >= width || j >= height) return detail::walk_grid(m, ray, max_range);
  const double n = options.angles;
  double a_real = angle * n / (2.0 * std::numbers::pi);
  a_real -= n * std::floor(a_real / n);
  const double beam = 0.0;
  BeamScratch scratch(1);
  Choice choice;
  choose(candidates(i, j, ray.ox, ray.oy), a_real, {&beam, 1}, scratch, {&choice, 1});
  const float range = read(choice, max_range);
  if (range != kCastExactly) return range;
  const detail::FlushDenormals denormals_off;
  float exact = max_range;
  detail::Single1 query(walls->scene(), max_range, std::span<float>(&exact, 1));
  query.add(ray, 0);
  detail::check_embree_thread("casting a ray");
  return exact;
}

template <class Wrap, class Exact>
void RangeTable::Impl::cast_chunk(const detail::BatchRays& rays, const detail::CellMask& m,
                                  std::span<const double> beam_index, const Wrap& wrap,
                                  std::size_t begin, std::size_t end, std::span<float> out_ranges,
                                  Exact* exact) const {
  const std::size_t beams = rays.beams();
  const double per_rad = options.angles / (2.0 * std::numbers::pi);
  std::vector<Choice> choices(beams);
  BeamScratch scratch(beams);
  for (std::size_t p = begin; p < end; ++p) {
    const detail::SensorFrame s = rays.sensor(p);
    float* out = out_ranges.data() + p * beams;
    if (!s.finite) {
      std::fill(out, out + beams, std::numeric_limits<float>::quiet_NaN());
      continue;
    }
    const int i = m.cell_of(s.ox, width);
    const int j = m.cell_of(s.oy, height);
    const bool on_map = i >= 0 && j >= 0 && i < width && j < height;
    if (m.blocks_start(s.ox, s.oy)) {
      std::fill(out, out + beams, 0.0F);
    } else if (!on_map) {
      for (std::size_t b = 0; b < beams; ++b) {
        out[b] = detail::walk_grid(m, m.prepare(rays.ray(s, b)), rays.max_range());
      }
    } else {
      choose(candidates(i, j, s.ox, s.oy), wrap(std::atan2(s.s, s.c) * per_rad), beam_index,
             scratch, choices);
      for (std::size_t b = 0; b < beams; ++b) out[b] = read(choices[b], rays.max_range());
      if (exact == nullptr) continue;
      for (std::size_t b = 0; b < beams; ++b) {
        if (out[b] == kCastExactly) exact->add(rays.ray(s, b), p * beams + b);
      }
    }
  }
}

RangeTable::RangeTable(const OccupancyGrid& grid, RangeTableOptions options)
    : impl_(std::make_unique<Impl>()) {
  check_options(options);
  impl_->width = grid.width();
  impl_->height = grid.height();
  impl_->resolution = static_cast<float>(grid.resolution());
  impl_->origin = grid.origin();
  impl_->options = options;
  impl_->blocking = detail::blocking_mask(grid, options.unknown_blocks);
  impl_->build();
}

RangeTable::~RangeTable() = default;
RangeTable::RangeTable(RangeTable&&) noexcept = default;
RangeTable& RangeTable::operator=(RangeTable&&) noexcept = default;

const RangeTableStats& RangeTable::stats() const noexcept { return impl_->stats; }

void RangeTable::cast(const RayBatch& batch, std::span<float> ranges) const {
  const Impl& t = *impl_;
  const detail::GridFrame frame(t.origin);
  const detail::CellMask m = t.mask();
  const detail::BatchRays rays(frame, m, batch, ranges.size());
  const std::size_t beams = rays.beams();
  const double per_rad = t.options.angles / (2.0 * std::numbers::pi);
  std::vector<double> beam_index(beams);
  const auto wrap = [n = double(t.options.angles)](double index) {
    return index - n * std::floor(index / n);  // into [0, n), so heading + beam stays in [0, 2n)
  };
  for (std::size_t b = 0; b < beams; ++b) beam_index[b] = wrap(batch.beam_angles[b] * per_rad);
  par::for_each_chunk(rays.particles(), t.options.particle_grain,
                      [&](std::size_t begin, std::size_t end) {
                        if (t.walls) {
                          t.cast_chunk_certified(rays, m, beam_index, wrap, begin, end, ranges);
                        } else {
                          t.cast_chunk<decltype(wrap), detail::Packet16>(
                              rays, m, beam_index, wrap, begin, end, ranges, nullptr);
                        }
                      });
}

float RangeTable::cast_one(Point2 origin, double angle, float max_range) const {
  detail::check_max_range(max_range);
  const detail::GridFrame frame(impl_->origin);
  const detail::GridRay ray = frame.ray(origin, angle);
  if (!std::isfinite(ray.ox) || !std::isfinite(ray.oy) || !std::isfinite(ray.dx)) {
    return std::numeric_limits<float>::quiet_NaN();
  }
  return impl_->cast_ray(ray, angle - impl_->origin.theta, max_range);
}

}  // namespace mote
