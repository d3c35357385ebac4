#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mote/core/error.hpp"
#include "mote/engine/localizer_config.hpp"
#include "mote_test/data.hpp"

namespace mote {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

TEST(LoadConfig, Nav2FileReadsEveryKey) {
  const LoadedConfig loaded = load_config(test::project_test_data() / "nav2_params.yaml");
  const LocalizerConfig defaults;
  const LocalizerConfig& c = loaded.config;
  EXPECT_EQ(c.min_particles, 500);
  EXPECT_EQ(c.max_particles, 2000);
  EXPECT_DOUBLE_EQ(c.pf_err, 0.05);
  EXPECT_DOUBLE_EQ(c.pf_z, 0.99);
  EXPECT_DOUBLE_EQ(c.alpha1, 0.2);
  EXPECT_DOUBLE_EQ(c.alpha5, 0.2);
  EXPECT_DOUBLE_EQ(c.laser_likelihood_max_dist, 2.0);
  EXPECT_DOUBLE_EQ(c.laser_max_range, 100.0);
  EXPECT_DOUBLE_EQ(c.laser_min_range, -1.0);
  EXPECT_EQ(c.max_beams, 60);
  EXPECT_EQ(c.laser_model_type, LaserModel::kLikelihoodField);
  EXPECT_EQ(c.odom_model_type, OdomModel::kDiff);
  EXPECT_DOUBLE_EQ(c.update_min_d, 0.25);
  EXPECT_DOUBLE_EQ(c.update_min_a, 0.2);
  EXPECT_DOUBLE_EQ(c.z_hit, defaults.z_hit);
  EXPECT_DOUBLE_EQ(c.sigma_hit, 0.2);
  // Nothing is worth a warning: do_beamskip is false and the beam_skip_* values tune what it
  // leaves off; frames, topics and tf are the node's (read_node_params), use_sim_time ROS's.
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
  EXPECT_TRUE(loaded.nav2_params);
  EXPECT_EQ(loaded.source, (test::project_test_data() / "nav2_params.yaml").string());
}

TEST(LoadConfig, TunedNav2FileOverridesEveryValue) {
  const LoadedConfig loaded = load_config(test::project_test_data() / "nav2_params_tuned.yaml");
  const LocalizerConfig& c = loaded.config;
  EXPECT_DOUBLE_EQ(c.alpha1, 0.05);
  EXPECT_DOUBLE_EQ(c.alpha2, 0.06);
  EXPECT_DOUBLE_EQ(c.alpha3, 0.07);
  EXPECT_DOUBLE_EQ(c.alpha4, 0.08);
  EXPECT_DOUBLE_EQ(c.alpha5, 0.09);
  EXPECT_EQ(c.laser_model_type, LaserModel::kBeam);
  EXPECT_EQ(c.odom_model_type, OdomModel::kOmni);
  EXPECT_EQ(c.max_beams, 120);
  EXPECT_EQ(c.max_particles, 8000);
  EXPECT_EQ(c.min_particles, 200);
  EXPECT_DOUBLE_EQ(c.pf_err, 0.02);
  EXPECT_DOUBLE_EQ(c.pf_z, 0.95);
  EXPECT_DOUBLE_EQ(c.recovery_alpha_fast, 0.1);
  EXPECT_DOUBLE_EQ(c.recovery_alpha_slow, 0.001);
  EXPECT_EQ(c.resample_interval, 2);
  EXPECT_DOUBLE_EQ(c.sigma_hit, 0.1);
  EXPECT_DOUBLE_EQ(c.laser_likelihood_max_dist, 4.0);
  EXPECT_DOUBLE_EQ(c.z_hit, 0.9);
  EXPECT_DOUBLE_EQ(c.z_short, 0.02);
  EXPECT_DOUBLE_EQ(c.z_max, 0.03);
  EXPECT_DOUBLE_EQ(c.z_rand, 0.05);
  EXPECT_DOUBLE_EQ(c.lambda_short, 0.2);
  EXPECT_DOUBLE_EQ(c.laser_min_range, 0.4);
  EXPECT_DOUBLE_EQ(c.laser_max_range, 30.0);
  ASSERT_EQ(loaded.warnings.size(), 1U);
  EXPECT_THAT(loaded.warnings[0], HasSubstr("do_beamskip"));
  EXPECT_THAT(loaded.warnings[0], HasSubstr("nav2_params_tuned.yaml: line 30"));
}

// An unknown key is an error naming file, line and key, with the key it was a typo of.
TEST(ParseConfig, UnknownKeysAreErrorsWithTheClosestKey) {
  const auto message = [](const std::string& yaml) {
    try {
      (void)parse_config(yaml, "typo.yaml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(message("alpha1: 0.2\nsigma_hitt: 0.1\n"),
              HasSubstr("typo.yaml: line 2, key 'sigma_hitt': unknown key (did you mean "
                        "'sigma_hit'?)"));
  EXPECT_THAT(message("min_partciles: 100\n"), HasSubstr("did you mean 'min_particles'?"));
  EXPECT_THAT(message("completely_unrelated_key: 1\n"), Not(HasSubstr("did you mean")));
  EXPECT_THAT(message("completely_unrelated_key: 1\n"), HasSubstr("unknown key"));
}

TEST(ParseConfig, FlatMoteFileReadsMoteKeys) {
  const LoadedConfig loaded = parse_config(
      "threads: 2\nseed: 7\nlikelihood_combination: amcl\nodom_model_type: ackermann\n"
      "wheelbase: 1.2\nlikelihood_tempering: 0.5\nselective_resampling: false\n",
      "flat.yaml");
  EXPECT_EQ(loaded.config.threads, 2);
  EXPECT_EQ(loaded.config.seed, 7U);
  EXPECT_EQ(loaded.config.likelihood_combination, LikelihoodCombination::kAmclCubedSum);
  EXPECT_EQ(loaded.config.odom_model_type, OdomModel::kAckermann);
  EXPECT_DOUBLE_EQ(loaded.config.wheelbase, 1.2);
  EXPECT_DOUBLE_EQ(loaded.config.likelihood_tempering, 0.5);
  EXPECT_DOUBLE_EQ(loaded.config.resample_ess_fraction, 1.0);
  EXPECT_TRUE(loaded.warnings.empty());
  EXPECT_DOUBLE_EQ(parse_config("tracking_tempering: 0.2\n", "t.yaml").config.tracking_tempering,
                   0.2);
}

void expect_input_error(const std::string& text, const std::string& fragment) {
  try {
    (void)parse_config(text, "bad.yaml");
    ADD_FAILURE() << "no error for: " << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "bad.yaml");
    EXPECT_THAT(e.what(), HasSubstr(fragment)) << text;
  }
}

TEST(ParseConfig, WrongTypesNameTheKeyAndLine) {
  expect_input_error("alpha1: 0.1\nalpha2: fast\n", "line 2, key 'alpha2': expected a number");
  expect_input_error("max_particles: 2000.5\n", "key 'max_particles': expected an integer");
  expect_input_error("laser_model_type: sonar\n", "expected likelihood_field");
  expect_input_error("amcl_motion_conventions: maybe\n", "expected true or false");
}

TEST(ParseConfig, OutOfRangeValuesAreRejected) {
  expect_input_error("min_particles: 100\nmax_particles: 50\n", "max_particles");
  expect_input_error("pf_err: 0\n", "pf_err");
  expect_input_error("pf_z: 1.5\n", "pf_z");
  expect_input_error("sigma_hit: -0.1\n", "sigma_hit");
  expect_input_error("z_hit: 0\nz_short: 0\nz_max: 0\nz_rand: 0\n", "not all 0");
}

TEST(ParseConfig, BrokenYamlAndMissingFile) {
  expect_input_error("alpha1: [0.1\n", "invalid YAML");
  expect_input_error("- just\n- a list\n", "expected a map");
  EXPECT_THROW((void)load_config("/nonexistent/mote.yaml"), InputError);
}

TEST(LocalizerConfig, DefaultsAreValid) {
  EXPECT_NO_THROW(LocalizerConfig{}.validate());
  EXPECT_NO_THROW(nav2_defaults().validate());
}

// Issue 46: a nav2 params file carries the robot, not amcl's algorithm. Its keys apply over
// mote's adaptive defaults; the file as nav2 ships it differs from them only in max_particles.
TEST(LoadConfig, Nav2FileStartsFromMoteDefaults) {
  const LoadedConfig loaded = load_config(test::project_test_data() / "nav2_params.yaml");
  EXPECT_EQ(loaded.defaults, ConfigDefaults::kMote);
  LocalizerConfig expected;
  expected.max_particles = 2000;
  EXPECT_TRUE(loaded.config == expected) << config_yaml(loaded.config);
  const LocalizerConfig& c = loaded.config;
  EXPECT_DOUBLE_EQ(c.likelihood_tempering, 0.0) << "the exponent adapts";
  EXPECT_TRUE(c.adaptive_motion_noise) << "the file's alphas are where the fit starts";
  EXPECT_TRUE(c.unmapped_obstacle_filter);
  EXPECT_TRUE(c.relocalize_when_lost);
  EXPECT_EQ(c.likelihood_combination, LikelihoodCombination::kProduct);
  // The tuned file's values apply as written over the same adaptive mechanisms.
  const LocalizerConfig tuned =
      load_config(test::project_test_data() / "nav2_params_tuned.yaml").config;
  EXPECT_DOUBLE_EQ(tuned.alpha1, 0.05);
  EXPECT_EQ(tuned.max_particles, 8000);
  EXPECT_DOUBLE_EQ(tuned.likelihood_tempering, 0.0);
  EXPECT_TRUE(tuned.adaptive_motion_noise);
}

// `defaults: nav2` in the file or from the caller (--nav2-defaults) stays amcl's behaviour:
// nav2's values under the file's, formula for formula.
TEST(LoadConfig, Nav2DefaultsAskedForGiveAmclsBehaviour) {
  const fs::path file = test::project_test_data() / "nav2_params.yaml";
  const LoadedConfig loaded = load_config(file, ConfigDefaults::kNav2);
  EXPECT_EQ(loaded.defaults, ConfigDefaults::kNav2);
  // The shipped file holds nav2's defaults, so nothing moves off them.
  EXPECT_TRUE(loaded.config == nav2_defaults()) << config_yaml(loaded.config, nav2_defaults());
  const LocalizerConfig& c = loaded.config;
  EXPECT_DOUBLE_EQ(c.likelihood_tempering, 1.0);
  EXPECT_FALSE(c.adaptive_motion_noise);
  EXPECT_FALSE(c.unmapped_obstacle_filter);
  EXPECT_DOUBLE_EQ(c.global_particles_per_bin, 0.0);
  EXPECT_EQ(c.likelihood_combination, LikelihoodCombination::kAmclCubedSum);
  EXPECT_DOUBLE_EQ(c.resample_ess_fraction, 1.0);
  EXPECT_TRUE(c.kld_z_is_quantile);
  EXPECT_TRUE(c.unknown_cells_block_rays);
  EXPECT_FALSE(c.relocalize_when_lost);
  // The same with `defaults: nav2` in the file, and the caller may repeat what the file says.
  const std::string text = "amcl:\n  ros__parameters:\n    defaults: nav2\n    alpha1: 0.1\n";
  LocalizerConfig expected = nav2_defaults();
  expected.alpha1 = 0.1;
  EXPECT_TRUE(parse_config(text, "n.yaml").config == expected);
  EXPECT_TRUE(parse_config(text, "n.yaml", ConfigDefaults::kNav2).config == expected);
  // The file and the caller naming different defaults is an error, not a silent choice.
  try {
    (void)parse_config("defaults: mote\n", "m.yaml", ConfigDefaults::kNav2);
    ADD_FAILURE() << "mote's and nav2's defaults both accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("m.yaml: line 1, key 'defaults': the file asks for mote's "
                                    "defaults, the caller for nav2's"));
  }
}

