#pragma once
// Connected-component labelling of occupied histogram bins (engine-internal).

#include <cstdint>
#include <vector>

#include "bin_map.hpp"

namespace mote::detail {

// The cluster of each bin: bins connected through their 26 (x, y, theta) neighbours, theta
// wrapping around after nt bins (nt = 1: 8-connectivity in x, y). Bin i is bins[i], numbered as
// in id_of; clusters are numbered in order of their lowest bin.
[[nodiscard]] std::vector<std::uint32_t> label_bins(const std::vector<BinCoord>& bins,
                                                    const BinMap& id_of, std::int32_t nt);

}  // namespace mote::detail
