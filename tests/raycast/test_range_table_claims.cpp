// The confirmed table's four claims a beam (range_table_claims.hpp) on the dispatched variant
// (AVX-512 lanes where the CPU has them) against the scalar rule: the same nearest confirmed claim,
// bit for bit, and the same "every claim left the map", on the Intel map with entries cast exactly
// (grid walk) from the nine lattice points around each sensor, beams at any angle including along
// the axes, a partial last set of lanes.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <numbers>
#include <random>
#include <vector>

#include "grid_walk.hpp"
#include "mote/core/isa.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote_test/data.hpp"
#include "range_table_claims.hpp"
#include "range_table_confirm.hpp"
#include "range_table_sweep.hpp"

namespace mote {
namespace {

constexpr std::uint32_t kAngles = 512;
constexpr float kUnitsPerCell = 8.0F;
constexpr float kMaxRange = 30.0F;
constexpr std::size_t kBeams = 61;  // three full sets of 16 lanes and 13

/// The lattice points of the 3 x 3 cells around cell (i, j), for a sensor at (ox, oy) cells:
/// slot k is candidate k, blocking and off-map cells missing (as Impl::tile_candidates).
detail::Candidates around(const detail::CellMask& m, int i, int j, float ox, float oy) {
  detail::Candidates c;
  c.missing.fill(detail::kMissing);
  std::size_t k = 0;
  for (int nj = j - 1; nj <= j + 1; ++nj) {
    for (int ni = i - 1; ni <= i + 1; ++ni, ++k) {
      c.slot[k] = static_cast<std::uint32_t>(k);
      c.wx[k] = (static_cast<float>(ni) + 0.5F) - ox;
      c.wy[k] = (static_cast<float>(nj) + 0.5F) - oy;
      const bool on_map = ni >= 0 && nj >= 0 && ni < m.width && nj < m.height;
      c.missing[k] = !on_map || m.blocks(ni, nj) ? detail::kMissing : 0;
    }
  }
  return c;
}

/// Candidate k's entry at angle a, cast exactly from its lattice point (table units; kNoHit
/// when its ray leaves the map within kMaxRange).
std::uint16_t entry(const detail::CellMask& m, const detail::Candidates& c, std::size_t k, float ox,
                    float oy, std::uint32_t a) {
  const double angle = 2.0 * std::numbers::pi * a / kAngles;
  const detail::GridRay ray{(ox + c.wx[k]) * m.resolution, (oy + c.wy[k]) * m.resolution,
                            std::cos(angle), std::sin(angle)};
  const float range = detail::walk_grid(m, m.prepare(ray), kMaxRange);
  if (range >= kMaxRange) return detail::kNoHit;
  return static_cast<std::uint16_t>(std::lround(range / m.resolution * kUnitsPerCell));
}

/// What the comparison saw: beams compared, confirmed by the scalar rule, and differing.
struct Compared {
  std::size_t beams = 0;
  std::size_t confirmed = 0;
  std::size_t differ = 0;
};

/// Both variants on `sensors` sensors at random in free cells of m (any cell, edges included).
Compared compare_variants(const detail::CellMask& m, int sensors_wanted) {
  const detail::CellBits bits(m);
  std::vector<float> cos_a(kAngles);
  std::vector<float> sin_a(kAngles);
  for (std::uint32_t a = 0; a < kAngles; ++a) {
    cos_a[a] = static_cast<float>(std::cos(2.0 * std::numbers::pi * a / kAngles));
    sin_a[a] = static_cast<float>(std::sin(2.0 * std::numbers::pi * a / kAngles));
  }
  std::vector<std::uint16_t> ranges(9 * kAngles, detail::kNoHit);
  const detail::ClaimTable table{ranges.data(),        kAngles, cos_a.data(), sin_a.data(),
                                 1.0F / kUnitsPerCell, m,       &bits};
  std::vector<std::uint32_t> below(kBeams);
  std::vector<std::uint32_t> next(kBeams);
  std::vector<float> ux(kBeams);
  std::vector<float> uy(kBeams);
  std::vector<float> nearest_scalar(kBeams);
  std::vector<float> nearest_lanes(kBeams);
  std::vector<std::uint32_t> leaves_scalar(kBeams);
  std::vector<std::uint32_t> leaves_lanes(kBeams);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> cell_i(0, m.width - 1);
  std::uniform_int_distribution<int> cell_j(0, m.height - 1);
  std::uniform_real_distribution<float> inside(0.0F, 1.0F);
  std::uniform_real_distribution<double> angle_index(0.0, kAngles);
  Compared seen;
  for (int sensors = 0; sensors < sensors_wanted;) {
    const int i = cell_i(rng);
    const int j = cell_j(rng);
    if (m.blocks(i, j)) continue;
    ++sensors;
    const float ox = static_cast<float>(i) + inside(rng);
    const float oy = static_cast<float>(j) + inside(rng);
    const detail::Candidates c = around(m, i, j, ox, oy);
    for (std::size_t b = 0; b < kBeams; ++b) {
      // Every eighth beam along an axis: a direction component of zero, an infinite reciprocal.
      const double a_real = b % 8 == 0 ? kAngles / 4.0 * double(b / 8 % 4) : angle_index(rng);
      below[b] = static_cast<std::uint32_t>(a_real) % kAngles;
      next[b] = (below[b] + 1) % kAngles;
      const double angle = 2.0 * std::numbers::pi * a_real / kAngles;
      ux[b] = b % 8 == 0 ? std::round(static_cast<float>(std::cos(angle)))
                         : static_cast<float>(std::cos(angle));
      uy[b] = b % 8 == 0 ? std::round(static_cast<float>(std::sin(angle)))
                         : static_cast<float>(std::sin(angle));
      for (std::size_t k = 0; k < detail::Candidates::kCount; ++k) {
        if (c.missing[k] != 0) continue;
        for (const std::uint32_t a : {below[b], next[b]}) {
          ranges[k * kAngles + a] = entry(m, c, k, ox, oy, a);
        }
      }
    }
    const detail::ClaimBeams in{below, next, ux, uy, nearest_scalar, leaves_scalar};
    detail::four_claims_scalar(table, c, ox, oy, in);
    // The variant this process dispatches to: AVX-512 lanes on a CPU that has them (unless
    // MOTE_ISA lowers it), else the scalar rule itself.
    detail::four_claims(table, c, ox, oy, {below, next, ux, uy, nearest_lanes, leaves_lanes}, true);
    for (std::size_t b = 0; b < kBeams; ++b) {
      ++seen.beams;
      if (nearest_scalar[b] != detail::kNotConfirmed) ++seen.confirmed;
      const bool same = std::bit_cast<std::uint32_t>(nearest_scalar[b]) ==
                            std::bit_cast<std::uint32_t>(nearest_lanes[b]) &&
                        leaves_scalar[b] == leaves_lanes[b];
      if (!same && seen.differ++ < 5) {
        ADD_FAILURE() << "sensor (" << ox << ", " << oy << ") cells, beam " << b << " along ("
                      << ux[b] << ", " << uy[b] << "): scalar " << nearest_scalar[b] << " leaves "
                      << leaves_scalar[b] << ", lanes " << nearest_lanes[b] << " leaves "
                      << leaves_lanes[b];
      }
    }
  }
  std::cout << "four claims on " << isa_name(active_isa()) << ": " << seen.confirmed << " of "
            << seen.beams << " beams confirmed\n";
  return seen;
}

TEST(RangeTableClaims, DispatchedVariantGivesTheScalarRulesRangesOnIntel) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  const OccupancyGrid grid = load_map(path);
  const std::vector<std::uint8_t> cells = detail::blocking_mask(grid, true);
  const Compared seen = compare_variants(
      {grid.width(), grid.height(), static_cast<float>(grid.resolution()), cells.data()}, 400);
  EXPECT_EQ(seen.differ, 0U) << "of " << seen.beams << " beams";
  // The comparison means something only where claims are confirmed: most beams are.
  EXPECT_GT(seen.confirmed, seen.beams * 9 / 10) << seen.confirmed << " of " << seen.beams;
}

// Faces on the map's edges: a small map of scattered blocking cells whose edge cells are free
// too (rays leave it, and the cells beyond an edge read free), 37 x 29 so rows and columns end
// inside a byte of the bit masks.
TEST(RangeTableClaims, DispatchedVariantGivesTheScalarRulesRangesAtTheMapsEdges) {
  constexpr int kWidth = 37;
  constexpr int kHeight = 29;
  std::vector<std::uint8_t> cells(kWidth * kHeight, 0);
  std::mt19937 rng(11);
  std::bernoulli_distribution blocks(0.15);
  for (std::uint8_t& c : cells) c = blocks(rng) ? 1 : 0;
  const Compared seen = compare_variants({kWidth, kHeight, 0.05F, cells.data()}, 400);
  EXPECT_EQ(seen.differ, 0U) << "of " << seen.beams << " beams";
  EXPECT_GT(seen.confirmed, seen.beams / 2) << seen.confirmed << " of " << seen.beams;
}

}  // namespace
}  // namespace mote
