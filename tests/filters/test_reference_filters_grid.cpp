// Grid localization (Thrun section 8.2) against a particle filter that samples the same
// discrete model: particles hold a state index, move by drawing from the grid's motion kernel
// and are weighed by the grid's likelihoods; their marginal over (x, y) cells must approach
// the histogram filter's as N grows. The convolution (histogram filter) and the sampling
// (particle filter) are independent computations of the same posterior.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "mote/engine/philox.hpp"
#include "mote/engine/state_store.hpp"
#include "mote/filters/histogram_filter.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/raycast/grid_ray_caster.hpp"
#include "mote_test/data.hpp"

namespace mote {
namespace {

// A 2.4 m x 2 m room at 10 cm with a pillar, so the posterior is not symmetric.
OccupancyGrid small_room() {
  const int w = 24, h = 20;
  std::vector<CellState> cells(static_cast<std::size_t>(w * h), CellState::kFree);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const bool wall = i == 0 || j == 0 || i == w - 1 || j == h - 1;
      const bool pillar = i >= 14 && i <= 16 && j >= 5 && j <= 8;
      if (wall || pillar) cells[static_cast<std::size_t>(j * w + i)] = CellState::kOccupied;
    }
  }
  return {w, h, 0.1, {0.0, 0.0, 0.0}, std::move(cells)};
}

// A 3 m x 3 m crop of a real map around (cx, cy).
OccupancyGrid crop(const OccupancyGrid& g, double cx, double cy, double size) {
  const CellIndex c = g.world_to_cell({cx, cy});
  const int half = static_cast<int>(size / (2.0 * g.resolution()));
  std::vector<CellState> cells;
  for (int j = c.j - half; j < c.j + half; ++j) {
    for (int i = c.i - half; i < c.i + half; ++i)
      cells.push_back(g.at_or({i, j}, CellState::kOccupied));
  }
  const Point2 corner =
      g.to_map_frame({(c.i - half) * g.resolution(), (c.j - half) * g.resolution()});
  return {
      2 * half, 2 * half, g.resolution(), {corner.x, corner.y, g.origin().theta}, std::move(cells)};
}

BeamSet simulated_scan(const OccupancyGrid& map, const Pose2& pose, int beams) {
  const GridRayCaster caster(map);
  BeamSet scan;
  scan.range_max = 4.0F;
  for (int b = 0; b < beams; ++b) {
    const double a = -M_PI + 2.0 * M_PI * b / beams;
    scan.angle.push_back(static_cast<float>(a));
    scan.range.push_back(caster.cast_one({pose.x, pose.y}, pose.theta + a, scan.range_max));
  }
  return scan;
}

struct Problem {
  std::vector<Odometry> moves;
  std::vector<std::vector<float>> loglik;  // per step, from the histogram filter
  std::vector<double> exact;               // the histogram filter's marginal over (x, y)
  std::vector<std::vector<std::vector<MotionKernelEntry>>> by_from;  // per step, per heading
};

// Runs the histogram filter along a path and records what the particle filter needs.
Problem solve(GridLocalization& hf, const OccupancyGrid& map, Pose2 pose, int steps) {
  Problem p;
  const Odometry u{{0.0, 0.0, 0.0}, {0.2, 0.0, 0.3}};
  for (int t = 0; t < steps; ++t) {
    pose = compose(pose, Pose2{0.2, 0.0, 0.3});
    const MotionKernel k = hf.motion_kernel(u);
    std::vector<std::vector<MotionKernelEntry>> from(static_cast<std::size_t>(hf.headings()));
    for (const auto& list : k.by_to) {
      for (const MotionKernelEntry& e : list) from[static_cast<std::size_t>(e.from)].push_back(e);
    }
    p.by_from.push_back(std::move(from));
    hf.predict(k);
    p.loglik.push_back(hf.measurement_log_likelihood(simulated_scan(map, pose, 16)));
    hf.correct(p.loglik.back());
  }
  p.exact = hf.marginal_xy();
  return p;
}

