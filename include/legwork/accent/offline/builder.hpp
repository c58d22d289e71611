#pragma once
// Offline: building an accentuation database from BVH trials (CoolMoves 3.1.1-3.1.2).
// Steps per trial: resample to the tracker rate, map onto the database
// skeleton (same joint names: rotations copied; other rigs: by roles, see
// retarget.hpp), express hands and feet relative to the head, keep the trial
// only if its hand-foot correlation passes the threshold, cut windows every
// `hop` samples (plus re-timed speed variants and optional mirrored copies),
// then normalise and project the features. May allocate and throw
// legwork::Error with the file at fault.
#include <legwork/accent/database.hpp>

#include <array>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace legwork::accent {

// One input trial: the motion (CMU T-pose frame already dropped) and labels.
struct TrialInput {
  std::string file, cls;
  int subject = 0, trial = 0;
  Motion motion;
};

struct BuildConfig {
  double fps = 90.0;  // tracker rate; windows are kWindow samples at this rate
  int hop = 4;        // samples between window ends (4 = 44 ms; the document used 50 ms)
  double correlation_threshold = 0.1;  // keep trials with hand-foot |r| above this
  // Speed augmentation: `speed_variants` extra copies of every window re-timed
  // by factors spread evenly over [1 - speed_range, 1 + speed_range] (1 excluded):
  // a factor s samples the source at s times the rate, so velocities scale by s
  // and accelerations by s^2, ending on the same (candidate) frame.
  int speed_variants = 2;
  double speed_range = 0.5;
  bool mirror = false;  // add left/right mirrored copies of every trial
  // Feature weights per group (position, velocity, acceleration), applied on
  // top of the per-dimension 1/std normalisation.
  std::array<double, 3> group_weight{1.0, 1.0, 0.5};
  int typical_samples = 300;  // windows sampled to estimate typical_distance
};

struct TrialVerdict {
  std::string file, cls;
  bool kept = false;
  double correlation = 0;
  int windows = 0;
  std::string reason;  // why it was dropped, or how it was mapped
};

struct BuildReport {
  std::vector<TrialVerdict> trials;
  int windows = 0, poses = 0;
  double seconds = 0;
  std::size_t bytes = 0;
  std::string skeleton_from;  // the trial whose skeleton the database uses
};

using Progress = std::function<void(int done, int total, const std::string& what)>;

// Reads the trials of `classes` (empty = all) from a CMU-style folder: rows of
// DIR/MANIFEST.tsv (columns file, class, subject, trial) or, without a
// manifest, DIR/bvh*/<class>/*.bvh. Frame 0 (the T-pose) is dropped.
// `exclude` lists files (as in the manifest, or basenames) to leave out; one matching no chosen trial is an error.
std::vector<TrialInput> load_trials(const std::string& dir, const std::vector<std::string>& classes,
                                    const std::vector<std::string>& exclude = {}, const Progress& progress = {});

// Reusable per-trial preparation, so leave-one-out evaluations can assemble
// many databases from one pass over the data.
struct PreparedTrial {
  TrialInfo info;
  bool kept = false;
  std::string reason;
  Motion motion;                     // on the reference skeleton at BuildConfig::fps
  std::array<std::vector<Vec3>, 2> hands;           // head-relative, per frame
  Motion mirrored;                   // empty unless BuildConfig::mirror
  std::array<std::vector<Vec3>, 2> mirrored_hands;
  // Per frame, 1 while the left [0] / right [1] foot is planted (foot_contacts
  // on foot height and speed), for `motion` and `mirrored`.
  std::array<std::vector<char>, 2> contacts, mirrored_contacts;
  // Per frame, the head joint's world position (metres), for the travel terms.
  std::vector<Vec3> head, mirrored_head;
};

// The skeleton a database of these trials uses: that of the first trial on the
// most common skeleton (by joint names).
Skeleton reference_skeleton(std::span<const TrialInput> trials);
// Hand-foot correlation: mean |Pearson r| over the x, y, z series of the four
// hand-foot pairs, positions relative to the head.
double hand_foot_correlation(const Motion& m);
PreparedTrial prepare_trial(const TrialInput& t, const Skeleton& reference, const BuildConfig& cfg);
// Database from prepared trials (dropped ones are skipped). Throws
// legwork::Error when no window remains.
Database assemble_database(std::span<const PreparedTrial* const> trials, const Skeleton& reference,
                           const BuildConfig& cfg, BuildReport* report = nullptr);
// All of the above in one call.
Database build_database(std::span<const TrialInput> trials, const BuildConfig& cfg, BuildReport* report = nullptr,
                        const Progress& progress = {});

// Speed factors used for a config (first = 1).
std::vector<double> speed_factors(const BuildConfig& cfg);

}  // namespace legwork::accent
