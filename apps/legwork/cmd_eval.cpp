// legwork eval accent: the CoolMoves section 4.1 protocol (cross-subject,
// cross-trial, cross-dataset) for the accentuation engine, its ablation and
// the full-body IK baseline, with a report (Markdown, JSON, charts).
#include "command.hpp"

#include <legwork/eval/report.hpp>
#include <legwork/io/options.hpp>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <memory>

namespace legwork::cli {
namespace {

struct EvalArgs {
  std::string data, manifest, test, test_manifest, classes, protocols, out;
  bool quick = false, no_ablation = false, no_ik = false, skip_no_class = false, keep_first = false, video = false;
  int threads = 0, quick_trials = 4;
  double max_seconds = 0, quick_seconds = 12;
  // Engine switches (defaults = the engine's own defaults).
  int hop = -1, k = -1, speed_variants = -1;
  double threshold = -1, hand_ik = -1, foot_lift_height = -1, foot_lock_slack = -1, foot_swing_speed = -1;
  double ik_blend_min = -1, ik_blend_near = -1, ik_blend_far = -1, foot_lock_follow = -1, contact_on = -1, contact_off = -1;
  bool mirror = false, exact = false;
};

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
  cmd->add_option("--quick-trials", a->quick_trials, "--quick: trials per class")->check(CLI::PositiveNumber);
  cmd->add_option("--max-seconds", a->max_seconds, "score only the first seconds of each test trial (0 = all)");
  cmd->add_option("--threads", a->threads, "worker threads (default: all cores)")->check(CLI::NonNegativeNumber);
  cmd->add_flag("--video", a->video, "also write compare.mp4: truth, engine and IK side by side (needs ffmpeg)");
  cmd->add_flag("--no-ablation", a->no_ablation, "skip the ablation variants");
  cmd->add_flag("--no-ik", a->no_ik, "skip the IK baselines (on the database skeleton at the user's height, and on the subject's own skeleton)");
  cmd->add_flag("--skip-no-class", a->skip_no_class,
                "skip the no-class setting (one database of every class per fold, the class recognised from the input)");
  cmd->add_flag("--keep-first-frame", a->keep_first, "do not drop frame 0 (CMU files start with a T-pose)");
  cmd->add_option("--hop", a->hop, "engine: window hop in samples")->check(CLI::PositiveNumber);
  cmd->add_option("--k", a->k, "engine: neighbours per hand")->check(CLI::Range(1, 32));
  cmd->add_option("--threshold", a->threshold, "engine: distance threshold in typical distances (0 = none)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--speed-variants", a->speed_variants, "engine: speed-augmented copies per window")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--hand-ik", a->hand_ik, "engine: 0..1 pull of the synthesized arms onto the real hands")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--foot-lift-height", a->foot_lift_height,
                  "engine: metres a released foot is lifted on its way back (0 = slides along the floor)")
      ->check(CLI::Range(0.0, 0.5));
  cmd->add_option("--foot-lock-slack", a->foot_lock_slack,
                  "engine: metres the synthesized foot may move from a planted one before the plant creeps (0 = always)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--foot-swing-speed", a->foot_swing_speed,
                  "engine: m/s above which a free foot is swinging and clears the floor (0 = off)")
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_option("--ik-blend-min", a->ik_blend_min,
                  "engine: share of the IK body where the database covers the user (0..1, at most the maximum share)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--ik-blend-near", a->ik_blend_near,
                  "engine: match distance (typical distances) where the IK body's share starts to rise")
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option("--ik-blend-far", a->ik_blend_far,
                  "engine: match distance (typical distances) where the IK body's share reaches its maximum")
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option("--foot-lock-follow", a->foot_lock_follow,
                  "engine: seconds a planted foot takes to creep toward the synthesized one (0 = held still)")
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_option("--contact-on", a->contact_on, "engine: blended candidate contact above which a foot locks (0..1)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--contact-off", a->contact_off, "engine: blended candidate contact below which a locked foot lets go (0..1)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_flag("--mirror", a->mirror, "engine: add mirrored trials to every database");
  cmd->add_flag("--exact", a->exact, "engine: exact k-NN search instead of the fast approximate one");
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
    if (a->threshold >= 0) opt.config.threshold = a->threshold;
    if (a->hand_ik >= 0) opt.config.hand_ik = a->hand_ik;
    if (a->foot_lift_height >= 0) opt.config.foot_lift_height = a->foot_lift_height;
    if (a->foot_lock_slack >= 0) opt.config.foot_lock_slack = a->foot_lock_slack;
    if (a->foot_swing_speed >= 0) opt.config.foot_swing_speed = a->foot_swing_speed;
    if (a->contact_on >= 0) opt.config.contact_on = a->contact_on;
    if (a->contact_off >= 0) opt.config.contact_off = a->contact_off;
    if (a->ik_blend_min >= 0) opt.config.ik_blend_min = a->ik_blend_min;
    if (a->ik_blend_near >= 0) opt.config.ik_blend_near = a->ik_blend_near;
    if (a->ik_blend_far >= 0) opt.config.ik_blend_far = a->ik_blend_far;
    if (a->foot_lock_follow >= 0) opt.config.foot_lock_follow_seconds = a->foot_lock_follow;
    if (a->exact) opt.config.search = accent::SearchMode::Exact;
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
