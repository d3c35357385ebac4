#pragma once
// map.png's colours and stroke sizes, shared by the map drawing and its legend.
#include <algorithm>

#include "mote/maps/figure.hpp"

namespace mote::replay::map_style {

inline constexpr figure::Rgb kFree{255, 255, 255};
inline constexpr figure::Rgb kOccupied{0, 0, 0};
inline constexpr figure::Rgb kUnknown{200, 200, 200};
inline constexpr figure::Rgb kReference{110, 210, 110};
inline constexpr figure::Rgb kEstimate{220, 20, 20};
inline constexpr figure::Rgb kLost{255, 140, 0};
inline constexpr figure::Rgb kParticle{30, 80, 255};
inline constexpr figure::Rgb kStart{140, 0, 170};
inline constexpr figure::Rgb kEnd{0, 0, 0};

/// Stroke widths and marker sizes in pixels for `scale` pixels per cell: the reference wide
/// enough to show on both sides of the estimate drawn over it.
struct Strokes {
  double estimate, lost, reference, particle, marker;
  explicit Strokes(int scale)
      : estimate(std::max(2.0, scale / 2.0)),
        lost(estimate + 2.0),
        reference(std::max(6.0, 2.0 * scale)),
        particle(std::max(2.0, 0.6 * scale)),
        marker(std::max(7.0, 2.0 * scale)) {}
};

}  // namespace mote::replay::map_style
