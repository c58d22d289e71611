#pragma once
// Runs the evaluation protocols (protocol.hpp) for the accentuation engine,
// its ablation variants and the full-body IK baseline, fold by fold, in
// parallel over the machine's cores. Offline code: allocates, throws
// legwork::Error for unusable input (no trial loads, a fold leaks).
#include <legwork/accent/offline/run.hpp>
#include <legwork/accent/offline/builder.hpp>
#include <legwork/eval/metrics.hpp>
#include <legwork/eval/protocol.hpp>

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace legwork::eval {

// One configuration of the engine under evaluation (the engine itself, or an
// ablation: its switches are the engine's own BuildConfig / AccentConfig).
struct Variant {
  std::string key;    // "accent", "nn", "nn_align", "hop_2", ...
  std::string label;  // for tables and charts
  accent::BuildConfig build;
  accent::Settings config;
};
// The document's ablation (NN only -> + alignment -> + smoothing) and the
// extra choices (window hop, speed augmentation, mirroring, k, distance
// threshold, exact search) around a base configuration. `quick` keeps only
// the document's three steps.
std::vector<Variant> ablation_variants(const accent::BuildConfig& build, const accent::Settings& config, bool quick);

struct RunOptions {
  std::vector<Protocol> protocols{Protocol::CrossSubject, Protocol::CrossTrial};
  accent::BuildConfig build;    // the engine's configuration ("accent")
  accent::Settings config;
  bool ablation = true;         // ablation variants, on the cross-subject protocol
  bool quick_ablation = false;  // only the document's three ablation steps
  // The IK baseline, given what the engine is given (method "ik"): the
  // database's reference skeleton scaled to the user's standing height.
  bool ik = true;
  // The IK baseline on the held-out subject's own skeleton (true bone
  // lengths; method "ik_own", the baseline of earlier reports): information
  // the engine does not get.
  bool ik_own_skeleton = true;
  // The "no class given" setting (method "no_class"): per fold one database of
  // every class (the fold's held-out subject or trials left out), the engine
  // recognising the class (accent::Settings::recognize_class). Not for
  // cross-dataset folds.
  bool no_class = true;
  int threads = 0;              // 0 = std::thread::hardware_concurrency()
  double max_test_seconds = 0;  // > 0: score only the first seconds of each test trial
  bool drop_first_frame = true; // CMU files start with a synthetic T-pose
  MetricOptions metrics;
  std::function<void(const std::string&)> progress;  // one status line at a time
};

// One method on one fold.
struct MethodFold {
  bool ok = false;
  std::string error;          // why it could not run (e.g. every database trial filtered out)
  TrialMetrics metrics;       // frame-weighted over the fold's test trials
  long frames = 0;
  double seconds = 0;         // time in the per-frame solver only
  int database_windows = 0;   // accent variants
  // "no_class": frames whose recognised class is the fold's, and class
  // switches (both over the fold's test trials).
  long class_frames_right = 0;
  int class_switches = 0;
};

struct FoldResult {
  Fold fold;
  std::vector<std::string> test_ids;   // "SS_TT" of the test trials
  std::map<std::string, MethodFold> methods;  // key: "ik" or a Variant key
};

struct ProtocolResult {
  Protocol protocol = Protocol::CrossSubject;
  FoldPlan plan;
  std::vector<FoldResult> folds;
  std::vector<std::string> methods;  // keys run on this protocol, in order
};

struct DatasetSummary {
  std::string root;
  int trials = 0;
  std::map<std::string, int> trials_per_class, subjects_per_class;
  std::map<std::string, std::string> dropped;  // trial id -> why the engine's filter dropped it
};

// A dedicated speed measurement after the folds: the engine and the IK
// baseline on one held-out trial, single-threaded with nothing else of the
// run in flight, best of three passes (per-frame solver time only).
struct SpeedResult {
  std::string trial, fold;
  int frames = 0, database_windows = 0;
  double accent_frames_per_second = 0, ik_frames_per_second = 0;
  double accent_p99_us = 0;  // 99th percentile of the engine's per-frame update time (fastest pass)
  double accent_cpu_frames_per_second = 0;  // the same pass in thread CPU time (what one core delivers)
  // Fast-mode search recall@k against brute force on that trial's live
  // queries (the engine's k, eps and check budget): seeded with the previous
  // frame's results as the engine searches, and without seeds.
  double fast_recall = 0, fast_recall_unseeded = 0;
  // The fold's database saved to a file and loaded with its search index
  // (default LoadOptions: checksum verified; and without the checksum), best of 5.
  double load_ms = 0, load_ms_unverified = 0;
  std::size_t database_bytes = 0;
  // The same trial in the no-class setting (a database of every class but the
  // held-out subject's/trials, class recognised): speed, recall, load.
  int no_class_windows = 0;
  double no_class_frames_per_second = 0, no_class_cpu_frames_per_second = 0, no_class_p99_us = 0;
  double no_class_fast_recall = 0, no_class_fast_recall_unseeded = 0, no_class_load_ms = 0, no_class_load_ms_unverified = 0;
  std::size_t no_class_database_bytes = 0;
  // That trial's ground truth and both methods' outputs (for a comparison video).
  Motion truth, accent, ik;
};

struct EvalResult {
  std::vector<ProtocolResult> protocols;
  std::vector<Variant> variants;  // variants[0] = the engine ("accent")
  DatasetSummary data;
  SpeedResult speed;
  double seconds = 0;  // wall time of the whole run
  int threads = 1;
};

// `test` is only used for Protocol::CrossDataset (may be null otherwise).
EvalResult run_evaluation(const Catalogue& data, const Catalogue* test, const RunOptions& opt);

// Output motion of the IK baseline driven by a motion's head and hands (on
// the motion's own skeleton, at its rate); `seconds` gets the solver time.
Motion run_ik_baseline(const Motion& truth, double* seconds = nullptr);
// The same on `reference` (a database skeleton) scaled to the motion's
// standing height: what the engine knows of the user (its height only).
Motion run_ik_baseline_at_height(const Skeleton& reference, const Motion& truth, double* seconds = nullptr);

// The IK baseline (the VRIK-style full-body IK of legwork::ik) over a clip:
// one ik avatar on `skel` driven by the frames' head and hands, output at
// `fps` (one frame per input frame; a rejected frame repeats the last pose).
// Adds the solver's time to *seconds if given.
Motion run_ik_baseline(const Skeleton& skel, std::span<const TrackerFrame> frames, double fps, double* seconds = nullptr);

}  // namespace legwork::eval
