// Every call from `legwork serve` into the runtimes lives here (see methods.hpp).
#include <legwork/serve/methods.hpp>

#include <legwork/accent/accent.hpp>
#include <legwork/accent/database.hpp>
#include <legwork/combined/combined.hpp>
#include <legwork/core/limits.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/ik/full_body.hpp>
#include <legwork/walkcycle/offline/keys.hpp>
#include <legwork/walkcycle/offline/ground.hpp>
#include <legwork/walkcycle/walker.hpp>
#include <legwork/wip/wip.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace legwork::serve {
namespace {

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

// The avatar skeleton for methods without a database of their own, scaled to
// the user's height (0 = as is).
Skeleton avatar_skeleton(const Resources& res, double user_height) {
  const Skeleton* base = res.db ? &res.db->skeleton() : res.skeleton;
  if (!base) throw Error("no avatar skeleton: start the server with --db FILE or --skeleton FILE.bvh");
  Skeleton skel = *base;
  if (user_height > 0) {
    const double h = measure_body(skel).standing_height;
    if (h <= 0) throw Error("the avatar skeleton has no measurable standing height");
    skel.scale(user_height / h);
  }
  return skel;
}

// The legs' foot-off detector and depth mapping named in the session's
// options (detector document | adaptive, mapping document | learned) and the
// learned table the mapping needs (null for the document's).
const wip::LearnedMapping* leg_mapping(const Resources& res, const MethodOptions& opt, wip::Settings& s) {
  if (opt.detector == "document") s.gait.detector = wip::StepDetector::Document;
  else if (opt.detector == "adaptive") s.gait.detector = wip::StepDetector::Adaptive;
  else if (!opt.detector.empty()) throw Error("detector '" + opt.detector + "' is not one of: document, adaptive");
  if (opt.mapping == "document") return nullptr;
  if (opt.mapping != "learned")
    throw Error("mapping '" + opt.mapping + "' is not one of: document, learned");
  if (!res.wip_learned)
    throw Error("mapping 'learned' needs the learned table: start the server with --wip-table FILE "
                "(data/wip/learned_mapping.txt, or one made by `legwork wip learn`)");
  s.mapping.depth = wip::DepthMapping::Learned;
  return res.wip_learned;
}

// One runtime on the per-frame contract (Model / State / Info / update) as a
// Method: Runtime names the types, forwards update and describes its Info.
template <typename Runtime>
class RuntimeMethod final : public Method {
 public:
  explicit RuntimeMethod(typename Runtime::Model model) : model_(std::move(model)), state_(model_) {}

  UpdateStatus update(const TrackerFrame& f, PoseRef out, InfoFields& info) override {
    typename Runtime::Info i;
    const UpdateStatus st = Runtime::update(model_, f, state_, out, &i);
    if (st != UpdateStatus::Rejected) describe(i, info);  // the runtime's own (InfoFields)
    return st;
  }
  const Skeleton& skeleton() const override { return model_.skeleton(); }

