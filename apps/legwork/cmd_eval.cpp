// legwork eval accent: the CoolMoves section 4.1 protocol (cross-subject,
// cross-trial, cross-dataset) for the accentuation engine, its ablation and
// the full-body IK baseline, with a report (Markdown, JSON, charts).
#include "command.hpp"

#include <legwork/eval/report.hpp>
#include <legwork/io/options.hpp>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <tuple>

namespace legwork::cli {
namespace {

// The engine's numeric settings the evaluation can override, one row each:
// flag, the accent::Settings field it sets, its range and its help.
struct EngineOption {
  const char* flag;
  double accent::Settings::*field;
  double lo, hi;
  const char* help;
};
constexpr std::array<EngineOption, 21> kEngineOptions{{
    {"--threshold", &accent::Settings::threshold, 0.0, std::numeric_limits<double>::infinity(), "engine: distance threshold in typical distances (0 = none)"},
    {"--hand-ik", &accent::Settings::hand_ik, 0.0, 1.0, "engine: 0..1 pull of the synthesized arms onto the real hands"},
    {"--foot-lift-height", &accent::Settings::foot_lift_height, 0.0, 0.5,
     "engine: metres a released foot is lifted on its way back (0 = slides along the floor)"},
    {"--foot-lock-slack", &accent::Settings::foot_lock_slack, 0.0, 1.0,
     "engine: metres the synthesized foot may move from a planted one before the plant creeps (0 = always)"},
    {"--foot-swing-speed", &accent::Settings::foot_swing_speed, 0.0, 10.0,
     "engine: m/s above which a free foot is swinging and clears the floor (0 = off)"},
    {"--travel-weight", &accent::Settings::travel_weight, 0.0, 100.0,
     "engine: weight of the user's head travel (speed, vertical velocity, height) against the hand features when "
     "ranking candidates (0 = hand features only)"},
    {"--ik-blend-min", &accent::Settings::ik_blend_min, 0.0, 1.0,
     "engine: share of the IK body where the database covers the user (0..1, at most the maximum share)"},
    {"--ik-blend-near", &accent::Settings::ik_blend_near, 0.0, 100.0,
     "engine: match distance (typical distances) where the IK body's share starts to rise"},
    {"--ik-blend-far", &accent::Settings::ik_blend_far, 0.0, 100.0,
     "engine: match distance (typical distances) where the IK body's share reaches its maximum"},
    {"--foot-lock-follow", &accent::Settings::foot_lock_follow_seconds, 0.0, 10.0,
     "engine: seconds a planted foot takes to creep toward the synthesized one (0 = held still)"},
    {"--foot-lock-hold", &accent::Settings::foot_lock_hold_seconds, 0.0, 10.0,
     "engine: seconds a planted foot stays put before it creeps (0 = it creeps from touch-down)"},
    {"--contact-on", &accent::Settings::contact_on, 0.0, 1.0,
     "engine: blended candidate contact above which a foot locks (0..1)"},
    {"--contact-off", &accent::Settings::contact_off, 0.0, 1.0,
     "engine: blended candidate contact below which a locked foot lets go (0..1)"},
    {"--max-head-height-diff", &accent::Settings::max_head_height_diff, 0.0, 2.0,
     "engine: reject candidates whose head height over body height differs from the user's by more than this (0 = off)"},
    {"--smooth-halflife", &accent::Settings::smooth_halflife, 0.0, 1.0,
     "engine: half-life (s) of the spring filter on the synthesized body (0 = the paper's EWMA only)"},
    {"--smooth-feedforward", &accent::Settings::smooth_feedforward, 0.0, 1.0,
     "engine: share of the matched candidates' own motion the smoothing plays forward (0 = none: it lags a moving body)"},
    {"--lying-root-smoothing", &accent::Settings::lying_root_smoothing, 1.0, 20.0,
     "engine: times the spring's half-life on the root for a lying user (1 = off)"},
    {"--other-class-cost", &accent::Settings::other_class_cost, 0.0, 1e6,
     "engine, no class given: factor on the distances of the classes other than the recognised one, also searched (0 = the recognised class only)"},
    {"--search-interval", &accent::Settings::search_interval, 0.0, 1.0,
     "engine: seconds between two searches of the database; in between each hand's matches are continued in their trials (0 = search every frame)"},
    {"--lying-crown", &accent::Settings::lying_crown, 0.0, 1.0,
     "engine: share of a lying user's candidate turn taken from the headset (yaw from its crown, roll from its face), and of the standing IK body taken out (0 = off)"},
    {"--floor-height", &accent::Settings::floor_height, -10.0, 10.0, "engine: metres, the play area's floor (y = this)"},
}};

struct EvalArgs {
  std::string data, manifest, test, test_manifest, classes, protocols, out;
  bool quick = false, no_ablation = false, no_ik = false, skip_no_class = false, keep_first = false, video = false;
  int threads = 0, quick_trials = 4;
  double max_seconds = 0, quick_seconds = 12;
  // Engine switches (unset = the engine's own defaults).
  int hop = -1, k = -1, speed_variants = -1;
  std::array<std::optional<double>, kEngineOptions.size()> engine;  // one per kEngineOptions row
  bool mirror = false, exact = false, no_floor = false;
};

// One override slot per option row: a row added to the table without growing
// the slots would write past them (it did once).
static_assert(std::tuple_size_v<decltype(EvalArgs::engine)> == kEngineOptions.size());

void register_eval(CLI::App& app) {
  auto* group = app.add_subcommand("eval", "Evaluate methods against motion-capture ground truth.");
  group->require_subcommand(1);
  auto* cmd = group->add_subcommand(
      "accent",
      "Reproduce CoolMoves section 4.1: leave-one-subject-out and leave-one-trial-out per class for the\n"
      "accentuation engine, its ablation and the full-body IK baseline; report.md, report.json and charts.\n"
      "Examples:\n"
      "  legwork eval accent --data ../shared/data/cmu --out eval-report\n"
      "  legwork eval accent --data data/cmu --quick --out quick-report\n"
      "  legwork eval accent --data ../shared/data/cmu --test my-recordings --out cross-dataset\n"
      "  legwork eval accent --data ../shared/data/cmu --classes boxing,running --protocols cross_subject");
  auto a = std::make_shared<EvalArgs>();
  cmd->add_option("--data", a->data, "folder of BVH trials laid out like ../shared/data/cmu (the database side)")
      ->required();
  cmd->add_option("--manifest", a->manifest, "manifest TSV (columns file, class, subject, trial) for --data");
  cmd->add_option("--test", a->test, "cross-dataset: score every trial of this folder against a --data database");
  cmd->add_option("--test-manifest", a->test_manifest, "manifest TSV for --test");
  cmd->add_option("--classes", a->classes, "comma-separated classes (default: every class present)");
  cmd->add_option("--protocols", a->protocols,
                  "comma-separated: cross_subject, cross_trial, cross_dataset (default: the first two, or "
                  "cross_dataset with --test)");
  cmd->add_option("--out", a->out, "write report.md, report.json and charts (PNG + SVG) into this folder");
  cmd->add_flag("--quick", a->quick, "a small subset for CI: few trials per class, short clips, 3-step ablation");
  cmd->add_option("--quick-trials", a->quick_trials, "--quick: trials per class")->check(positive_number());
  cmd->add_option("--max-seconds", a->max_seconds, "score only the first seconds of each test trial (0 = all)");
  cmd->add_option("--threads", a->threads, "worker threads (default: all cores)")->check(non_negative_number());
  cmd->add_flag("--video", a->video, "also write compare.mp4: truth, engine and IK side by side (needs ffmpeg)");
  cmd->add_flag("--no-ablation", a->no_ablation, "skip the ablation variants");
  cmd->add_flag("--no-ik", a->no_ik, "skip the IK baselines (on the database skeleton at the user's height, and on the subject's own skeleton)");
  cmd->add_flag("--skip-no-class", a->skip_no_class,
                "skip the no-class setting (one database of every class per fold, the class recognised from the input)");
  cmd->add_flag("--keep-first-frame", a->keep_first, "do not drop frame 0 (CMU files start with a T-pose)");
  cmd->add_option("--hop", a->hop, "engine: window hop in samples")->check(positive_number());
  cmd->add_option("--k", a->k, "engine: neighbours per hand")->check(CLI::Range(1, 32));
  cmd->add_option("--speed-variants", a->speed_variants, "engine: speed-augmented copies per window")
      ->check(non_negative_number());
  for (std::size_t i = 0; i < kEngineOptions.size(); ++i) {
    const EngineOption& o = kEngineOptions[i];
    CLI::Option* opt = cmd->add_option(o.flag, a->engine[i], o.help);
    if (o.field == &accent::Settings::other_class_cost)
      opt->check(zero_or_factor());
    else
      opt->check(std::isinf(o.hi) ? non_negative_number() : CLI::Validator(CLI::Range(o.lo, o.hi)));
  }
  cmd->add_flag("--mirror", a->mirror, "engine: add mirrored trials to every database");
  cmd->add_flag("--exact", a->exact, "engine: exact k-NN search instead of the fast approximate one");
  cmd->add_flag("--no-floor", a->no_floor, "engine: feet may go through the floor (floor = false)");
  cmd->callback([a] {
    if (a->video && a->out.empty()) throw Error("--video needs --out DIR");
    if (!a->out.empty()) io::require_writable_folder(a->out, "--out");
    const auto classes = split_commas(a->classes);
    eval::Catalogue data = eval::read_catalogue(a->data, a->manifest, classes);
    std::unique_ptr<eval::Catalogue> test;
    if (!a->test.empty()) test = std::make_unique<eval::Catalogue>(eval::read_catalogue(a->test, a->test_manifest, classes));
    eval::RunOptions opt;
    opt.protocols = eval::parse_protocols(a->protocols, test != nullptr);
    for (auto p : opt.protocols)
      if (p == eval::Protocol::CrossDataset && !test) throw Error("--protocols cross_dataset needs --test DIR");
    if (a->quick) {
      data = eval::quick_subset(data, a->quick_trials);
      if (test) *test = eval::quick_subset(*test, a->quick_trials);
      opt.quick_ablation = true;
      opt.max_test_seconds = a->quick_seconds;
    }
    if (a->max_seconds > 0) opt.max_test_seconds = a->max_seconds;
    opt.ablation = !a->no_ablation;
    opt.ik = !a->no_ik;
    opt.ik_own_skeleton = !a->no_ik;
    opt.no_class = !a->skip_no_class;
    opt.threads = a->threads;
    opt.drop_first_frame = !a->keep_first;
    if (a->hop > 0) opt.build.hop = a->hop;
    if (a->speed_variants >= 0) opt.build.speed_variants = a->speed_variants;
    opt.build.mirror = a->mirror;
    if (a->k > 0) opt.config.k_left = opt.config.k_right = a->k;
    for (std::size_t i = 0; i < kEngineOptions.size(); ++i)
      if (a->engine[i]) opt.config.*kEngineOptions[i].field = *a->engine[i];
    if (a->exact) opt.config.search = accent::SearchMode::Exact;
    if (a->no_floor) opt.config.floor = false;
    opt.progress = io::status_printer("[eval] ");

    const eval::EvalResult res = eval::run_evaluation(data, test.get(), opt);
    if (isatty(fileno(stderr))) std::fprintf(stderr, "\n");
    const nlohmann::json report = eval::report_json(res);
    std::printf("%s", eval::report_summary(report).c_str());
    std::printf("%zu trials, %.1f s on %d threads\n", data.trials.size(), res.seconds, res.threads);
    if (!a->out.empty()) {
      for (const auto& f : eval::write_report(res, a->out))
        if (f.ends_with(".md") || f.ends_with(".json")) announce("report", f);
        else if (f.ends_with(".png")) announce("chart (and .svg)", f);
      if (a->video) announce("video", eval::write_comparison_video(res, a->out));
    }
  });
}

LEGWORK_COMMAND(register_eval, 90);

}  // namespace
}  // namespace legwork::cli
