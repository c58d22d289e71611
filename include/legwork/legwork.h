/* legwork C API: the per-frame contract of docs/architecture.md for engines
 * (Unity, Unreal, Godot) and any language with a C FFI.
 *
 * Shape: opaque handles, plain structs, lw_status codes. No C++ exception
 * crosses this boundary; on an error the function returns a negative status
 * and lw_last_error() (thread-local) says why in words.
 *
 *   lw_database  an accentuation database, memory-mapped read-only
 *   lw_skeleton  a skeleton (from a BVH file or a database)
 *   lw_model     an immutable, shareable avatar model of one method
 *                (accentuation, full-body IK, walking-in-place legs, walker)
 *   lw_avatar    one avatar's state + its output pose; lw_avatar_update()
 *                per frame allocates nothing.
 *
 * Units and frames: metres, seconds, legwork's world frame (right-handed,
 * y up, the character faces +z, +x is its left). lw_convert_* give Unity,
 * Unreal and Godot frames (formulas in legwork/core/engine.hpp and the README).
 * Quaternions are (w, x, y, z).
 *
 * Thread safety: lw_database, lw_skeleton and lw_model are immutable after
 * creation and may be used from any number of threads at once. An lw_avatar
 * must be used by one thread at a time. lw_set_allocator must be called before
 * any other function, from one thread.
 */
#ifndef LEGWORK_LEGWORK_H
#define LEGWORK_LEGWORK_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32)
#if defined(LEGWORK_C_BUILD)
#define LW_API __declspec(dllexport)
#else
#define LW_API __declspec(dllimport)
#endif
#else
#define LW_API __attribute__((visibility("default")))
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ABI version: bumped whenever a struct layout or a signature changes. */
#define LW_ABI_VERSION 15u
LW_API uint32_t lw_abi_version(void);
LW_API const char* lw_version_string(void);

typedef enum lw_status {
  LW_OK = 0,                       /* frame consumed, every needed device usable */
  LW_DEGRADED = 1,                 /* consumed; a needed device was missing (held / faded) */
  LW_REJECTED = 2,                 /* not consumed: time not finite, absurd or not increasing */
  LW_RESTARTED = 3,                /* the stream's clock restarted; the avatar was reset */
  LW_ERROR_INVALID_ARGUMENT = -1,  /* a NULL pointer, a bad value or size */
  LW_ERROR_IO = -2,                /* a file could not be read or written */
  LW_ERROR_FORMAT = -3,            /* a file's content is malformed or of another version */
  LW_ERROR_OUT_OF_MEMORY = -4,
  LW_ERROR_UNSUPPORTED = -5,       /* the operation does not apply to this method */
  LW_ERROR_INTERNAL = -6
} lw_status;

/* The reason for the last error on this thread ("" if none). Valid until the
 * next failing call on this thread. */
LW_API const char* lw_last_error(void);
LW_API const char* lw_status_name(lw_status s);

/* Optional caller-supplied allocator for the handle objects legwork creates
 * (NULL restores malloc/free); as in ACL, the engine's allocator sees and
 * accounts for every handle. The containers inside a handle (joint arrays, a
 * database's search index) are sized once at creation by the C++ runtime's
 * allocator; nothing is allocated per frame. */
typedef struct lw_allocator {
  void* (*allocate)(size_t size, size_t alignment, void* user);
  void (*deallocate)(void* pointer, void* user);
  void* user;
} lw_allocator;
LW_API lw_status lw_set_allocator(const lw_allocator* allocator);

/* ---- tracker input ------------------------------------------------------ */

enum { LW_HEAD = 0, LW_LEFT_HAND = 1, LW_RIGHT_HAND = 2, LW_LEFT_FOOT = 3, LW_RIGHT_FOOT = 4, LW_DEVICE_COUNT = 5 };

typedef struct lw_device {
  double position[3]; /* metres, world */
  double rotation[4]; /* w, x, y, z, world; head: identity looks along +z */
  int32_t valid;      /* 0: not tracked this frame */
} lw_device;

typedef struct lw_frame {
  double time; /* absolute seconds, increasing */
  lw_device devices[LW_DEVICE_COUNT];
} lw_frame;

/* ---- databases and skeletons -------------------------------------------- */

typedef struct lw_database lw_database;
typedef struct lw_skeleton lw_skeleton;

/* Memory-maps a database built by `legwork accent build` and checks it
 * (magic, version, checksum, contents). */