 private:
  const typename Runtime::Model model_;
  typename Runtime::State state_;
};

// A runtime's contract types and its update(), named once for RuntimeMethod.
template <class M, class S, class I, UpdateStatus (*Update)(const M&, const TrackerFrame&, S&, PoseRef, I*)>
struct Contract {
  using Model = M;
  using State = S;
  using Info = I;
  static UpdateStatus update(const M& m, const TrackerFrame& f, S& s, PoseRef o, I* i) { return Update(m, f, s, o, i); }
};

// The VRIK-style full-body IK avatar (head + hands).
struct IkRuntime : Contract<ik::Model, ik::State, ik::Info, &ik::update> {
  static Model model(const Resources& res, const MethodOptions& opt) { return ik::make_model(avatar_skeleton(res, opt.user_height)); }
};

// Walking-in-place legs from the ankles (the head's yaw is the walking heading).
struct WipRuntime : Contract<wip::Model, wip::State, wip::Info, &wip::update> {
  static Model model(const Resources& res, const MethodOptions& opt) {
    wip::Settings s;
    const wip::LearnedMapping* learned = leg_mapping(res, opt, s);
    return wip::make_model(avatar_skeleton(res, opt.user_height), s, {}, learned);
  }
};

// The session's accentuation options (hello fields) on accent::Settings.
void accent_options(const MethodOptions& opt, accent::Settings& c) {
  c.classes = opt.classes;
  c.recognize_class = opt.recognize_class;
  c.foot_lift_height = opt.foot_lift_height;
  c.foot_lock_slack = opt.foot_lock_slack;
  c.foot_lock_hold_seconds = opt.foot_lock_hold_seconds;
  c.foot_swing_speed = opt.foot_swing_speed;
  c.travel_weight = opt.travel_weight;
  c.max_head_height_diff = opt.max_head_height_diff;
  c.smooth_feedforward = opt.smooth_feedforward;
  c.lying_root_smoothing = opt.lying_root_smoothing;
  c.lying_crown = opt.lying_crown;
  c.other_class_cost = opt.other_class_cost;
  c.search_interval = opt.search_interval;
  c.floor = opt.floor;
  c.floor_height = opt.floor_height;
  c.exaggeration = opt.exaggeration;
  c.user_height = opt.user_height;
}

// CoolMoves accentuation over the shared database (one Model per session's settings).
struct AccentRuntime : Contract<accent::Model, accent::State, accent::Info, &accent::update> {
  static Model model(const Resources& res, const MethodOptions& opt) {
    accent::Settings c;
    accent_options(opt, c);
    return accent::make_model(*res.db, c);
  }
};

template <typename Runtime>
std::unique_ptr<Method> runtime_method(const Resources& res, const MethodOptions& opt) {
  return std::make_unique<RuntimeMethod<Runtime>>(Runtime::model(res, opt));
}

// The combined avatar (legwork::combined): upper body from accent (ik without
// a database), legs from walking-in-place, faded over blend_time.
struct CombinedRuntime : Contract<combined::Model, combined::State, combined::Info, &combined::update> {
  static Model model(const Resources& res, const MethodOptions& opt) {
    combined::Settings c;
    const wip::LearnedMapping* learned = leg_mapping(res, opt, c.wip);
    if (!res.db) return combined::make_model(avatar_skeleton(res, opt.user_height), c, learned);
    accent_options(opt, c.accent);
    return combined::make_model(*res.db, c, learned);
  }
};

// The walk-cycle walker (walkcycle::update) on a walk file of the server's
// --walks folder, steered by the head's yaw; its own skeleton (user_height
// does not apply).
struct WalkerRuntime : Contract<walkcycle::Model, walkcycle::State, walkcycle::Info, &walkcycle::update> {
  static std::vector<std::string> walks(const Resources& res) {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(res.walks_dir, ec))
      if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  static Model model(const Resources& res, const MethodOptions& opt) {
    walkcycle::Settings s;
    if (opt.root != "smooth" && opt.root != "pivot") throw Error("root '" + opt.root + "' is not one of: smooth, pivot");
    s.root = opt.root == "pivot" ? walkcycle::RootMotion::Pivot : walkcycle::RootMotion::Smooth;
    if (!opt.ground.empty()) s.ground = walkcycle::parse_ground_json(opt.ground, "hello.ground");
    s.max_turn_per_step = opt.max_turn_per_step;
    s.soft_reach = opt.soft_reach;
    s.stairs_cadence = opt.stairs_cadence;
    const auto names = walks(res);
    if (std::find(names.begin(), names.end(), opt.walk) == names.end())
      throw Error("walk '" + opt.walk + "' is not one of this server's walks (" + join(names) + ")");
    const walkcycle::WalkFile w = walkcycle::load_walk((std::filesystem::path(res.walks_dir) / (opt.walk + ".json")).string());
    return walkcycle::make_model(walkcycle::build_cycle(w.skeleton, w.keys), s);
  }
};

}  // namespace

const std::vector<std::string>& known_methods() {
  static const std::vector<std::string> m{"accent", "ik", "wip", "combined", "walker"};
  return m;
}

std::vector<std::string> available_methods(const Resources& res) {
  std::vector<std::string> out;
  if (res.db) out.push_back("accent");
  if (res.db || res.skeleton) {
    out.push_back("ik");
    out.push_back("wip");
    out.push_back("combined");
  }
  if (!res.walks_dir.empty()) out.push_back("walker");
  return out;
}