// Keys that ask for nothing pass in silence; a value that asks for what mote does not do warns
// with the key's line, and nav2's newer keys (Jazzy and later) are read rather than refused.
TEST(ParseConfig, KeysAtTheirOffValueDoNotWarn) {
  const std::string ros = "amcl:\n  ros__parameters:\n";
  const LoadedConfig quiet = parse_config(
      ros +
          "    do_beamskip: false\n    beam_skip_distance: 0.5\n    random_seed: -1\n"
          "    freespace_downsampling: false\n    introspection_mode: \"disabled\"\n"
          "    service_introspection_mode: disabled\n    allow_parameter_qos_overrides: true\n"
          "    initialize_at_saved_pose: false\n    saved_pose_filepath: /tmp/p\n"
          "    first_map_only: false\n    always_reset_initial_pose: false\n"
          "    map_topic: map\n    initial_pose: {x: 1.0, y: 2.0, z: 0.0, yaw: 0.5}\n",
      "quiet.yaml");
  EXPECT_TRUE(quiet.warnings.empty()) << quiet.warnings.front();
  EXPECT_EQ(quiet.config.seed, LocalizerConfig{}.seed) << "-1 asks for no particular seed";
  EXPECT_EQ(parse_config(ros + "    random_seed: 7\n", "s.yaml").config.seed, 7U);
  const LoadedConfig loud = parse_config(ros +
                                             "    do_beamskip: true\n"
                                             "    freespace_downsampling: true\n"
                                             "    introspection_mode: contents\n",
                                         "loud.yaml");
  ASSERT_EQ(loud.warnings.size(), 3U);
  EXPECT_THAT(loud.warnings[0], HasSubstr("loud.yaml: line 3, key 'do_beamskip': beam skipping "
                                          "is not implemented"));
  EXPECT_THAT(loud.warnings[1], HasSubstr("line 4, key 'freespace_downsampling'"));
  EXPECT_THAT(loud.warnings[2], HasSubstr("line 5, key 'introspection_mode'"));
  for (const std::string& w : loud.warnings) EXPECT_THAT(w, HasSubstr("key ignored"));
  expect_input_error("do_beamskip: maybe\n", "line 1, key 'do_beamskip': expected true or false");
  expect_input_error("beam_skip_distance: far\n", "key 'beam_skip_distance': expected a number");
}

