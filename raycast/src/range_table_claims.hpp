#pragma once
/// \file
/// Internal: the confirmed table's first step (RangeTableOptions::confirm) over all the beams of
/// one sensor: the four claims of each beam (the lattice point nearest its ray on each side, at
/// the two table directions around it; range_table_confirm.hpp), checked on the map. Compiled
/// per instruction set: the AVX-512 variant runs 16 beams on vector lanes, with the table's
/// entries and the map's cells read by gathers (the scalar rule executes about 1 260
/// instructions a ray, BENCHMARKS.md "Claims that name a wall face"); every other variant runs
/// the scalar rule. Both give the same ranges, bit for bit (range_table_claims.cpp, where both
/// are, is compiled without floating-point contraction).

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "ray_setup.hpp"

namespace mote::detail {

struct Candidates;

/// The map as bits twice, for the vector lanes' gathers: row-major (cell (i, j) is bit
/// j * width + i) and column-major (bit i * height + j), so that the two cells on either side of
/// a face (neighbours along a row for a face across x, along a column for one across y) are
/// read by one 32-bit load from the byte holding the first. Each ends in a spare word, so such a
/// load never leaves the array. Together a quarter of the byte mask: Intel's map stays in L2
/// beside the table rows a cast reads.
class CellBits {
 public:
  explicit CellBits(const CellMask& m);
  /// Row-major (`along_rows`) or column-major bits, as bytes.
  [[nodiscard]] const std::uint8_t* bits(bool along_rows) const noexcept {
    return reinterpret_cast<const std::uint8_t*>(along_rows ? rows_.data() : columns_.data());
  }
  [[nodiscard]] std::size_t bytes() const noexcept {
    return (rows_.size() + columns_.size()) * sizeof(std::uint32_t);
  }

 private:
  std::vector<std::uint32_t> rows_;
  std::vector<std::uint32_t> columns_;
};

/// What a claim reads: the table and the map.
struct ClaimTable {
  const std::uint16_t* ranges = nullptr;  ///< ranges[slot * angles + a]
  std::uint32_t angles = 0;
  const float* cos_a = nullptr;  ///< direction of table angle a, grid frame
  const float* sin_a = nullptr;
  float inv_units = 1.0F;          ///< cells per table unit
  CellMask mask;                   ///< the map, a byte a cell
  const CellBits* bits = nullptr;  ///< the same, a bit a cell (the vector lanes')
};

/// The beams of one sensor: inputs (table angle below each ray's, the next one, the ray's unit
/// direction in cells) and outputs (the nearest confirmed claim in cells, or kNotConfirmed;
/// whether every claim's ray left the map, 1, or some claim named a face, 0).
struct ClaimBeams {
  std::span<const std::uint32_t> below;
  std::span<const std::uint32_t> next;
  std::span<const float> ux;
  std::span<const float> uy;
  std::span<float> nearest;
  std::span<std::uint32_t> leaves;
};

/// Whether the vector lanes can index this table and map with 32-bit gathers (and read whole
/// 32-bit words of the table: an even number of angles).
[[nodiscard]] bool claims_fit_lanes(std::size_t entries, int angles, int width,
                                    int height) noexcept;

/// The four claims of every beam, for a sensor at (ox, oy) cells among candidates c, on the
/// variant active_isa() picks (the scalar rule where `lanes` is false).
void four_claims(const ClaimTable& t, const Candidates& c, float ox, float oy,
                 const ClaimBeams& beams, bool lanes) noexcept;

/// The scalar rule alone, for tests that compare the variants.
void four_claims_scalar(const ClaimTable& t, const Candidates& c, float ox, float oy,
                        const ClaimBeams& beams) noexcept;

/// The vector lanes alone (AVX-512); false, without touching `beams`, when this CPU or build
/// has none.
bool four_claims_lanes(const ClaimTable& t, const Candidates& c, float ox, float oy,
                       const ClaimBeams& beams) noexcept;

}  // namespace mote::detail
