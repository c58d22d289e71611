// Offline database builder (CoolMoves 3.1.1-3.1.2).
#include <legwork/accent/offline/builder.hpp>
#include <legwork/core/stats.hpp>
#include <legwork/accent/offline/retarget.hpp>

#include "../database_impl.hpp"

#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/core/mirror.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/catalogue.hpp>
#include <legwork/io/text.hpp>
#include <legwork/core/contacts.hpp>

#include <Eigen/Eigenvalues>

#include <fnmatch.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <sstream>

namespace legwork::accent {
namespace {

namespace fs = std::filesystem;

// An exclusion names a trial by its manifest path or its file name, or matches either as a
// shell pattern (fnmatch: '16_*' leaves out subject 16, 'bvh/running/*' a class).
bool excluded(const std::string& file, const std::vector<std::string>& exclude) {
  const std::string name = fs::path(file).filename().string();
  for (const auto& e : exclude)
    if (file == e || name == fs::path(e).filename().string() || fnmatch(e.c_str(), file.c_str(), FNM_PATHNAME) == 0 ||
        fnmatch(e.c_str(), name.c_str(), 0) == 0)
      return true;
  return false;
}

// A joint's world path over the motion's frames (pos: joint_positions(m)).
std::vector<Vec3> joint_path(const Motion& m, const std::vector<Vec3>& pos, Role role) {
  const int nj = m.joint_count();
  const auto j = static_cast<std::size_t>(m.skeleton.roles[role]);
  std::vector<Vec3> out(static_cast<std::size_t>(m.frame_count()));
  for (int f = 0; f < m.frame_count(); ++f) out[static_cast<std::size_t>(f)] = pos[static_cast<std::size_t>(f) * static_cast<std::size_t>(nj) + j];
  return out;
}

// A joint's path relative to the head's path (same length).
std::vector<Vec3> head_relative(const Motion& m, const std::vector<Vec3>& pos, Role role, const std::vector<Vec3>& head) {
  std::vector<Vec3> out = joint_path(m, pos, role);
  for (std::size_t f = 0; f < out.size(); ++f) out[f] -= head[f];
  return out;
}

Vec3 sample_path(const std::vector<Vec3>& path, double frame) {
  const double last = static_cast<double>(path.size() - 1);
  frame = std::clamp(frame, 0.0, last);
  const auto i0 = static_cast<std::size_t>(std::floor(frame));
  const std::size_t i1 = std::min(i0 + 1, path.size() - 1);
  const double t = frame - static_cast<double>(i0);
  return t == 0.0 ? path[i0] : Vec3((1 - t) * path[i0] + t * path[i1]);
}

// The travel terms (database.hpp, Travel) at source frame `end` of a head path
// played at `speed` (source frames per played frame): displacements over the
// last played seconds, shorter at the start of a trial.
Travel head_travel(const std::vector<Vec3>& head, int end, double speed, double fps, double height) {
  const Vec3 now = head[static_cast<std::size_t>(end)];
  auto velocity = [&](double seconds) -> Vec3 {
    const double from = std::max(0.0, end - seconds * fps * speed);
    const double played = (end - from) / (fps * speed);
    return played > 0 ? Vec3((now - sample_path(head, from)) / played) : Vec3::Zero();
  };
  const Vec3 a = velocity(kTravelShort), b = velocity(kTravelLong), v = velocity(kTravelVertical);
  return {static_cast<float>(std::hypot(a.x(), a.z())), static_cast<float>(std::hypot(b.x(), b.z())),
          static_cast<float>(v.y()), static_cast<float>(now.y() / height)};
}

// 1 / standard deviation of each travel term over the windows.
Travel travel_scale(const std::vector<Travel>& travel) {
  Travel out{1, 1, 1, 1};
  if (travel.empty()) return out;
  for (int d = 0; d < kTravelDim; ++d) {
    double sum = 0, sum2 = 0;
    for (const Travel& t : travel) sum += t[static_cast<std::size_t>(d)], sum2 += double{t[static_cast<std::size_t>(d)]} * t[static_cast<std::size_t>(d)];
    const double n = static_cast<double>(travel.size()), mean = sum / n;
    const double sd = std::sqrt(std::max(sum2 / n - mean * mean, 0.0));
    out[static_cast<std::size_t>(d)] = static_cast<float>(1.0 / std::max(sd, 1e-3));
  }
  return out;
}

// The 72 x 27 matrix W with raw_feature(w) = W * (stacked window positions).
Eigen::Matrix<double, kRawDim, kPosDim> raw_feature_matrix(double fps) {
  Eigen::Matrix<double, kRawDim, kPosDim> W;
  for (int k = 0; k < kPosDim; ++k) {
    HandWindow w;
    for (auto& p : w) p.setZero();
    w[static_cast<std::size_t>(k / 3)][k % 3] = 1.0;
    RawFeature f;
    raw_feature(w, fps, f);
    for (int d = 0; d < kRawDim; ++d) W(d, k) = f[static_cast<std::size_t>(d)];
  }
  return W;
}

// Foot contacts are kept only while the head's up axis is within 45 degrees of vertical.
constexpr double kContactUpright = 0.7071;

int group_of(int raw_dim) { return raw_dim < kPosDim ? 0 : raw_dim < kPosDim + 3 * (kWindow - 1) ? 1 : 2; }

using PosVec = Eigen::Matrix<double, kPosDim, 1>;
PosVec stack(const HandWindow& w) {
  PosVec p;
  for (int i = 0; i < kWindow; ++i) p.segment<3>(3 * i) = w[static_cast<std::size_t>(i)];
  return p;
}

}  // namespace

std::vector<double> speed_factors(const BuildConfig& cfg) {
  // Slower copies below 1, faster above (one more of them for an odd count),
  // each side spread evenly up to speed_range: distinct factors, no copy twice.
  std::vector<double> s{1.0};
  const int below = cfg.speed_variants / 2, above = cfg.speed_variants - below;
  for (int i = 1; i <= above; ++i) {
    if (i <= below) s.push_back(1.0 - cfg.speed_range * i / below);
    s.push_back(1.0 + cfg.speed_range * i / above);
  }
  return s;
}

std::vector<TrialInput> load_trials(const std::string& dir, const std::vector<std::string>& classes,
                                    const std::vector<std::string>& exclude, const Progress& progress) {
  if (!fs::is_directory(dir)) throw Error("data folder '" + dir + "' does not exist");
  const io::Catalogue catalogue = io::read_catalogue(dir, "", classes, /*cmu_names=*/false);
  // An exclusion that matches nothing is a typo that would leak a held-out trial into the database.
  for (const auto& e : exclude)
    if (std::none_of(catalogue.trials.begin(), catalogue.trials.end(), [&](const io::TrialEntry& t) { return excluded(t.file, {e}); }))
      throw Error("exclude '" + e + "' matches no trial of '" + dir + "'" + (classes.empty() ? "" : " in the chosen classes") +
                  " (name a file as in the manifest, e.g. '" +
                  (catalogue.trials.empty() ? std::string("bvh/walking/07_01.bvh") : catalogue.trials.front().file) +
                  "', by its file name, or a pattern such as '16_*')");
  std::vector<io::TrialEntry> chosen;
  for (const auto& t : catalogue.trials)
    if (!excluded(t.file, exclude)) chosen.push_back(t);
  std::vector<TrialInput> out;
  out.reserve(chosen.size());
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    const auto& r = chosen[i];
    if (progress) progress(static_cast<int>(i), static_cast<int>(chosen.size()), r.file);
    io::BvhReadOptions opt;
    opt.drop_first_frame = true;  // CMU's synthetic T-pose (DAZ: the reference pose)
    TrialInput t{r.file, r.cls, r.subject, r.trial, io::load_bvh(r.path, opt)};
    out.push_back(std::move(t));
  }
  if (progress) progress(static_cast<int>(chosen.size()), static_cast<int>(chosen.size()), "");
  return out;
}