// The lines a run prints first say which defaults it uses and how a file's keys apply.
TEST(ConfigSummary, SaysWhichDefaultsAndHowTheFileApplies) {
  const fs::path file = test::project_test_data() / "nav2_params.yaml";
  const std::vector<std::string> mote = config_summary(load_config(file));
  ASSERT_EQ(mote.size(), 2U);
  EXPECT_THAT(mote[0], HasSubstr("defaults: mote's adaptive ones"));
  EXPECT_THAT(mote[0], HasSubstr("--nav2-defaults"));
  EXPECT_THAT(mote[1], HasSubstr("a nav2 params file: its laser, robot model, particle bounds"));
  EXPECT_THAT(mote[1], HasSubstr("where the odometry-noise fit starts"));
  const std::vector<std::string> nav2 = config_summary(load_config(file, ConfigDefaults::kNav2));
  ASSERT_EQ(nav2.size(), 2U);
  EXPECT_THAT(nav2[0], HasSubstr("defaults: nav2_amcl's fixed behaviour"));
  EXPECT_THAT(nav2[1], HasSubstr("every value as amcl reads it"));
  EXPECT_THAT(config_summary(parse_config("seed: 3\n", "flat.yaml"))[1],
              HasSubstr("config: flat.yaml, its keys over those defaults"));
  EXPECT_EQ(config_summary(LoadedConfig{}).size(), 1U) << "no file, no config line";
}

