// The C API (include/legwork/legwork.h) over the C++ runtimes. Every entry
// point catches everything: no exception crosses the boundary; errors become
// an lw_status plus a thread-local message.
#define LEGWORK_C_BUILD 1
#include <legwork/legwork.h>

#include <legwork/accent/accent.hpp>
#include <legwork/combined/combined.hpp>
#include <legwork/core/engine.hpp>
#include <legwork/core/fk.hpp>
#include <legwork/core/tracker.hpp>
#include <legwork/ik/full_body.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/walkcycle/offline/keys.hpp>
#include <legwork/walkcycle/offline/ground.hpp>
#include <legwork/walkcycle/walker.hpp>
#include <legwork/wip/offline/learn.hpp>
#include <legwork/wip/wip.hpp>

#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <variant>
#include <vector>

using namespace legwork;

namespace {

thread_local std::string g_error;
lw_allocator g_alloc{};  // all-null: malloc/free

lw_status fail(lw_status s, std::string message) {
  g_error = std::move(message);
  return s;
}

// Runs `fn`, mapping every exception to a status and a message.
template <class Fn>
lw_status guarded(const char* where, Fn&& fn) {
  try {
    g_error.clear();
    return fn();
  } catch (const std::bad_alloc&) {
    return fail(LW_ERROR_OUT_OF_MEMORY, std::string(where) + ": out of memory");
  } catch (const Error& e) {
    const std::string what = e.what();
    const bool io = what.find("cannot open") != std::string::npos || what.find("No such file") != std::string::npos ||
                    what.find("does not exist") != std::string::npos;
    return fail(io ? LW_ERROR_IO : LW_ERROR_FORMAT, std::string(where) + ": " + what);
  } catch (const std::exception& e) {
    return fail(LW_ERROR_INTERNAL, std::string(where) + ": internal error: " + e.what());
  } catch (...) {
    return fail(LW_ERROR_INTERNAL, std::string(where) + ": internal error");
  }
}

void* allocate(std::size_t size, std::size_t align) {
  if (g_alloc.allocate) return g_alloc.allocate(size, align, g_alloc.user);
  return std::aligned_alloc(align, (size + align - 1) / align * align);
}
void deallocate(void* p) {
  if (!p) return;
  if (g_alloc.deallocate)
    g_alloc.deallocate(p, g_alloc.user);
  else
    std::free(p);
}

// Handle objects live in memory from the caller's allocator.
template <class T, class... Args>
T* make_handle(Args&&... args) {
  void* mem = allocate(sizeof(T), alignof(T));
  if (!mem) throw std::bad_alloc();
  try {
    return new (mem) T(std::forward<Args>(args)...);
  } catch (...) {
    deallocate(mem);
    throw;
  }
}
template <class T>
void destroy_handle(T* p) {
  if (!p) return;
  p->~T();
  deallocate(p);
}

TrackerFrame to_frame(const lw_frame& f) {
  TrackerFrame t;
  t.time = f.time;
  for (int d = 0; d < kDeviceCount; ++d) {
    const lw_device& s = f.devices[d];
    auto& o = t.devices[static_cast<std::size_t>(d)];
    o.position = Vec3(s.position[0], s.position[1], s.position[2]);
    o.rotation = Quat(s.rotation[0], s.rotation[1], s.rotation[2], s.rotation[3]);
    o.valid = s.valid != 0;
  }
  return t;
}

lw_frame from_frame(const TrackerFrame& t) {
  lw_frame f{};
  f.time = t.time;
  for (int d = 0; d < kDeviceCount; ++d) {
    const auto& s = t.devices[static_cast<std::size_t>(d)];
    lw_device& o = f.devices[d];
    for (int i = 0; i < 3; ++i) o.position[i] = s.position[i];
    o.rotation[0] = s.rotation.w();
    o.rotation[1] = s.rotation.x();
    o.rotation[2] = s.rotation.y();
    o.rotation[3] = s.rotation.z();
    o.valid = s.valid ? 1 : 0;
  }
  return f;
}

lw_status to_status(UpdateStatus s) {
  switch (s) {
    case UpdateStatus::Ok: return LW_OK;
    case UpdateStatus::Degraded: return LW_DEGRADED;
    case UpdateStatus::Rejected: return LW_REJECTED;
    case UpdateStatus::Restarted: return LW_RESTARTED;
  }
  return LW_ERROR_INTERNAL;
}

}  // namespace