LW_API lw_status lw_database_load(const char* path, lw_database** out);
LW_API void lw_database_destroy(lw_database* db);
LW_API int32_t lw_database_class_count(const lw_database* db);
/* Name of class i (owned by the database), NULL if out of range. */
LW_API const char* lw_database_class_name(const lw_database* db, int32_t i);
LW_API int32_t lw_database_window_count(const lw_database* db);
/* The database's skeleton (owned by the database; do not destroy). */
LW_API const lw_skeleton* lw_database_skeleton(const lw_database* db);

/* Skeleton of a BVH file (units detected, metres). */
LW_API lw_status lw_skeleton_load_bvh(const char* path, lw_skeleton** out);
LW_API void lw_skeleton_destroy(lw_skeleton* s);
LW_API int32_t lw_skeleton_joint_count(const lw_skeleton* s);
LW_API const char* lw_skeleton_joint_name(const lw_skeleton* s, int32_t joint);
/* Parent of each joint (-1 for the root), depth-first order: `parents` holds
 * `capacity` entries. */
LW_API lw_status lw_skeleton_parents(const lw_skeleton* s, int32_t* parents, int32_t capacity);

/* Tracker frames from a BVH trial's head, wrists and ankles (the CMU T-pose
 * frame 0 dropped if drop_first), at `rate` Hz (0 = the file's rate). The
 * array is allocated by legwork: release it with lw_frames_free. */
LW_API lw_status lw_frames_from_bvh(const char* path, double rate, int32_t drop_first, lw_frame** frames, int32_t* count);
LW_API void lw_frames_free(lw_frame* frames);

/* ---- models --------------------------------------------------------------- */

typedef struct lw_model lw_model;

typedef enum lw_method {
  LW_METHOD_ACCENT = 0,
  LW_METHOD_IK = 1,
  LW_METHOD_WIP = 2,
  LW_METHOD_WALKER = 3,
  LW_METHOD_COMBINED = 4
} lw_method;

typedef struct lw_accent_settings {
  const char* classes;   /* comma-separated activity classes; NULL or "" = all */
  int32_t k;             /* matches per hand (1..32) */
  double exaggeration;   /* hands scaled about the head before matching (> 0) */
  double user_height;    /* metres; 0 = the database skeleton's height */
  double hand_ik;        /* 0..1: wrists pulled onto the controllers */
  double smooth_halflife; /* seconds; 0 = the paper's EWMA only */
  int32_t recognize_class; /* 1: with several classes allowed, recognise the activity from the input (with
                              hysteresis) and search only its class; 0: search every allowed class each frame */
  double foot_lift_height; /* metres (0..0.5) a foot released at the end of a contact is lifted on its way back;
                              0 = slides along the floor (ABI 3) */
  double foot_lock_slack;  /* metres (0..1) the synthesized foot may move from a planted foot before the plant creeps
                              after it; 0 = it always creeps (ABI 4) */
  double foot_swing_speed; /* m/s (0..10) above which a free foot is swinging and is lifted to clear the floor by
                              foot_lift_height; 0 = off (ABI 4) */
  double travel_weight;    /* (0..100) weight of the user's head travel (horizontal speed, vertical velocity, height)
                              against the hand features when ranking candidates; 0 = hand features only (ABI 6) */
  double max_head_height_diff; /* (0..2) while the user stands upright, candidates whose head is lower than the
                                  user's by more than this share of body height are rejected (while the user is
                                  lower, those whose head is higher by more, unless none would be left); 0 = off
                                  (ABI 7) */
  double smooth_feedforward; /* (0..1) share of the matched candidates' own motion the smoothing plays forward, so a
                                moving body does not trail its target; 0 = the filters pull toward a still target (ABI 8) */
  double lying_root_smoothing; /* (1..20) times the spring's half-life on the root for a lying user (head at most
                                  0.5 of their height up); 1 = off (ABI 9) */
  double lying_crown; /* (0..1) share of a lying user's candidate turn taken from the headset (yaw from its crown, which
                         points away from the feet; roll from its face), and of the standing IK body taken out; 0 = off
                         (ABI 10) */
  double other_class_cost; /* 0, or a factor in [1, 1e6]: while the class is recognised (recognize_class, several
                              classes allowed), the other allowed classes are searched too, their distances times this
                              factor; 0 = the recognised class only (ABI 11) */
  double search_interval;  /* seconds (0..1) between two searches of the database; in between each hand's matches are
                              continued in their trials (the last matches and their next windows, ranked by distance);
                              0 = search every frame (ABI 13) */
  int32_t floor;           /* 1: feet never go through the floor (the knee bends; a foot pushed into it stands on it);
                              0: they follow the synthesized pose below it too (ABI 14) */
  double floor_height;     /* metres (-10..10): the play area's floor is y = floor_height (0 = a floor-level tracking
                              origin) (ABI 14) */
  double foot_lock_hold_seconds;   /* seconds (0..10) a planted foot stays put before it creeps after the synthesized foot;
                              0 = it creeps from touch-down (ABI 15) */
} lw_accent_settings;
LW_API void lw_accent_settings_default(lw_accent_settings* s);
/* The database must outlive the model. */
LW_API lw_status lw_model_create_accent(const lw_database* db, const lw_accent_settings* s, lw_model** out);