TEST(ParseConfig, DefaultsKeyChoosesTheBase) {
  const LocalizerConfig nav2 = parse_config("defaults: nav2\nseed: 3\n", "n.yaml").config;
  EXPECT_DOUBLE_EQ(nav2.likelihood_tempering, 1.0);
  EXPECT_EQ(nav2.max_particles, 2000);
  EXPECT_EQ(nav2.seed, 3U);
  const LocalizerConfig mote = parse_config("defaults: mote\nseed: 3\n", "m.yaml").config;
  EXPECT_DOUBLE_EQ(mote.likelihood_tempering, 0.0);
  EXPECT_TRUE(mote.adaptive_motion_noise);
  EXPECT_TRUE(mote.unmapped_obstacle_filter);
  EXPECT_FALSE(
      parse_config("unmapped_obstacle_filter: false\n", "u.yaml").config.unmapped_obstacle_filter);
  // Order does not matter: defaults applies first.
  EXPECT_EQ(parse_config("max_particles: 900\ndefaults: nav2\n", "o.yaml").config.max_particles,
            900);
  EXPECT_DOUBLE_EQ(
      parse_config("likelihood_tempering: auto\n", "a.yaml").config.likelihood_tempering, 0.0);
  expect_input_error("defaults: ros\n", "expected mote or nav2");
  expect_input_error("likelihood_tempering: 2\n", "likelihood_tempering");
  expect_input_error("tracking_tempering: -0.1\n", "tracking_tempering");
  expect_input_error("motion_noise_margin: 0\n", "motion_noise_margin");
  // A fixed exponent has no adaptive search for tracking_tempering to replace.
  expect_input_error("likelihood_tempering: 0.3\ntracking_tempering: 0.2\n",
                     "0 when likelihood_tempering fixes the exponent");
  expect_input_error("defaults: nav2\ntracking_tempering: 0.2\n", "tracking_tempering");
  expect_input_error("lost_misfit: 2\n", "lost_misfit");
}