struct lw_skeleton {
  Skeleton skeleton;
};

struct lw_database {
  accent::Database db;
  lw_skeleton skeleton;
};

struct lw_model {
  lw_method method = LW_METHOD_ACCENT;
  std::variant<accent::Model, ik::Model, wip::Model, walkcycle::Model, combined::Model> model;
  lw_skeleton skeleton;  // the output skeleton
};

namespace {
accent::State state_of(const accent::Model& m) { return accent::State(m); }
ik::State state_of(const ik::Model& m) { return ik::State(m); }
wip::State state_of(const wip::Model& m) { return wip::State(m); }
walkcycle::State state_of(const walkcycle::Model& m) { return walkcycle::State(m); }
combined::State state_of(const combined::Model& m) { return combined::State(m); }
}  // namespace

struct lw_avatar {
  const lw_model* model = nullptr;
  std::variant<accent::State, ik::State, wip::State, walkcycle::State, combined::State> state;
  Pose pose;
  std::vector<Transform> world;  // scratch for lw_avatar_pose
  InfoFields info;               // the last consumed frame's (lw_avatar_info_*)
};

namespace {
// One frame of runtime M (its Info I): the pose into a.pose, the consumed
// frame's figures into a.info (a rejected frame keeps the last ones).
template <class M, class I, class S>
UpdateStatus step(lw_avatar& a, S& state, const TrackerFrame& in) {
  I info;
  const UpdateStatus s = update(std::get<M>(a.model->model), in, state, a.pose.ref(), &info);
  if (s != UpdateStatus::Rejected) {
    a.info = {};
    describe(info, a.info);
  }
  return s;
}

void put_field(const InfoFields::Item& f, const char** name, double* number, const char** text) {
  if (name) *name = f.key;
  if (number) *number = f.text ? 0.0 : f.number;
  if (text) *text = f.text;
}

// A model handle that owns `model`; its output skeleton is exposed as lw_skeleton.
template <class M>
lw_status store_model(lw_method method, M model, lw_model** out) {
  auto* h = make_handle<lw_model>(lw_model{method, std::move(model), {}});
  h->skeleton.skeleton = std::get<M>(h->model).skeleton();
  *out = h;
  return LW_OK;
}
}  // namespace