/* Full-body IK (the VRIK-style IK baseline) on a skeleton (copied). */
LW_API lw_status lw_model_create_ik(const lw_skeleton* skeleton, lw_model** out);

/* Walking-in-place legs on a skeleton (copied), driven by the feet devices'
 * heights; the head's yaw steers. Call lw_avatar_set_floor after create. */
LW_API lw_status lw_model_create_wip(const lw_skeleton* skeleton, lw_model** out);
/* The same with the depth mapping learned from real walks instead of the
 * document's equations: `table_path` is a table written by `legwork wip learn`
 * (the repository ships data/wip/learned_mapping.txt); read once, copied. */
LW_API lw_status lw_model_create_wip_learned(const lw_skeleton* skeleton, const char* table_path, lw_model** out);

/* Walking-in-place options (legwork::wip::Settings, the rest at their defaults). */
typedef enum lw_wip_detector {
  LW_WIP_DETECTOR_DEFAULT = 0,   /* the library's default detector */
  LW_WIP_DETECTOR_DOCUMENT = 1,  /* the document's H1/V1/V2 on the 4 Hz height (the reference) */
  LW_WIP_DETECTOR_ADAPTIVE = 2   /* lighter filter, per-foot stance baseline, jitter-scaled thresholds (docs/wip.md) */
} lw_wip_detector;
typedef struct lw_wip_settings {
  const char* table_path;  /* NULL: the document's depth mapping; else the learned table (as lw_model_create_wip_learned) */
  int32_t detector;        /* lw_wip_detector */
} lw_wip_settings;
LW_API void lw_wip_settings_default(lw_wip_settings* s);
/* Walking-in-place legs with these options (s NULL = defaults). */
LW_API lw_status lw_model_create_wip_with(const lw_skeleton* skeleton, const lw_wip_settings* s, lw_model** out);

/* A walk-cycle walker from a key-pose JSON file (skeleton found next to it);
 * steered frame by frame by the head device's yaw. Default settings. */
LW_API lw_status lw_model_create_walker(const char* keys_json_path, lw_model** out);

typedef enum lw_walker_root {
  LW_WALKER_ROOT_SMOOTH = 0, /* the root travels evenly, the legs (two-bone IK) hold the planted feet (default) */
  LW_WALKER_ROOT_PIVOT = 1   /* document 001: the root is pushed so the planted foot's pivot stays put */
} lw_walker_root;
typedef struct lw_walker_settings {
  int32_t root;              /* lw_walker_root */
  double max_turn_per_step;  /* radians of heading change per step, >= 0 */
  double soft_reach;         /* smooth root: fraction of a leg's length it may straighten to, (0, 1] */
  /* The ground walked on (smooth root): the JSON text of a path file's "ground"
   * object, e.g. {"slope": {"origin": [0, 1], "direction": [0, 1], "grade": 0.1}}
   * or {"heightfield": {...}} or {"stairs": {...}} (docs/walkcycle.md); NULL or
   * "" = the flat floor. Copied by lw_model_create_walker_with_settings. */
  const char* ground_json;
  /* Stairs: the cycle's rate while climbing or descending, a fraction of the
   * flat walk's, (0, 1] (default 0.8; ABI 5). */
  double stairs_cadence;
} lw_walker_settings;
LW_API void lw_walker_settings_default(lw_walker_settings* s);
/* The walker with settings (`s` NULL = defaults); a bad value is
 * LW_ERROR_INVALID_ARGUMENT naming the field. */
LW_API lw_status lw_model_create_walker_with_settings(const char* keys_json_path, const lw_walker_settings* s, lw_model** out);

/* One avatar, two sources (legwork::combined): the upper body from head and
 * hands by accentuation over `db` (settings `s`, NULL = defaults), or, with
 * db NULL, by full-body IK on `skeleton` (copied); the leg joints (hips down)
 * from walking-in-place on the feet devices, faded over 0.3 s when both feet
 * are found or lost. lw_avatar_set_floor applies to its legs. The database
 * must outlive the model. */