void expect_config_error(const LocalizerConfig& c, const std::string& fragment) {
  try {
    c.validate();
    ADD_FAILURE() << "validate() accepted a config that should name " << fragment;
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr(fragment));
  }
}

TEST(LocalizerConfig, RecoveryNeedsASlowAverageSlowerThanTheFastOne) {
  // Thrun table 8.3: 0 <= alpha_slow << alpha_fast; the other way round w_fast / w_slow
  // inverts its meaning and injects particles while tracking well.
  LocalizerConfig c;
  c.recovery_alpha_slow = 0.1;
  c.recovery_alpha_fast = 0.001;
  expect_config_error(c, "LocalizerConfig.recovery_alpha_slow");
  c.recovery_alpha_fast = 0.1;
  expect_config_error(c, "LocalizerConfig.recovery_alpha_slow");
  c.recovery_alpha_slow = 0.001;
  EXPECT_NO_THROW(c.validate());
  c.recovery_alpha_slow = 0.0;  // either 0 disables recovery (amcl): no order to check
  c.recovery_alpha_fast = 0.0;
  EXPECT_NO_THROW(c.validate());
}

TEST(LocalizerConfig, RefusesParticleAndThreadCountsThatWouldExhaustMemory) {
  // The same limits as the YAML loader's, so a program that fills the config itself is
  // refused too, instead of failing on allocation.
  LocalizerConfig c;
  c.max_particles = 100'000'001;
  expect_config_error(c, "LocalizerConfig.max_particles");
  c.max_particles = 100'000'000;
  EXPECT_NO_THROW(c.validate());
  c = LocalizerConfig{};
  c.threads = 1025;
  expect_config_error(c, "LocalizerConfig.threads");
  c.threads = 1024;
  EXPECT_NO_THROW(c.validate());
}

TEST(ParseConfig, SizeLimitsNameTheKeyAndLine) {
  expect_input_error("alpha1: 0.1\nmax_particles: 1000000000\n", "line 2, key 'max_particles'");
  expect_input_error("threads: 1000000\n", "line 1, key 'threads'");
  expect_input_error("recovery_alpha_slow: 0.5\nrecovery_alpha_fast: 0.1\n",
                     "key 'recovery_alpha_slow'");
}

}  // namespace
}  // namespace mote