extern "C" {

uint32_t lw_abi_version(void) { return LW_ABI_VERSION; }
const char* lw_version_string(void) { return "legwork 0.2.0 (C ABI 1)"; }
const char* lw_last_error(void) { return g_error.c_str(); }

const char* lw_status_name(lw_status s) {
  switch (s) {
    case LW_OK: return "ok";
    case LW_DEGRADED: return "degraded";
    case LW_REJECTED: return "rejected";
    case LW_RESTARTED: return "restarted";
    case LW_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case LW_ERROR_IO: return "i/o error";
    case LW_ERROR_FORMAT: return "format error";
    case LW_ERROR_OUT_OF_MEMORY: return "out of memory";
    case LW_ERROR_UNSUPPORTED: return "unsupported";
    case LW_ERROR_INTERNAL: return "internal error";
  }
  return "unknown status";
}

lw_status lw_set_allocator(const lw_allocator* a) {
  if (a && (!a->allocate || !a->deallocate))
    return fail(LW_ERROR_INVALID_ARGUMENT, "lw_set_allocator: both allocate and deallocate are needed");
  g_alloc = a ? *a : lw_allocator{};
  return LW_OK;
}

// ---- databases and skeletons

lw_status lw_database_load(const char* path, lw_database** out) {
  if (!path || !out) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_database_load: path and out must not be NULL");
  *out = nullptr;
  return guarded("lw_database_load", [&] {
    auto* h = make_handle<lw_database>();
    try {
      h->db = accent::load_database(path);
      h->skeleton.skeleton = h->db.skeleton();
    } catch (...) {
      destroy_handle(h);
      throw;
    }
    *out = h;
    return LW_OK;
  });
}
void lw_database_destroy(lw_database* db) { destroy_handle(db); }
int32_t lw_database_class_count(const lw_database* db) { return db ? db->db.class_count() : 0; }
const char* lw_database_class_name(const lw_database* db, int32_t i) {
  if (!db || i < 0 || i >= db->db.class_count()) return nullptr;
  return db->db.classes()[static_cast<std::size_t>(i)].c_str();
}
int32_t lw_database_window_count(const lw_database* db) { return db ? db->db.window_count() : 0; }
const lw_skeleton* lw_database_skeleton(const lw_database* db) { return db ? &db->skeleton : nullptr; }

lw_status lw_skeleton_load_bvh(const char* path, lw_skeleton** out) {
  if (!path || !out) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_skeleton_load_bvh: path and out must not be NULL");
  *out = nullptr;
  return guarded("lw_skeleton_load_bvh", [&] {
    Skeleton s = io::read_bvh(path).motion.skeleton;
    *out = make_handle<lw_skeleton>(lw_skeleton{std::move(s)});
    return LW_OK;
  });
}
void lw_skeleton_destroy(lw_skeleton* s) { destroy_handle(s); }
int32_t lw_skeleton_joint_count(const lw_skeleton* s) { return s ? s->skeleton.joint_count() : 0; }
const char* lw_skeleton_joint_name(const lw_skeleton* s, int32_t j) {
  if (!s || j < 0 || j >= s->skeleton.joint_count()) return nullptr;
  return s->skeleton.names[static_cast<std::size_t>(j)].c_str();
}
lw_status lw_skeleton_parents(const lw_skeleton* s, int32_t* parents, int32_t capacity) {
  if (!s || !parents) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_skeleton_parents: skeleton and parents must not be NULL");
  const int n = s->skeleton.joint_count();
  if (capacity < n)
    return fail(LW_ERROR_INVALID_ARGUMENT, "lw_skeleton_parents: capacity " + std::to_string(capacity) + " < " + std::to_string(n) + " joints");
  for (int j = 0; j < n; ++j) parents[j] = s->skeleton.parents[static_cast<std::size_t>(j)];
  return LW_OK;
}

lw_status lw_frames_from_bvh(const char* path, double rate, int32_t drop_first, lw_frame** frames, int32_t* count) {
  if (!path || !frames || !count) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_frames_from_bvh: path, frames and count must not be NULL");
  *frames = nullptr;
  *count = 0;
  return guarded("lw_frames_from_bvh", [&] {
    io::BvhReadOptions o;
    o.drop_first_frame = drop_first != 0;
    const Motion m = io::load_bvh(path, o);
    const auto t = tracker_frames_from_motion(m, rate);
    if (t.size() > 100'000'000u) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_frames_from_bvh: too many frames");
    auto* out = static_cast<lw_frame*>(allocate(sizeof(lw_frame) * std::max<std::size_t>(t.size(), 1), alignof(lw_frame)));
    if (!out) throw std::bad_alloc();
    for (std::size_t i = 0; i < t.size(); ++i) out[i] = from_frame(t[i]);
    *frames = out;
    *count = static_cast<int32_t>(t.size());
    return LW_OK;
  });
}
void lw_frames_free(lw_frame* frames) { deallocate(frames); }

// ---- models

void lw_accent_settings_default(lw_accent_settings* s) {
  if (!s) return;
  const accent::Settings d;
  *s = lw_accent_settings{nullptr, d.k_left, d.exaggeration, d.user_height, d.hand_ik, d.smooth_halflife, d.recognize_class ? 1 : 0,
                           d.foot_lift_height, d.foot_lock_slack, d.foot_swing_speed, d.travel_weight,
                           d.max_head_height_diff, d.smooth_feedforward, d.lying_root_smoothing, d.lying_crown,
                           d.other_class_cost, d.search_interval, d.floor ? 1 : 0, d.floor_height,
                           d.foot_lock_hold_seconds};
}

}  // extern "C"