Skeleton reference_skeleton(std::span<const TrialInput> trials) {
  if (trials.empty()) throw Error("accent build: no trials given");
  std::map<std::vector<std::string>, int> count;
  for (const auto& t : trials) ++count[t.motion.skeleton.names];
  const auto best = std::max_element(count.begin(), count.end(), [](auto& a, auto& b) { return a.second < b.second; });
  for (const auto& t : trials)
    if (t.motion.skeleton.names == best->first) return t.motion.skeleton;
  return trials.front().motion.skeleton;
}

double hand_foot_correlation(const Motion& m) {
  const auto pos = joint_positions(m);
  const std::array<Role, 2> hands{Role::LeftHand, Role::RightHand};
  const std::array<Role, 2> feet{Role::LeftAnkle, Role::RightAnkle};
  double sum = 0;
  int n = 0;
  const auto head = joint_path(m, pos, Role::Head);
  for (Role h : hands) {
    const auto hp = head_relative(m, pos, h, head);
    for (Role f : feet) {
      const auto fp = head_relative(m, pos, f, head);
      for (int a = 0; a < 3; ++a) {
        std::vector<double> x(hp.size()), y(fp.size());
        for (std::size_t i = 0; i < hp.size(); ++i) x[i] = hp[i][a], y[i] = fp[i][a];
        const double r = pearson(x, y);
        sum += std::isfinite(r) ? std::abs(r) : 0.0;  // a series that does not move: no correlation
        ++n;
      }
    }
  }
  return n ? sum / n : 0.0;
}