namespace mote {
namespace {

// Issue 19: the beam model's ray_casting switch and the range table's angles and budget.
TEST(ParseConfig, RayCastingSelectsExactOrTable) {
  EXPECT_EQ(LocalizerConfig{}.ray_casting, RayCasting::kTable) << "the table is the default";
  EXPECT_EQ(nav2_defaults().ray_casting, RayCasting::kExact) << "amcl casts every ray";
  const LoadedConfig loaded = parse_config(
      "ray_casting: table\nrange_table_angles: 256\nrange_table_budget_mb: 64\n", "t.yaml");
  EXPECT_EQ(loaded.config.ray_casting, RayCasting::kTable);
  EXPECT_EQ(loaded.config.range_table_angles, 256);
  EXPECT_DOUBLE_EQ(loaded.config.range_table_budget_mb, 64.0);
  EXPECT_TRUE(loaded.warnings.empty());
  EXPECT_EQ(parse_config("ray_casting: exact\n", "e.yaml").config.ray_casting, RayCasting::kExact);
  expect_input_error("ray_casting: fast\n", "line 1, key 'ray_casting': expected exact or table");
  expect_input_error("ray_casting: table_certified\n",
                     "line 1, key 'ray_casting': expected exact or table");
  expect_input_error("range_table_angles: 100\n", "range_table_angles");
  expect_input_error("range_table_budget_mb: 0\n", "range_table_budget_mb");
}

// Every field away from its default, each to a value validate() accepts.
LocalizerConfig every_field_changed() {
  LocalizerConfig c;
  c.min_particles = 300;
  c.max_particles = 9000;
  c.global_particles_per_bin = 2.5;
  c.pf_err = 0.02;
  c.pf_z = 0.95;
  c.kld_z_is_quantile = true;
  c.kld_bin_xy = 0.3;
  c.kld_bin_theta = 0.1 + 0.2;  // 0.30000000000000004: doubles must round-trip exactly
  c.resample_interval = 2;
  c.resample_ess_fraction = 0.4;
  c.recovery_alpha_slow = 0.002;
  c.recovery_alpha_fast = 0.2;
  c.lost_misfit = 0.8;
  c.relocalize_when_lost = false;
  c.update_min_d = 0.1;
  c.update_min_a = 0.05;
  c.odom_jump_max_d = 3.0;
  c.odom_model_type = OdomModel::kAckermann;
  c.amcl_motion_conventions = false;
  c.alpha1 = 1e-5;
  c.alpha2 = 0.00201878;
  c.alpha3 = 0.03;
  c.alpha4 = 0.04;
  c.alpha5 = 0.05;
  c.wheelbase = 1.2;
  c.adaptive_motion_noise = false;
  c.motion_noise_margin = 11.3137;
  c.laser_model_type = LaserModel::kBeam;
  c.likelihood_combination = LikelihoodCombination::kAmclCubedSum;
  c.max_beams = 90;
  c.laser_min_range = 0.15;
  c.laser_max_range = 12.0;
  c.z_hit = 0.8;
  c.z_short = 0.02;
  c.z_max = 0.03;
  c.z_rand = 0.15;
  c.sigma_hit = 0.0530479;
  c.lambda_short = 0.4;
  c.laser_likelihood_max_dist = 1.5;
  c.likelihood_tempering = 0.0;  // the default: tracking_tempering needs the adaptive search
  c.tracking_tempering = 0.162786;
  c.tempering_ess_fraction = 0.2;
  c.unknown_cells_block_rays = true;
  c.ray_casting = RayCasting::kTable;
  c.range_table_angles = 256;
  c.range_table_budget_mb = 64.0;
  c.unmapped_obstacle_filter = false;
  c.threads = 2;
  c.seed = 18446744073709551615ULL;
  c.grain = 1024;
  return c;
}

TEST(ConfigYaml, WritesEveryFieldSoThatParseConfigReadsItBack) {
  const LocalizerConfig c = every_field_changed();
  const std::string yaml = config_yaml(c);
  const LoadedConfig back = parse_config(yaml, "written.yaml");
  EXPECT_TRUE(back.warnings.empty());
  EXPECT_TRUE(back.config == c) << yaml;
  EXPECT_DOUBLE_EQ(back.config.kld_bin_theta, 0.1 + 0.2);
  EXPECT_EQ(back.config.seed, c.seed);
  EXPECT_THAT(yaml, HasSubstr("odom_model_type: ackermann\n"));
  EXPECT_THAT(yaml, HasSubstr("laser_model_type: beam\n"));
  // Aliases are not written beside the keys they stand for.
  EXPECT_THAT(yaml, Not(HasSubstr("robot_model_type")));
  EXPECT_THAT(yaml, Not(HasSubstr("selective_resampling")));
}

TEST(ConfigYaml, WritesOnlyWhatDiffersFromTheBase) {
  EXPECT_EQ(config_yaml(LocalizerConfig{}), "");
  LocalizerConfig c;
  c.wheelbase = 1.2;
  c.max_beams = 90;
  EXPECT_EQ(config_yaml(c), "wheelbase: 1.2\nmax_beams: 90\n");
  // every_field_changed keeps the adaptive search (tracking_tempering needs it): a fixed
  // exponent is written and read back too.
  LocalizerConfig fixed;
  fixed.likelihood_tempering = 0.3;
  EXPECT_EQ(config_yaml(fixed), "likelihood_tempering: 0.3\n");
  EXPECT_TRUE(parse_config(config_yaml(fixed), "f.yaml").config == fixed);
  // Against nav2's defaults, the text holds what mote's defaults change, and read over nav2's
  // values (`defaults: nav2`) gives mote's defaults back.
  const std::string over_nav2 = config_yaml(LocalizerConfig{}, nav2_defaults());
  EXPECT_THAT(over_nav2, HasSubstr("max_particles: 500000\n"));
  EXPECT_TRUE(parse_config("defaults: nav2\n" + over_nav2, "n.yaml").config == LocalizerConfig{});
}

}  // namespace
}  // namespace mote