namespace {
// lw_accent_settings -> accent::Settings; an empty string when valid, else the reason.
std::string accent_settings(const lw_accent_settings* s, accent::Settings& cfg) {
  if (!s) return "";
  if (s->k < 1 || s->k > accent::kMaxK) return "k must be 1.." + std::to_string(accent::kMaxK) + ", got " + std::to_string(s->k);
  cfg.k_left = cfg.k_right = s->k;
  cfg.exaggeration = s->exaggeration;
  cfg.user_height = s->user_height;
  cfg.hand_ik = s->hand_ik;
  cfg.smooth_halflife = s->smooth_halflife;
  if (s->recognize_class != 0 && s->recognize_class != 1)
    return "recognize_class must be 0 or 1, got " + std::to_string(s->recognize_class);
  cfg.recognize_class = s->recognize_class == 1;
  cfg.foot_lift_height = s->foot_lift_height;  // checked by make_model
  cfg.foot_lock_slack = s->foot_lock_slack;    // checked by make_model
  cfg.foot_swing_speed = s->foot_swing_speed;  // checked by make_model
  cfg.travel_weight = s->travel_weight;        // checked by make_model
  cfg.max_head_height_diff = s->max_head_height_diff;  // checked by make_model
  cfg.smooth_feedforward = s->smooth_feedforward;      // checked by make_model
  cfg.lying_root_smoothing = s->lying_root_smoothing;  // checked by make_model
  cfg.lying_crown = s->lying_crown;                    // checked by make_model
  cfg.other_class_cost = s->other_class_cost;          // checked by make_model
  cfg.search_interval = s->search_interval;            // checked by make_model
  if (s->floor != 0 && s->floor != 1) return "floor must be 0 or 1, got " + std::to_string(s->floor);
  cfg.floor = s->floor == 1;
  cfg.floor_height = s->floor_height;  // checked by make_model
  cfg.foot_lock_hold_seconds = s->foot_lock_hold_seconds;  // checked by make_model
  if (s->classes) {
    std::string cur;
    for (const char* c = s->classes;; ++c) {
      if (*c == ',' || *c == 0) {
        if (!cur.empty()) cfg.classes.push_back(cur);
        cur.clear();
        if (*c == 0) break;
      } else {
        cur += *c;
      }
    }
  }
  return "";
}
}  // namespace

