// Filling the likelihood table: grid cells get f(distance), the ring gets `outside`.
#include "mote/maps/likelihood_table.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mote/core/error.hpp"
#include "mote/core/parallel.hpp"

namespace mote {

namespace {

int checked_border(int border, const DistanceField& field) {
  if (border < 1 || border > 1'000'000) {
    throw ConfigError("likelihood table: border must be 1..1000000 cells, got " +
                      std::to_string(border));
  }
  // The float clamp bounds must stay exactly representable (2^24) and every index must fit
  // int32 (LikelihoodView::lookup gathers with 32-bit indices).
  const long long w = field.width() + 2LL * border;
  const long long h = field.height() + 2LL * border;
  if (w > (1 << 24) || h > (1 << 24) || w * h > 0x7FFFFFFFLL) {
    throw ConfigError("likelihood table: more than 2^24 cells a side or 2^31 cells in all");
  }
  return border;
}

TableTransform make_transform(const DistanceField& field, int border, int width, int height) {
  TableTransform t;
  t.cos_yaw = static_cast<float>(std::cos(field.origin().theta));
  t.sin_yaw = static_cast<float>(std::sin(field.origin().theta));
  t.origin_x = static_cast<float>(field.origin().x);
  t.origin_y = static_cast<float>(field.origin().y);
  t.inv_resolution = static_cast<float>(1.0 / field.resolution());
  t.border = static_cast<float>(border);
  t.max_col = static_cast<float>(width - 1);
  t.max_row = static_cast<float>(height - 1);
  return t;
}

}  // namespace

LikelihoodTable::LikelihoodTable(const DistanceField& field, const std::function<float(float)>& f,
                                 float outside, int border)
    : width_(field.width() + 2 * checked_border(border, field)),
      height_(field.height() + 2 * border),
      border_(border),
      stride_(static_cast<std::size_t>(width_)),
      outside_(outside),
      transform_(make_transform(field, border, width_, height_)),
      values_(stride_ * static_cast<std::size_t>(height_), outside) {
  const auto w = static_cast<std::size_t>(field.width());
  const auto b = static_cast<std::size_t>(border);
  const float* distances = field.distances().data();
  par::for_each_chunk(static_cast<std::size_t>(field.height()), /*grain=*/16,
                      [&](std::size_t j0, std::size_t j1) {
                        for (std::size_t j = j0; j < j1; ++j) {
                          float* row = values_.data() + (j + b) * stride_ + b;
                          const float* d = distances + j * w;
                          for (std::size_t i = 0; i < w; ++i) row[i] = f(d[i]);
                        }
                      });
}

}  // namespace mote