// One particle filter run on the discrete model; returns the TV distance to the exact marginal
// and its Monte Carlo scale (see test_reference_filters_histogram.cpp).
std::pair<double, double> particle_filter(const GridLocalization& hf, const Problem& p,
                                          std::size_t n, std::uint64_t seed) {
  std::vector<std::size_t> free_states;
  for (std::size_t k = 0; k < hf.state_count(); ++k) {
    if (hf.is_free(k)) free_states.push_back(k);
  }
  StateStore store(1, n);
  const RngStream init{seed, 0, RngPurpose::kInitial};
  for (std::size_t i = 0; i < n; ++i) {
    const double u = init.uniform_double(static_cast<std::uint32_t>(i));
    store.view().column(0)[i] = static_cast<float>(
        free_states[static_cast<std::size_t>(u * static_cast<double>(free_states.size()))]);
  }
  const auto nx = static_cast<std::size_t>(hf.nx()), ny = static_cast<std::size_t>(hf.ny());
  double ess = static_cast<double>(n);
  for (std::size_t t = 0; t < p.moves.size() + p.loglik.size() && t < p.loglik.size(); ++t) {
    if (t > 0 && should_resample(ess, n)) resample_systematic(store, n, seed, t);
    const RngStream rng{seed, t + 1, RngPurpose::kMotion};
    const StateView s = store.view();
    for (std::size_t i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(s.column(0)[i]);
      const std::size_t from = k / (nx * ny);
      double u = rng.uniform_double(static_cast<std::uint32_t>(i));
      const auto& entries = p.by_from[t][from];
      std::size_t e = 0;
      while (e + 1 < entries.size() && u >= entries[e].p) u -= entries[e++].p;
      const long i2 = static_cast<long>(k % nx) + entries[e].di;
      const long j2 = static_cast<long>((k / nx) % ny) + entries[e].dj;
      if (i2 < 0 || j2 < 0 || i2 >= static_cast<long>(nx) || j2 >= static_cast<long>(ny)) {
        s.logw[i] = -INFINITY;  // moved off the grid: the histogram filter drops this mass too
        continue;
      }
      const std::size_t next =
          (static_cast<std::size_t>(entries[e].to) * ny + static_cast<std::size_t>(j2)) * nx +
          static_cast<std::size_t>(i2);
      s.column(0)[i] = static_cast<float>(next);
      s.logw[i] += p.loglik[t][next];
    }
    ess = normalize(store.view()).effective_sample_size;
  }
  std::vector<double> hist(nx * ny, 0.0);
  const ConstStateView s = std::as_const(store).view();
  for (std::size_t i = 0; i < n; ++i)
    hist[static_cast<std::size_t>(s.column(0)[i]) % (nx * ny)] += std::exp(double{s.logw[i]});
  double tv = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < hist.size(); ++k) {
    tv += 0.5 * std::abs(hist[k] - p.exact[k]);
    scale += 0.5 * std::sqrt(p.exact[k] * (1.0 - p.exact[k]) / ess);
  }
  return {tv, scale};
}

// Bound as in test_reference_filters_histogram.cpp: 4 Monte Carlo scales.
void expect_converges(const GridLocalization& hf, const Problem& p) {
  double tv_small = 0.0, tv_large = 0.0, z2 = 0.0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const auto [s_tv, s_scale] = particle_filter(hf, p, 1000, seed);
    const auto [l_tv, l_scale] = particle_filter(hf, p, 100000, seed);
    std::printf("seed %llu: TV 1k %.4f (z %.2f), 100k %.5f (z %.2f)\n",
                static_cast<unsigned long long>(seed), s_tv, s_tv / s_scale, l_tv, l_tv / l_scale);
    z2 += (l_tv / l_scale) * (l_tv / l_scale);
    tv_small += s_tv;
    tv_large += l_tv;
  }
  EXPECT_LT(std::sqrt(z2 / 3.0), 4.0);  // RMS over seeds (measured 1.4-2.0 per seed)
  EXPECT_LT(tv_large * 4.0, tv_small);
}

GridLocalizationConfig config() {
  GridLocalizationConfig c;
  c.headings = 16;
  c.motion = {.alpha1 = 0.1, .alpha2 = 0.1, .alpha3 = 0.1, .alpha4 = 0.1};
  c.sensor.mixture.sigma_hit = 0.2;
  c.sensor.tempering = 0.3;  // keeps several modes alive, so the comparison covers many cells
  return c;
}

TEST(GridLocalization, KernelRowsAreDistributionsAndLocalizationConverges) {
  const OccupancyGrid map = small_room();
  GridLocalization hf(map, config());
  const MotionKernel k = hf.motion_kernel({{0, 0, 0}, {0.2, 0.0, 0.3}});
  std::vector<double> sums(static_cast<std::size_t>(hf.headings()), 0.0);
  for (const auto& list : k.by_to) {
    for (const MotionKernelEntry& e : list) sums[static_cast<std::size_t>(e.from)] += e.p;
  }
  for (const double s : sums) EXPECT_NEAR(s, 1.0, 1e-12);
  const Pose2 truth{0.6, 0.5, 0.2};
  const Problem p = solve(hf, map, truth, 3);
  expect_converges(hf, p);
}

TEST(GridLocalization, RealMapCrop) {
  MOTE_REQUIRE_DATA(yaml, "intel/intel.yaml");
  const OccupancyGrid full = load_map(yaml);
  const OccupancyGrid map = crop(full, 0.6, -0.03, 3.0);
  GridLocalizationConfig c = config();
  c.cell_stride = 2;  // 10 cm state cells on the 5 cm map
  GridLocalization hf(map, c);
  const Problem p = solve(hf, map, {0.6, -0.03, -0.35}, 3);
  expect_converges(hf, p);
}

}  // namespace
}  // namespace mote