PreparedTrial prepare_trial(const TrialInput& t, const Skeleton& reference, const BuildConfig& cfg) {
  PreparedTrial p;
  p.info = {t.file, t.cls, t.subject, t.trial, 0.0};
  const Skeleton& s = t.motion.skeleton;
  for (Role r : {Role::Head, Role::LeftHand, Role::RightHand, Role::LeftAnkle, Role::RightAnkle, Role::Pelvis})
    if (!s.roles.has(r)) {
      p.reason = "no joint for role " + std::string(role_name(r));
      return p;
    }
  if (t.motion.frame_count() <= window_lag(0)) {  // not one whole window
    p.reason = "too short (" + std::to_string(t.motion.frame_count()) + " frames)";
    return p;
  }
  Motion m = resample(t.motion, cfg.fps);
  if (s.names == reference.names) {
    // Same rig: copy rotations onto the reference bone lengths.
    Motion on_ref(reference, m.fps, m.frame_count());
    std::copy(m.all_rotations().begin(), m.all_rotations().end(), on_ref.all_rotations().begin());
    for (int f = 0; f < m.frame_count(); ++f) {
      auto fr = on_ref.frame(f);
      fr.translations[0] = m.frame(f).translations[0];
    }
    p.motion = std::move(on_ref);
    p.reason = "kept";
  } else {
    p.motion = retarget_motion(m, reference);
    p.reason = "kept (mapped by joint roles onto the database skeleton)";
  }
  p.info.correlation = hand_foot_correlation(p.motion);
  if (!(p.info.correlation > cfg.correlation_threshold)) {
    std::ostringstream why;
    why.precision(3);
    why << "hand-foot correlation " << p.info.correlation << " <= threshold " << cfg.correlation_threshold;
    p.reason = why.str();
    p.motion = Motion();
    return p;
  }
  const auto pos = joint_positions(p.motion);
  p.contacts = foot_contacts(p.motion);
  p.head = joint_path(p.motion, pos, Role::Head);
  p.hands[0] = head_relative(p.motion, pos, Role::LeftHand, p.head);
  p.hands[1] = head_relative(p.motion, pos, Role::RightHand, p.head);
  if (cfg.mirror) {
    p.mirrored = mirror_motion(p.motion);
    const auto mpos = joint_positions(p.mirrored);
    p.mirrored_head = joint_path(p.mirrored, mpos, Role::Head);
    p.mirrored_hands[0] = head_relative(p.mirrored, mpos, Role::LeftHand, p.mirrored_head);
    p.mirrored_hands[1] = head_relative(p.mirrored, mpos, Role::RightHand, p.mirrored_head);
    p.mirrored_contacts = foot_contacts(p.mirrored);
  }
  p.kept = true;
  return p;
}

