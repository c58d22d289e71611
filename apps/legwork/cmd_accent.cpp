// legwork accent build / run / bench: full-body accentuation from headset + controllers.
#include "command.hpp"

#include <legwork/accent/offline/builder.hpp>
#include <legwork/accent/offline/report.hpp>
#include <legwork/eval/accent_job.hpp>
#include <legwork/io/options.hpp>

#include <chrono>
#include <cstdio>
#include <memory>

namespace legwork::cli {
namespace {

using namespace legwork::accent;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// ---------------------------------------------------------------- build

struct BuildArgs {
  std::string data, out, classes, json_path, weights;
  std::vector<std::string> exclude;
  BuildConfig cfg;
};

void register_build(CLI::App& parent) {
  auto* cmd = parent.add_subcommand("build",
                                    "Build a motion database from BVH trials (classes from MANIFEST.tsv or bvh*/<class>/ folders).\n"
                                    "Example: legwork accent build --data ../shared/data/cmu --classes boxing,running --out box_run.lwdb");
  auto a = std::make_shared<BuildArgs>();
  cmd->add_option("--data", a->data, "folder laid out like data/cmu (MANIFEST.tsv, bvh/<class>/*.bvh)")->required();
  output_file(cmd->add_option("--out", a->out, "database file to write (.lwdb)"))->required();
  cmd->add_option("--classes", a->classes, "comma-separated classes (default: every class present)");
  cmd->add_option("--exclude", a->exclude, "trial files to leave out (e.g. a held-out trial), by manifest path, file name or pattern ('16_*': subject 16)");
  cmd->add_option("--fps", a->cfg.fps, "tracker rate the trials are resampled to (Hz)")->check(positive_number());
  cmd->add_option("--hop", a->cfg.hop, "samples between window ends (4 = 44 ms at 90 Hz)")->check(positive_number());
  cmd->add_option("--correlation", a->cfg.correlation_threshold, "keep trials whose hand-foot |Pearson r| exceeds this");
  cmd->add_option("--speeds", a->cfg.speed_variants, "re-timed copies per window (0 = none; 2 = x0.5 and x1.5)")->check(non_negative_number());
  cmd->add_option("--speed-range", a->cfg.speed_range, "largest relative speed change of the re-timed copies")->check(CLI::Range(0.0, 0.9));
  cmd->add_flag("--mirror", a->cfg.mirror, "add left/right mirrored copies of every trial");
  cmd->add_option("--weights", a->weights, "feature group weights position,velocity,acceleration (default 1,1,0.5)");
  output_file(cmd->add_option("--json", a->json_path, "write the build report (per-trial verdicts) as JSON"));
  cmd->callback([a] {
    require_extension("--out", a->out, {".lwdb"});
    if (!a->weights.empty()) {
      const auto w = io::parse_number_list(a->weights, 3, "--weights", "position,velocity,acceleration weights such as 1,1,0.5");
      for (std::size_t i = 0; i < 3; ++i) a->cfg.group_weight[i] = w[i];
    }
    const auto t0 = Clock::now();
    auto trials = load_trials(a->data, split_commas(a->classes), a->exclude, progress_bar("reading"));
    if (trials.empty()) throw Error("no trials selected in '" + a->data + "'");
    const double read_s = seconds_since(t0);
    BuildReport report;
    Database db;
    try {
      db = build_database(trials, a->cfg, &report, progress_bar("building"));
    } catch (const Error&) {
      std::printf("%s", class_table(report).c_str());
      throw;
    }
    save_database(a->out, db);
    std::printf("%s", class_table(report).c_str());
    int kept = 0;
    for (const auto& t : report.trials) kept += t.kept;
    std::printf("database: %d of %zu trials kept, %d classes, %d windows, %d poses, %.1f MB, built in %.2f s (+ %.2f s reading BVH)\n",
                kept, report.trials.size(), db.class_count(), report.windows, report.poses, report.bytes / 1e6, report.seconds, read_s);
    std::printf("skeleton: %s (%d joints, %.2f m tall)\n", report.skeleton_from.c_str(), db.joint_count(), db.height());
    announce("database", a->out);
    if (!a->json_path.empty()) {
      auto j = build_report_json(report, db, a->cfg, a->out);
      j["read_seconds"] = read_s;
      io::write_text_file(a->json_path, j.dump(2) + "\n");
      announce("build report", a->json_path);
    }
  });
}

// ---------------------------------------------------------------- run



void register_run(CLI::App& parent) {
  auto* cmd = parent.add_subcommand(
      "run",
      "Accentuate a session: a BVH trial (only its head and wrists are used as headset + controllers; the rest is\n"
      "ground truth for the video) or a headset CSV (time, head xyz + quaternion, hands xyz).\n"
      "Example: legwork accent run --db box_run.lwdb --input data/cmu/bvh/walking/07_02.bvh --drop-first --out walk.glb "
      "--video walk.mp4 --compare-ik");
  auto a = std::make_shared<eval::AccentJob>();
  cmd->add_option("--db", a->db, "database built by 'legwork accent build'")->required()->check(CLI::ExistingFile);
  cmd->add_option("--input", a->input, "session: .bvh trial or .csv headset recording")->required()->check(CLI::ExistingFile);
  cmd->add_option("--scale", a->input_options.scale, "BVH input: file units -> metres (0 = detect)")->check(non_negative_number());
  cmd->add_flag("--drop-first", a->input_options.drop_first, "BVH input: drop frame 0 (the CMU T-pose)");
  cmd->add_flag("--lenient", a->input_options.lenient, "BVH input: accept more motion lines than 'Frames:' declares");
  output_file(cmd->add_option("--out", a->out, "result: .glb or .bvh"))->required();
  output_file(cmd->add_option("--video", a->video, "side-by-side MP4: input, accentuated body (and IK baseline, ground truth)"));
  cmd->add_flag("--compare-ik", a->compare_ik, "add the IK baseline (the VRIK-style full-body IK of legwork::ik) to the video and the JSON");
  output_file(cmd->add_option("--json", a->json_path, "per-frame match statistics and summary as JSON"));
  cmd->add_option("--mode", a->mode, "search: fast (KD-tree, approximate), exact (KD-tree) or brute");
  cmd->add_option("--k", a->k, "matches per hand (the paper used 5)")->capture_default_str()->check(CLI::Range(1, kMaxK));
  cmd->add_option("--k-left", a->k_left, "matches for the left hand (default --k)")->check(CLI::Range(0, kMaxK));
  cmd->add_option("--k-right", a->k_right, "matches for the right hand (default --k)")->check(CLI::Range(0, kMaxK));
  cmd->add_option("--threshold", a->threshold, "match distance limit in typical-distance units (0 = none)")->check(non_negative_number());
  cmd->add_flag("--no-align", a->no_align, "skip the rotation alignment of candidates");
  cmd->add_flag("--no-smooth", a->no_smooth, "skip the temporal smoothing (both the paper's EWMA and the spring filter)");
  cmd->add_option("--smooth-halflife", a->smooth_halflife,
                  "seconds for the spring filter on the blended rotations to halve an error (0 = the paper's EWMA only)")
      ->capture_default_str()
      ->check(non_negative_number());
  cmd->add_option("--lying-root-smoothing", a->lying_root_smoothing,
                  "times the spring's half-life on the root for a lying user (head at most 0.5 of their height up), "
                  "so a swimmer's body does not wobble its feet across the floor (1 = off)")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 20.0));
  cmd->add_option("--other-class-cost", a->other_class_cost,
                  "no class given: also search the classes other than the recognised one, their distances times "
                  "this factor (1 = no preference; 0 = the recognised class only)")
      ->capture_default_str()
      ->check(zero_or_factor());
  cmd->add_option("--search-interval", a->search_interval,
                  "seconds between two searches of the database; in between each hand's matches are continued in "
                  "their trials, as motion matching does (0 = search every frame)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--lying-crown", a->lying_crown,
                  "share of a lying user's candidate turn taken from the headset (yaw from its crown, which points "
                  "away from the feet; roll from its face), and of the standing IK body taken out (0 = off)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--smooth-feedforward", a->smooth_feedforward,
                  "share of the matched candidates' own motion the smoothing plays forward, so a moving body does not "
                  "trail its target (0 = none: the filters pull toward a still target and lag)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_flag("--no-limits", a->no_limits, "skip the joint angle limits");
  cmd->add_option("--height", a->height, "user height in metres (default: the BVH's standing height, or the database's)")->check(positive_number());
  cmd->add_option("--exaggerate", a->exaggerate, "scale the input hands about the head before matching")->check(positive_number());
  cmd->add_option("--classes", a->classes, "comma-separated classes to match against (default: all in the database)");
  cmd->add_flag("--no-class-recognition", a->no_class_recognition,
                "with several classes allowed, search all of them every frame instead of recognising the activity and "
                "searching only its class");
  cmd->add_option("--class-hold", a->class_hold, "class recognition: seconds another class must stay better before a switch")
      ->capture_default_str()
      ->check(non_negative_number());
  cmd->add_option("--class-margin", a->class_margin, "class recognition: relative cost margin another class needs (0..1)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.99));
  cmd->add_option("--hand-ik", a->hand_ik,
                  "0..1: pull the synthesized arms onto the real hands (needs legwork::ik); 1 = wrists on the controllers, "
                  "0 = the paper's pure synthesis")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--foot-lift-height", a->foot_lift_height,
                  "metres a foot released at the end of a contact is lifted on its way back to the synthesized foot (0 = "
                  "slides along the floor)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.5));
  cmd->add_option("--foot-lock-slack", a->foot_lock_slack,
                  "metres the synthesized foot may move away from a planted foot before the plant creeps after it (0 = "
                  "it always creeps)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--foot-lock-hold", a->foot_lock_hold,
                  "seconds a planted foot stays put before it creeps after the synthesized foot (0 = it creeps from "
                  "touch-down)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_option("--travel-weight", a->travel_weight,
                  "weight of the user's head travel (horizontal speed over 0.2 and 0.6 s, vertical velocity, height) "
                  "against the hand features when ranking candidates: walking users get walking legs (0 = hand "
                  "features only)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option("--max-head-height-diff", a->max_head_height_diff,
                  "while the user stands upright, reject candidates whose head is lower than the user's by more than "
                  "this share of body height (a lying swimmer under a standing user); while the user is lower, those "
                  "whose head is higher by more, unless none would be left (0 = off)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 2.0));
  cmd->add_option("--foot-swing-speed", a->foot_swing_speed,
                  "m/s above which a free foot counts as swinging and is lifted to clear the floor by --foot-lift-height "
                  "(0 = off)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_flag("--no-floor", a->no_floor,
                "let feet follow the synthesized pose below the floor (default: never through it; the knee bends, "
                "feet pushed into it stand on it)");
  cmd->add_option("--floor-height", a->floor_height, "metres: the play area's floor, y = this (0 = a floor-level tracking origin)")
      ->capture_default_str()
      ->check(CLI::Range(-10.0, 10.0));
  cmd->add_option("--max-head-tilt", a->max_tilt, "reject candidates whose head tilt differs from the headset's by more than this (degrees, 0 = off)")
      ->check(non_negative_number());
  cmd->add_option("--target", a->target, "retarget the result by joint roles onto this BVH's skeleton");
  output_file(cmd->add_option("--save-session", a->save_session, "also write the input as a headset session CSV (the format --input reads)"));
  cmd->callback([a] { eval::run_accent_job(*a); });
#include <legwork/io/options.hpp>
}

void register_accent(CLI::App& app) {
  auto* cmd = app.add_subcommand("accent",
                                 "Full-body accentuation from headset + two controllers by nearest-neighbour synthesis over a mocap\n"
                                 "database (CoolMoves). Subcommands: build, run (figures: build/bench/accent_speed).");
  cmd->require_subcommand(1);
  register_build(*cmd);
  register_run(*cmd);
}

LEGWORK_COMMAND(register_accent, 50);

}  // namespace
}  // namespace legwork::cli