std::unique_ptr<Method> make_method(const Resources& res, const MethodOptions& opt) {
  const auto avail = available_methods(res);
  if (std::find(avail.begin(), avail.end(), opt.method) == avail.end()) {
    const auto& known = known_methods();
    if (std::find(known.begin(), known.end(), opt.method) == known.end())
      throw Error("unknown method '" + opt.method + "' (known: " + join(known) + ")");
    if (opt.method == "accent" && !res.db)
      throw Error("method '" + opt.method + "' needs a database: start the server with --db FILE");
    throw Error("method '" + opt.method + "' is not available in this server (available: " + join(avail) + ")");
  }
  if (!(opt.exaggeration > 0 && opt.exaggeration <= 4))
    throw Error("exaggeration " + std::to_string(opt.exaggeration) + " is outside (0, 4]");
  if (!(opt.foot_lift_height >= 0 && opt.foot_lift_height <= 0.5))
    throw Error("foot_lift_height " + std::to_string(opt.foot_lift_height) + " m is outside [0, 0.5]");
  if (!(opt.foot_lock_slack >= 0 && opt.foot_lock_slack <= 1))
    throw Error("foot_lock_slack " + std::to_string(opt.foot_lock_slack) + " m is outside [0, 1]");
  if (!(opt.foot_lock_hold_seconds >= 0 && opt.foot_lock_hold_seconds <= 10))
    throw Error("foot_lock_hold_seconds " + std::to_string(opt.foot_lock_hold_seconds) + " s is outside [0, 10]");
  if (!(opt.travel_weight >= 0 && opt.travel_weight <= 100))
    throw Error("travel_weight " + std::to_string(opt.travel_weight) + " is outside [0, 100] (0 = off)");
  if (!(opt.max_head_height_diff >= 0 && opt.max_head_height_diff <= 2))
    throw Error("max_head_height_diff " + std::to_string(opt.max_head_height_diff) + " is outside [0, 2] (0 = off)");
  if (!(opt.smooth_feedforward >= 0 && opt.smooth_feedforward <= 1))
    throw Error("smooth_feedforward " + std::to_string(opt.smooth_feedforward) + " is outside [0, 1] (0 = off)");
  if (!(opt.lying_root_smoothing >= 1 && opt.lying_root_smoothing <= 20))
    throw Error("lying_root_smoothing " + std::to_string(opt.lying_root_smoothing) + " is outside [1, 20] (1 = off)");
  if (!(opt.lying_crown >= 0 && opt.lying_crown <= 1))
    throw Error("lying_crown " + std::to_string(opt.lying_crown) + " is outside [0, 1] (0 = off)");
  if (!(opt.other_class_cost == 0 || (opt.other_class_cost >= 1 && opt.other_class_cost <= 1e6)))
    throw Error("other_class_cost " + std::to_string(opt.other_class_cost) + " is neither 0 (off) nor in [1, 1e6]");
  if (!(opt.search_interval >= 0 && opt.search_interval <= 1))
    throw Error("search_interval " + std::to_string(opt.search_interval) + " is outside [0, 1] seconds (0 = every frame)");
  if (!(opt.floor_height >= -10 && opt.floor_height <= 10))
    throw Error("floor_height " + std::to_string(opt.floor_height) + " m is outside [-10, 10]");
  if (!(opt.foot_swing_speed >= 0 && opt.foot_swing_speed <= 10))
    throw Error("foot_swing_speed " + std::to_string(opt.foot_swing_speed) + " m/s is outside [0, 10]");
  if (!(opt.user_height == 0 || (opt.user_height >= kMinUserHeight && opt.user_height <= kMaxUserHeight))) {
    char msg[160];
    std::snprintf(msg, sizeof msg, "user_height %f m is outside [%g, %g] (0 = the avatar's own)", opt.user_height,
                  kMinUserHeight, kMaxUserHeight);
    throw Error(msg);
  }
  if (opt.method == "ik") return runtime_method<IkRuntime>(res, opt);
  if (opt.method == "wip") return runtime_method<WipRuntime>(res, opt);
  if (opt.method == "combined") return runtime_method<CombinedRuntime>(res, opt);
  if (opt.method == "walker") return runtime_method<WalkerRuntime>(res, opt);
  return runtime_method<AccentRuntime>(res, opt);
}

}  // namespace legwork::serve