namespace {

// Every window of one trial (and of its mirrored copy): its pose, head-up
// vector, foot contacts, re-timed hand windows and alignment, appended to
// `parts` and `windows`.
void add_trial_windows(const PreparedTrial* t, std::uint32_t trial_index, int head_joint, const Skeleton& reference,
                       const BuildConfig& cfg, BlockParts& parts, std::vector<std::array<PosVec, 2>>& windows) {
  const int nj = reference.joint_count();
  const auto& speeds = parts.meta.settings.speeds;
  for (int mir = 0; mir < (cfg.mirror ? 2 : 1); ++mir) {
    const Motion& m = mir ? t->mirrored : t->motion;
    const auto& hands = mir ? t->mirrored_hands : t->hands;
    const auto& contacts = mir ? t->mirrored_contacts : t->contacts;
    const auto& head = mir ? t->mirrored_head : t->head;
    for (int e = window_lag(0); e < m.frame_count(); e += cfg.hop) {  // the first window inside the trial
      const auto pose = static_cast<std::uint32_t>(parts.poses.size() / (static_cast<std::size_t>(nj) * 4));
      const auto fr = m.frame(e);
      for (int j = 0; j < nj; ++j) {
        const Quat q = fr.rotations[static_cast<std::size_t>(j)].normalized();
        parts.poses.insert(parts.poses.end(), {static_cast<float>(q.w()), static_cast<float>(q.x()),
                                               static_cast<float>(q.y()), static_cast<float>(q.z())});
      }
      Quat head_model = Quat::Identity();
      for (int j = head_joint; j >= 0; j = reference.parents[static_cast<std::size_t>(j)])
        head_model = fr.rotations[static_cast<std::size_t>(j)] * head_model;
      const Vec3 up = (head_model * Vec3::UnitY()).normalized();
      parts.head_up.insert(parts.head_up.end(), {static_cast<float>(up.x()), static_cast<float>(up.y()), static_cast<float>(up.z())});
      // A planted foot only for a performer standing upright (not a swimmer's kick).
      const bool upright = up.y() > kContactUpright;
      for (const auto& c : contacts)
        parts.contacts.push_back(upright && c[static_cast<std::size_t>(e)] ? std::uint8_t{1} : std::uint8_t{0});
      for (std::size_t si = 0; si < speeds.size(); ++si) {
        const double s = speeds[si];
        if (e - window_lag(0) * s < -1e-9) continue;
        std::array<HandWindow, 2> w;
        for (int h = 0; h < 2; ++h)
          for (int i = 0; i < kWindow; ++i)
            w[static_cast<std::size_t>(h)][static_cast<std::size_t>(i)] =
                sample_path(hands[static_cast<std::size_t>(h)], e - window_lag(i) * s);
        windows.push_back({stack(w[0]), stack(w[1])});
        AlignXZ a;
        fill_align(w[0], w[1], a);
        parts.align.push_back(a);
        parts.travel.push_back(head_travel(head, e, s, cfg.fps, parts.meta.height));
        parts.sources.push_back({pose, trial_index, static_cast<std::uint32_t>(e), static_cast<std::uint16_t>(parts.meta.classes.size() - 1),
                                 static_cast<std::uint8_t>(si), static_cast<std::uint8_t>(mir)});
      }
    }
  }
}

// Per-dimension normalisation of the raw features and the projection onto
// their principal axes (parts.meta.space), then every window's features.
void project_features(const std::vector<std::array<PosVec, 2>>& windows, const BuildConfig& cfg, BlockParts& parts) {
  // From the mean and covariance of the stacked positions (raw = W p is linear in them).
  const auto W = raw_feature_matrix(cfg.fps);
  PosVec mean = PosVec::Zero();
  Eigen::Matrix<double, kPosDim, kPosDim> cov = Eigen::Matrix<double, kPosDim, kPosDim>::Zero();
  for (const auto& w : windows)
    for (const auto& p : w) mean += p;
  const double count = 2.0 * static_cast<double>(windows.size());
  mean /= count;
  for (const auto& w : windows)
    for (const auto& p : w) cov.noalias() += (p - mean) * (p - mean).transpose();
  cov /= count;
  parts.meta.space.fps = cfg.fps;
  parts.meta.space.group_weight = cfg.group_weight;
  Eigen::Matrix<double, kRawDim, 1> scale;
  for (int d = 0; d < kRawDim; ++d) {
    const double var = W.row(d) * cov * W.row(d).transpose();
    const double sd = std::sqrt(std::max(var, 0.0));
    scale(d) = cfg.group_weight[static_cast<std::size_t>(group_of(d))] / std::max(sd, 1e-9);
    parts.meta.space.scale[static_cast<std::size_t>(d)] = scale(d);
  }
  // Metric on positions M = W^T S^2 W = A^T A, then rotate onto the principal
  // axes of the data in that metric (distances unchanged, KD-trees split well).
  const Eigen::Matrix<double, kRawDim, kPosDim> SW = scale.asDiagonal() * W;
  const Eigen::Matrix<double, kPosDim, kPosDim> M = SW.transpose() * SW;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, kPosDim, kPosDim>> es(M);
  const Eigen::Matrix<double, kPosDim, kPosDim> A =
      es.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal() * es.eigenvectors().transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, kPosDim, kPosDim>> pca(A * cov * A.transpose());
  const Eigen::Matrix<double, kPosDim, kPosDim> U = pca.eigenvectors().rowwise().reverse();  // descending variance
  const Eigen::Matrix<double, kPosDim, kPosDim> P = U.transpose() * A;
  for (int r = 0; r < kDim; ++r)
    for (int c = 0; c < kPosDim; ++c) parts.meta.space.projection[static_cast<std::size_t>(r * kPosDim + c)] = P(r, c);
  for (int h = 0; h < 2; ++h) {
    auto& out = parts.features[h];
    out.resize(windows.size());
    for (std::size_t w = 0; w < windows.size(); ++w) {
      const PosVec y = P * windows[w][static_cast<std::size_t>(h)];
      for (int d = 0; d < kDim; ++d) out[w][static_cast<std::size_t>(d)] = static_cast<float>(y(d));
    }
  }

}

// Typical distance: median over sampled original-speed windows of the
// distance to the nearest window of another trial (left hand).
double typical_distance(const BlockParts& parts, int samples) {
  std::vector<int> originals;
  for (std::size_t w = 0; w < parts.sources.size(); ++w)
    if (parts.sources[w].speed == 0 && !parts.sources[w].mirrored) originals.push_back(static_cast<int>(w));
  std::mt19937 rng(12345);
  std::shuffle(originals.begin(), originals.end(), rng);
  originals.resize(std::min<std::size_t>(originals.size(), static_cast<std::size_t>(std::max(samples, 1))));
  std::vector<double> nn;
  const auto& F = parts.features[0];
  for (int q : originals) {
    float best = std::numeric_limits<float>::max();
    for (std::size_t w = 0; w < F.size(); ++w) {
      if (parts.sources[w].trial == parts.sources[static_cast<std::size_t>(q)].trial) continue;
      float s = 0;
      for (int d = 0; d < kDim; ++d) {
        const float x = F[w][static_cast<std::size_t>(d)] - F[static_cast<std::size_t>(q)][static_cast<std::size_t>(d)];
        s += x * x;
      }
      best = std::min(best, s);
    }
    if (best < std::numeric_limits<float>::max()) nn.push_back(std::sqrt(best));
  }
  return nn.empty() ? 1.0  // a single trial: no cross-trial distance to measure
                    : std::max(median(nn), 1e-6);
}

}  // namespace