extern "C" {

lw_status lw_model_create_accent(const lw_database* db, const lw_accent_settings* s, lw_model** out) {
  if (!db || !out) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_model_create_accent: database and out must not be NULL");
  *out = nullptr;
  return guarded("lw_model_create_accent", [&] {
    accent::Settings cfg;
    if (const std::string why = accent_settings(s, cfg); !why.empty())
      return fail(LW_ERROR_INVALID_ARGUMENT, "lw_model_create_accent: " + why);
    return store_model(LW_METHOD_ACCENT, accent::make_model(db->db, cfg), out);
  });
}

lw_status lw_model_create_combined(const lw_database* db, const lw_accent_settings* s, const lw_skeleton* skeleton, lw_model** out) {
  if ((!db && !skeleton) || !out)
    return fail(LW_ERROR_INVALID_ARGUMENT, "lw_model_create_combined: give a database or a skeleton, and out (not NULL)");
  *out = nullptr;
  return guarded("lw_model_create_combined", [&] {
    combined::Settings cfg;
    if (const std::string why = accent_settings(s, cfg.accent); !why.empty())
      return fail(LW_ERROR_INVALID_ARGUMENT, "lw_model_create_combined: " + why);
    return store_model(LW_METHOD_COMBINED, db ? combined::make_model(db->db, cfg) : combined::make_model(skeleton->skeleton, cfg), out);
  });
}

lw_status lw_model_create_combined_learned(const lw_database* db, const lw_accent_settings* s, const lw_skeleton* skeleton,
                                           const char* table_path, lw_model** out) {
  if ((!db && !skeleton) || !table_path || !out)
    return fail(LW_ERROR_INVALID_ARGUMENT,
                "lw_model_create_combined_learned: give a database or a skeleton, table_path and out (not NULL)");
  *out = nullptr;
  return guarded("lw_model_create_combined_learned", [&] {
    combined::Settings cfg;
    if (const std::string why = accent_settings(s, cfg.accent); !why.empty())
      return fail(LW_ERROR_INVALID_ARGUMENT, "lw_model_create_combined_learned: " + why);
    cfg.wip.mapping.depth = wip::DepthMapping::Learned;
    const wip::LearnedMapping table = wip::read_learned_mapping(table_path);
    return store_model(LW_METHOD_COMBINED,
                       db ? combined::make_model(db->db, cfg, &table) : combined::make_model(skeleton->skeleton, cfg, &table), out);
  });
}

lw_status lw_model_create_ik(const lw_skeleton* skeleton, lw_model** out) {
  if (!skeleton || !out) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_model_create_ik: skeleton and out must not be NULL");
  *out = nullptr;
  return guarded("lw_model_create_ik", [&] {
    return store_model(LW_METHOD_IK, ik::make_model(skeleton->skeleton, ik::Settings{}), out);
  });
}

lw_status lw_model_create_wip(const lw_skeleton* skeleton, lw_model** out) {
  if (!skeleton || !out) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_model_create_wip: skeleton and out must not be NULL");
  *out = nullptr;
  return guarded("lw_model_create_wip", [&] {
    return store_model(LW_METHOD_WIP, wip::make_model(skeleton->skeleton, wip::Settings{}), out);
  });
}

lw_status lw_model_create_wip_learned(const lw_skeleton* skeleton, const char* table_path, lw_model** out) {
  if (!skeleton || !table_path || !out)
    return fail(LW_ERROR_INVALID_ARGUMENT, "lw_model_create_wip_learned: skeleton, table_path and out must not be NULL");
  *out = nullptr;
  return guarded("lw_model_create_wip_learned", [&] {
    wip::Settings settings;
    settings.mapping.depth = wip::DepthMapping::Learned;
    const wip::LearnedMapping table = wip::read_learned_mapping(table_path);
    return store_model(LW_METHOD_WIP, wip::make_model(skeleton->skeleton, settings, {}, &table), out);
  });
}

void lw_wip_settings_default(lw_wip_settings* s) {
  if (s) *s = lw_wip_settings{nullptr, LW_WIP_DETECTOR_DEFAULT};
}

lw_status lw_model_create_wip_with(const lw_skeleton* skeleton, const lw_wip_settings* s, lw_model** out) {
  if (!skeleton || !out) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_model_create_wip_with: skeleton and out must not be NULL");
  *out = nullptr;
  const int32_t detector = s ? s->detector : LW_WIP_DETECTOR_DEFAULT;
  if (detector < LW_WIP_DETECTOR_DEFAULT || detector > LW_WIP_DETECTOR_ADAPTIVE)
    return fail(LW_ERROR_INVALID_ARGUMENT, "lw_model_create_wip_with: detector must be 0 (default), 1 (document) or "
                                           "2 (adaptive), got " + std::to_string(detector));
  return guarded("lw_model_create_wip_with", [&] {
    wip::Settings settings;
    if (detector == LW_WIP_DETECTOR_DOCUMENT) settings.gait.detector = wip::StepDetector::Document;
    if (detector == LW_WIP_DETECTOR_ADAPTIVE) settings.gait.detector = wip::StepDetector::Adaptive;
    wip::LearnedMapping table;
    if (s && s->table_path) {
      settings.mapping.depth = wip::DepthMapping::Learned;
      table = wip::read_learned_mapping(s->table_path);
    }
    return store_model(LW_METHOD_WIP, wip::make_model(skeleton->skeleton, settings, {}, &table), out);
  });
}

lw_status lw_model_create_walker(const char* keys_json_path, lw_model** out) {
  if (!keys_json_path || !out) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_model_create_walker: path and out must not be NULL");
  return lw_model_create_walker_with_settings(keys_json_path, nullptr, out);
}

void lw_walker_settings_default(lw_walker_settings* s) {
  if (!s) return;
  const walkcycle::Settings d;
  *s = lw_walker_settings{d.root == walkcycle::RootMotion::Pivot ? LW_WALKER_ROOT_PIVOT : LW_WALKER_ROOT_SMOOTH, d.max_turn_per_step,
                          d.soft_reach, nullptr, d.stairs_cadence};
}

lw_status lw_model_create_walker_with_settings(const char* keys_json_path, const lw_walker_settings* s, lw_model** out) {
  const char* where = "lw_model_create_walker_with_settings";
  if (!keys_json_path || !out) return fail(LW_ERROR_INVALID_ARGUMENT, std::string(where) + ": path and out must not be NULL");
  *out = nullptr;
  walkcycle::Settings settings;
  if (s) {
    if (s->root != LW_WALKER_ROOT_SMOOTH && s->root != LW_WALKER_ROOT_PIVOT)
      return fail(LW_ERROR_INVALID_ARGUMENT, std::string(where) + ": root must be LW_WALKER_ROOT_SMOOTH (0) or LW_WALKER_ROOT_PIVOT (1), got " +
                                                 std::to_string(s->root));
    if (!std::isfinite(s->max_turn_per_step) || s->max_turn_per_step < 0)
      return fail(LW_ERROR_INVALID_ARGUMENT, std::string(where) + ": max_turn_per_step must be a finite angle >= 0 (radians)");
    if (!(s->soft_reach > 0 && s->soft_reach <= 1))
      return fail(LW_ERROR_INVALID_ARGUMENT, std::string(where) + ": soft_reach must be in (0, 1]");
    settings.root = s->root == LW_WALKER_ROOT_PIVOT ? walkcycle::RootMotion::Pivot : walkcycle::RootMotion::Smooth;
    settings.max_turn_per_step = s->max_turn_per_step;
    if (!(s->stairs_cadence > 0 && s->stairs_cadence <= 1))
      return fail(LW_ERROR_INVALID_ARGUMENT, std::string(where) + ": stairs_cadence must be in (0, 1]");
    settings.soft_reach = s->soft_reach;
    settings.stairs_cadence = s->stairs_cadence;
  }
  if (s && s->ground_json && *s->ground_json) {
    try {
      settings.ground = walkcycle::parse_ground_json(s->ground_json, "lw_walker_settings.ground_json");
    } catch (const Error& e) {
      return fail(LW_ERROR_INVALID_ARGUMENT, std::string(where) + ": " + e.what());
    }
  }
  return guarded(where, [&] {
    const walkcycle::WalkFile walk = walkcycle::load_walk(keys_json_path);
    const walkcycle::CycleModel cycle = walkcycle::build_cycle(walk.skeleton, walk.keys);
    return store_model(LW_METHOD_WALKER, walkcycle::make_model(cycle, settings), out);
  });
}

void lw_model_destroy(lw_model* m) { destroy_handle(m); }
lw_method lw_model_method(const lw_model* m) { return m ? m->method : LW_METHOD_ACCENT; }
const lw_skeleton* lw_model_skeleton(const lw_model* m) { return m ? &m->skeleton : nullptr; }

const char* lw_model_humanoid_name(const lw_model* m, int32_t joint, int32_t vrm) {
  if (!m) return nullptr;
  const auto& r = m->skeleton.skeleton.roles;
  for (int i = 0; i < kRoleCount; ++i)
    if (r.joint[static_cast<std::size_t>(i)] == joint && joint >= 0)
      return humanoid_bone(static_cast<Role>(i), vrm ? Humanoid::Vrm : Humanoid::Unity).data();
  return nullptr;
}

// ---- avatars

lw_status lw_avatar_create(const lw_model* m, lw_avatar** out) {
  if (!m || !out) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_avatar_create: model and out must not be NULL");
  *out = nullptr;
  return guarded("lw_avatar_create", [&] {
    auto* a = std::visit(
        [&](const auto& model) { return make_handle<lw_avatar>(lw_avatar{m, state_of(model), Pose(model.skeleton()), {}, {}}); },
        m->model);
    a->world.resize(static_cast<std::size_t>(m->skeleton.skeleton.joint_count()));
    *out = a;
    return LW_OK;
  });
}
void lw_avatar_destroy(lw_avatar* a) { destroy_handle(a); }

lw_status lw_avatar_reset(lw_avatar* a) {
  if (!a) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_avatar_reset: avatar must not be NULL");
  std::visit(
      [&](auto& state) {
        using S = std::decay_t<decltype(state)>;
        if constexpr (std::is_same_v<S, accent::State>) accent::reset(std::get<accent::Model>(a->model->model), state);
        else if constexpr (std::is_same_v<S, ik::State>) ik::reset(std::get<ik::Model>(a->model->model), state);
        else if constexpr (std::is_same_v<S, wip::State>) wip::reset(std::get<wip::Model>(a->model->model), state);
        else if constexpr (std::is_same_v<S, combined::State>) combined::reset(std::get<combined::Model>(a->model->model), state);
        else walkcycle::reset(std::get<walkcycle::Model>(a->model->model), state);
      },
      a->state);
  a->info = {};
  return LW_OK;
}

lw_status lw_avatar_set_floor(lw_avatar* a, double left, double right) {
  if (!a) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_avatar_set_floor: avatar must not be NULL");
  auto* s = std::get_if<wip::State>(&a->state);
  if (auto* c = std::get_if<combined::State>(&a->state)) s = &c->wip;
  if (!s) return fail(LW_ERROR_UNSUPPORTED, "lw_avatar_set_floor: only walking-in-place and combined avatars have a floor");
  if (!std::isfinite(left) || !std::isfinite(right)) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_avatar_set_floor: floor heights must be finite");
  wip::set_floor(*s, left, right);
  return LW_OK;
}

lw_status lw_avatar_update(lw_avatar* a, const lw_frame* frame) {
  if (!a || !frame) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_avatar_update: avatar and frame must not be NULL");
  const TrackerFrame in = to_frame(*frame);
  const UpdateStatus s = std::visit(
      [&](auto& state) {
        using S = std::decay_t<decltype(state)>;
        if constexpr (std::is_same_v<S, accent::State>)
          return step<accent::Model, accent::Info>(*a, state, in);
        else if constexpr (std::is_same_v<S, ik::State>)
          return step<ik::Model, ik::Info>(*a, state, in);
        else if constexpr (std::is_same_v<S, wip::State>)
          return step<wip::Model, wip::Info>(*a, state, in);
        else if constexpr (std::is_same_v<S, combined::State>)
          return step<combined::Model, combined::Info>(*a, state, in);
        else
          return step<walkcycle::Model, walkcycle::Info>(*a, state, in);
      },
      a->state);
  return to_status(s);
}

int32_t lw_avatar_info_count(const lw_avatar* a) { return a ? a->info.count : 0; }

lw_status lw_avatar_info_field(const lw_avatar* a, int32_t i, const char** name, double* number, const char** text) {
  if (!a) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_avatar_info_field: avatar must not be NULL");
  if (i < 0 || i >= a->info.count)
    return fail(LW_ERROR_INVALID_ARGUMENT, "lw_avatar_info_field: field " + std::to_string(i) + " of " +
                                               std::to_string(a->info.count) + " (lw_avatar_info_count)");
  put_field(a->info.items[static_cast<std::size_t>(i)], name, number, text);
  return LW_OK;
}

lw_status lw_avatar_info_find(const lw_avatar* a, const char* key, double* number, const char** text) {
  if (!a || !key) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_avatar_info_find: avatar and name must not be NULL");
  if (const InfoFields::Item* f = a->info.find(key)) {
    put_field(*f, nullptr, number, text);
    return LW_OK;
  }
  std::string names;
  for (int i = 0; i < a->info.count; ++i) names += (i ? ", " : "") + std::string(a->info.items[static_cast<std::size_t>(i)].key);
  return fail(LW_ERROR_INVALID_ARGUMENT, "lw_avatar_info_find: no field '" + std::string(key) + "' " +
                                             (a->info.count ? "(this avatar's: " + names + ")"
                                                            : "(no frame consumed yet since the avatar's creation or reset)"));
}

lw_status lw_avatar_pose(const lw_avatar* a, double* rotations, double* root, double* world, int32_t capacity) {
  if (!a) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_avatar_pose: avatar must not be NULL");
  const int n = a->pose.joint_count();
  if ((rotations || world) && capacity < n)
    return fail(LW_ERROR_INVALID_ARGUMENT, "lw_avatar_pose: capacity " + std::to_string(capacity) + " < " + std::to_string(n) + " joints");
  if (rotations)
    for (int j = 0; j < n; ++j) {
      const Quat& q = a->pose.rotations[static_cast<std::size_t>(j)];
      double* o = rotations + 4 * j;
      o[0] = q.w(), o[1] = q.x(), o[2] = q.y(), o[3] = q.z();
    }
  if (root)
    for (int i = 0; i < 3; ++i) root[i] = a->pose.translations[0][i];
  if (world) {
    auto& g = const_cast<lw_avatar*>(a)->world;  // scratch, sized at creation
    forward_kinematics(a->model->skeleton.skeleton, a->pose, g);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < 3; ++i) world[3 * j + i] = g[static_cast<std::size_t>(j)].translation[i];
  }
  return LW_OK;
}

