#include "e2e_cases.hpp"

#include "e2e_world.hpp"

namespace mote::bench {

namespace {

const char* model_name(LaserModel model) {
  return model == LaserModel::kBeam ? "beam" : "likelihood_field";
}

const char* setting_name(Setting setting) {
  return setting == Setting::kGlobal ? "global" : "tracking";
}

// The one case left out: the beam model weighing 1M particles spread over the whole map with
// 180 beams casts 180M long rays per update, over 5 s each (BENCHMARKS.md).
bool too_slow(const Case& c) {
  return c.model == LaserModel::kBeam && c.setting == Setting::kGlobal &&
         c.particles == 1'000'000 && c.beams == 180;
}

}  // namespace

std::string Case::name() const {
  return std::string("BM_Localizer_Update/") + model_name(model) + "/" + setting_name(setting) +
         "/n:" + std::to_string(particles) + "/beams:" + std::to_string(beams) +
         "/threads:" + std::to_string(threads) + (nav2 ? "/defaults:nav2" : "") +
         (kld_min > 0 ? "/kld_min:" + std::to_string(kld_min) : "") +
         (ray_casting != RayCasting::kExact ? std::string("/ray_casting:") + name_of(ray_casting)
                                            : "");
}

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  for (const LaserModel model : {LaserModel::kLikelihoodField, LaserModel::kBeam}) {
    for (const int threads : {1, 2}) {
      for (const int particles : {1'000, 10'000, 100'000, 1'000'000}) {
        for (const Setting setting : {Setting::kTracking, Setting::kGlobal}) {
          for (const int beams : kBeamCounts) {
            const Case c{model, setting, particles, beams, threads};
            if (!too_slow(c)) cases.push_back(c);
          }
        }
      }
    }
  }
  return cases;
}

std::vector<Case> nav2_baseline_cases() {
  std::vector<Case> cases;
  for (const LaserModel model : {LaserModel::kLikelihoodField, LaserModel::kBeam}) {
    for (const int particles : {10'000, 100'000}) {
      for (const bool nav2 : {false, true}) {
        cases.push_back({model, Setting::kTracking, particles, 60, 2, nav2});
      }
    }
  }
  return cases;
}

std::vector<Case> range_table_cases() {
  std::vector<Case> cases;
  for (const int particles : {10'000, 100'000}) {
    for (const RayCasting source : {RayCasting::kExact, RayCasting::kTable}) {
      Case c{LaserModel::kBeam, Setting::kTracking, particles, 60, 2};
      c.ray_casting = source;
      cases.push_back(c);
    }
  }
  return cases;
}

std::vector<Case> kld_cases() {
  std::vector<Case> cases;
  const auto add = [&](LaserModel model, int particles) {
    for (const Setting setting : {Setting::kTracking, Setting::kGlobal}) {
      cases.push_back({model, setting, particles, 60, 2, false, 500});
    }
  };
  add(LaserModel::kLikelihoodField, 100'000);
  add(LaserModel::kLikelihoodField, 1'000'000);
  add(LaserModel::kBeam, 10'000);
  return cases;
}

}  // namespace mote::bench