Database assemble_database(std::span<const PreparedTrial* const> trials, const Skeleton& reference,
                           const BuildConfig& cfg, BuildReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  if (cfg.hop < 1) throw Error("accent build: hop must be at least 1 sample");
  BlockParts parts;
  parts.meta.skeleton = reference;
  resolve_roles(parts.meta.skeleton);
  parts.meta.height = measure_body(parts.meta.skeleton).standing_height;
  parts.meta.settings = {cfg.fps, cfg.hop, cfg.correlation_threshold, speed_factors(cfg), cfg.mirror};
  const int nj = reference.joint_count();

  // Kept trials in class order (windows of a class must be contiguous).
  std::vector<const PreparedTrial*> kept;
  for (const auto* t : trials)
    if (t->kept) kept.push_back(t);
  std::stable_sort(kept.begin(), kept.end(), [](auto* a, auto* b) { return a->info.cls < b->info.cls; });

  std::vector<std::array<PosVec, 2>> windows;
  std::vector<int> window_counts;
  const int head_joint = parts.meta.skeleton.roles[Role::Head];
  if (head_joint < 0) throw Error("accent build: the reference skeleton has no head joint");
  for (const auto* t : kept) {
    if (t->motion.joint_count() != nj) throw Error("accent build: trial '" + t->info.file + "' is not on the reference skeleton");
    if (parts.meta.classes.empty() || parts.meta.classes.back() != t->info.cls) {
      if (!parts.meta.ranges.empty()) parts.meta.ranges.back().second = static_cast<int>(parts.sources.size());
      parts.meta.classes.push_back(t->info.cls);
      parts.meta.ranges.emplace_back(static_cast<int>(parts.sources.size()), 0);
    }
    const auto trial_index = static_cast<std::uint32_t>(parts.meta.trials.size());
    parts.meta.trials.push_back(t->info);
    const int before = static_cast<int>(parts.sources.size());
    add_trial_windows(t, trial_index, head_joint, reference, cfg, parts, windows);
    window_counts.push_back(static_cast<int>(parts.sources.size()) - before);
  }
  if (!parts.meta.ranges.empty()) parts.meta.ranges.back().second = static_cast<int>(parts.sources.size());
  // Per-trial verdicts (also when the build fails, so the CLI can show why).
  auto fill_verdicts = [&] {
    if (!report) return;
    report->trials.clear();
    for (const auto* t : trials) {
      TrialVerdict v{t->info.file, t->info.cls, t->kept, t->info.correlation, 0, t->reason};
      const auto it = std::find(kept.begin(), kept.end(), t);
      if (it != kept.end()) v.windows = window_counts[static_cast<std::size_t>(it - kept.begin())];
      report->trials.push_back(v);
    }
  };
  if (windows.empty()) fill_verdicts();
  if (windows.empty())
    throw Error("accent build: no windows: every trial was dropped or too short (see the per-trial report; "
                "lower --correlation or add trials)");

  project_features(windows, cfg, parts);
  parts.meta.typical_distance = typical_distance(parts, cfg.typical_samples);
  parts.meta.travel_scale = travel_scale(parts.travel);

  auto block = serialize_block(parts);
  if (report) {
    fill_verdicts();
    report->windows = static_cast<int>(parts.sources.size());
    report->poses = static_cast<int>(parts.poses.size() / (static_cast<std::size_t>(nj) * 4));
    report->bytes = block.size();
    report->seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  return Database::from_bytes(std::move(block), "(in memory)");
}

Database build_database(std::span<const TrialInput> trials, const BuildConfig& cfg, BuildReport* report,
                        const Progress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  const Skeleton ref = reference_skeleton(trials);
  std::vector<PreparedTrial> prepared;
  prepared.reserve(trials.size());
  for (std::size_t i = 0; i < trials.size(); ++i) {
    if (progress) progress(static_cast<int>(i), static_cast<int>(trials.size()), trials[i].file);
    try {
      prepared.push_back(prepare_trial(trials[i], ref, cfg));
    } catch (const Error& e) {
      PreparedTrial p;
      p.info = {trials[i].file, trials[i].cls, trials[i].subject, trials[i].trial, 0.0};
      p.reason = e.what();
      prepared.push_back(std::move(p));
    }
  }
  if (progress) progress(static_cast<int>(trials.size()), static_cast<int>(trials.size()), "assembling");
  std::vector<const PreparedTrial*> ptrs;
  for (const auto& p : prepared) ptrs.push_back(&p);
  BuildReport local;
  BuildReport* r = report ? report : &local;
  r->seconds = 0;
  for (const auto& t : trials)
    if (t.motion.skeleton.names == ref.names) {
      r->skeleton_from = t.file;
      break;
    }
  Database db = assemble_database(ptrs, ref, cfg, r);
  r->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return db;
}

}  // namespace legwork::accent