LW_API lw_status lw_model_create_combined(const lw_database* db, const lw_accent_settings* s, const lw_skeleton* skeleton,
                                          lw_model** out);
/* The same with the legs' depth mapping learned from real walks (the table at
 * `table_path`, as lw_model_create_wip_learned). */
LW_API lw_status lw_model_create_combined_learned(const lw_database* db, const lw_accent_settings* s,
                                                  const lw_skeleton* skeleton, const char* table_path, lw_model** out);

LW_API void lw_model_destroy(lw_model* m);
LW_API lw_method lw_model_method(const lw_model* m);
/* The output pose's skeleton (owned by the model). */
LW_API const lw_skeleton* lw_model_skeleton(const lw_model* m);
/* Unity HumanBodyBones (vrm = 0) or VRM humanoid (vrm = 1) name of a joint of
 * the model's skeleton, or NULL if it has no humanoid role. */
LW_API const char* lw_model_humanoid_name(const lw_model* m, int32_t joint, int32_t vrm);

/* ---- avatars --------------------------------------------------------------- */

typedef struct lw_avatar lw_avatar;

/* The model must outlive the avatar. */
LW_API lw_status lw_avatar_create(const lw_model* m, lw_avatar** out);
LW_API void lw_avatar_destroy(lw_avatar* a);
LW_API lw_status lw_avatar_reset(lw_avatar* a);
/* Walking-in-place only: the tracker-space heights of the floor under each ankle. */
LW_API lw_status lw_avatar_set_floor(lw_avatar* a, double left, double right);

/* One frame. Returns LW_OK / LW_DEGRADED / LW_REJECTED / LW_RESTARTED, or a
 * negative error for a NULL argument. Allocates nothing. */
LW_API lw_status lw_avatar_update(lw_avatar* a, const lw_frame* frame);

/* The current output pose into caller buffers sized for `capacity` joints
 * (any pointer may be NULL to skip it): local rotations (4 per joint, w x y z),
 * the root's world position (3), and model-space = world joint positions
 * (3 per joint). */
LW_API lw_status lw_avatar_pose(const lw_avatar* a, double* local_rotations, double* root_position, double* world_positions,
                                int32_t capacity);

/* The figures of the last consumed frame (ABI 12), by the names of the
 * server's pose "info" object (docs/protocol.md, "Per-frame info"), each a
 * number or a text:
 *   accentuation  match (text: matched, partial, unmatched, tracking-lost),
 *                 match_weight, fallback, matches_left, matches_right,
 *                 active_class (index for lw_database_class_name, -1 when not
 *                 recognising), classes_searched
 *   full-body IK  steps, lean, head_tracked
 *   walking-in-place  walking, speed, distance, heading, phase_left, phase_right
 *   combined      walking, speed, distance, heading, legs (text), legs_weight
 *   walker        step, heading, desired_heading, planted, pivot, pelvis_drop,
 *                 reach_limited
 * None before the first consumed frame or after lw_avatar_reset; a rejected
 * frame keeps the last ones. Texts are static strings. Allocates nothing. */
LW_API int32_t lw_avatar_info_count(const lw_avatar* a);
/* Field i (0 <= i < lw_avatar_info_count): its name, and its text (NULL for a
 * number) or number (0 for a text). Any out pointer may be NULL. */
LW_API lw_status lw_avatar_info_field(const lw_avatar* a, int32_t i, const char** name, double* number, const char** text);
/* The field called `name`; LW_ERROR_INVALID_ARGUMENT (lw_last_error() lists
 * this avatar's fields) when there is none. */
LW_API lw_status lw_avatar_info_find(const lw_avatar* a, const char* name, double* number, const char** text);

/* ---- engine frames ------------------------------------------------------- */

typedef enum lw_engine { LW_ENGINE_LEGWORK = 0, LW_ENGINE_UNITY = 1, LW_ENGINE_UNREAL = 2, LW_ENGINE_GODOT = 3 } lw_engine;
/* In place: `count` positions (xyz) / rotations (wxyz) from legwork's frame
 * into the engine's (to_engine = 1) or back (0). */
LW_API lw_status lw_convert_positions(lw_engine engine, int32_t to_engine, double* xyz, int32_t count);
LW_API lw_status lw_convert_rotations(lw_engine engine, int32_t to_engine, double* wxyz, int32_t count);

#ifdef __cplusplus
}
#endif

#endif /* LEGWORK_LEGWORK_H */