// ---- engine frames

lw_status lw_convert_positions(lw_engine engine, int32_t to, double* xyz, int32_t count) {
  if (!xyz || count < 0) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_convert_positions: xyz must not be NULL and count >= 0");
  if (engine < LW_ENGINE_LEGWORK || engine > LW_ENGINE_GODOT) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_convert_positions: unknown engine");
  const auto e = static_cast<Engine>(engine);
  for (int32_t i = 0; i < count; ++i) {
    double* p = xyz + 3 * i;
    const Vec3 v = to ? to_engine(e, Vec3(p[0], p[1], p[2])) : from_engine(e, Vec3(p[0], p[1], p[2]));
    p[0] = v.x(), p[1] = v.y(), p[2] = v.z();
  }
  return LW_OK;
}

lw_status lw_convert_rotations(lw_engine engine, int32_t to, double* wxyz, int32_t count) {
  if (!wxyz || count < 0) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_convert_rotations: wxyz must not be NULL and count >= 0");
  if (engine < LW_ENGINE_LEGWORK || engine > LW_ENGINE_GODOT) return fail(LW_ERROR_INVALID_ARGUMENT, "lw_convert_rotations: unknown engine");
  const auto e = static_cast<Engine>(engine);
  for (int32_t i = 0; i < count; ++i) {
    double* p = wxyz + 4 * i;
    const Quat q(p[0], p[1], p[2], p[3]);
    const Quat r = to ? to_engine(e, q) : from_engine(e, q);
    p[0] = r.w(), p[1] = r.x(), p[2] = r.y(), p[3] = r.z();
  }
  return LW_OK;
}

}  // extern "C"
