#pragma once
// The one place where `legwork serve` calls the runtimes (accent, ik, wip,
// combined, walker). Each live avatar owns one Method: built from the session's
// options, fed one TrackerFrame per update, writing a pose on skeleton().
// Adapting the server to a runtime API change touches only methods.cpp.
#include <legwork/accent/accent.hpp>
#include <legwork/core/info_fields.hpp>
#include <legwork/core/motion.hpp>
#include <legwork/core/tracker.hpp>
#include <legwork/walkcycle/walker.hpp>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace legwork::accent {
class Database;
}
namespace legwork::wip {
struct LearnedMapping;
}

namespace legwork::serve {

// What the server shares read-only between every session.
struct Resources {
  const accent::Database* db = nullptr;  // null: methods needing a database are unavailable
  const Skeleton* skeleton = nullptr;    // avatar skeleton for ik/wip when there is no database
  const wip::LearnedMapping* wip_learned = nullptr;  // null: the learned walking-in-place mapping is unavailable
  std::string walks_dir;                 // walk files (legwork-walk/1) for the walker ("" = no walker)
  std::string database_name;             // for /api/info
};

// Session options (the hello message, later "options" messages).
struct MethodOptions {
  std::string method = "accent";     // accent | ik | wip | combined | walker
  std::vector<std::string> classes;  // accent classes to match (empty = all)
  // accent: hand-motion exaggeration about the head. The accent fields below are
  // accent::Settings' and take the engine's defaults from it.
  double exaggeration = accent::Settings{}.exaggeration;
  double user_height = 0;            // metres; 0 = the avatar skeleton's own height
  std::string mapping = "document";  // wip / combined legs' depths: document (equations 1-4) | learned
  std::string detector;              // wip / combined legs' foot-off detector: document | adaptive ("" = the default)
  // accent: with several classes allowed, recognise the activity and search
  // only its class (accent::Settings::recognize_class); false: search all.
  bool recognize_class = accent::Settings{}.recognize_class;
  // accent (and combined's upper body): metres a foot released at the end of
  // a contact is lifted on its way back (accent::Settings::foot_lift_height).
  double foot_lift_height = accent::Settings{}.foot_lift_height;
  // accent::Settings::foot_lock_slack (metres) and foot_swing_speed (m/s), the engine's defaults.
  double foot_lock_slack = accent::Settings{}.foot_lock_slack;
  double foot_lock_hold_seconds = accent::Settings{}.foot_lock_hold_seconds;  // seconds (accent::Settings::foot_lock_hold_seconds)
  double foot_swing_speed = accent::Settings{}.foot_swing_speed;
  // accent (and combined's upper body): accent::Settings::travel_weight, the engine's default (0 = off).
  double travel_weight = accent::Settings{}.travel_weight;
  // accent (and combined's upper body): accent::Settings::max_head_height_diff, the engine's default (0 = off).
  double max_head_height_diff = accent::Settings{}.max_head_height_diff;
  // accent (and combined's upper body): accent::Settings::smooth_feedforward, the engine's default (0 = off).
  double smooth_feedforward = accent::Settings{}.smooth_feedforward;
  // accent (and combined's upper body): accent::Settings::lying_root_smoothing, the engine's default (1 = off).
  double lying_root_smoothing = accent::Settings{}.lying_root_smoothing;
  // accent (and combined's upper body): accent::Settings::lying_crown, the engine's default (0 = off).
  double lying_crown = accent::Settings{}.lying_crown;
  // accent (and combined's upper body): accent::Settings::other_class_cost, the engine's default (0 = the recognised class only).
  double other_class_cost = accent::Settings{}.other_class_cost;
  // accent (and combined's upper body): accent::Settings::search_interval, the engine's default (0 = search every frame).
  double search_interval = accent::Settings{}.search_interval;
  // accent (and combined's upper body): accent::Settings::floor and floor_height, the engine's defaults.
  bool floor = accent::Settings{}.floor;
  double floor_height = accent::Settings{}.floor_height;
  std::string walk = "normal";       // walker: the walk file's name in Resources::walks_dir, without .json
  std::string root = "smooth";       // walker: smooth (even travel, legs by IK) | pivot (document 001)
  std::string ground;                // walker: the ground walked on, JSON of a path file's "ground" object ("" = flat)
  // walker: walkcycle::Settings' max_turn_per_step (radians), soft_reach and
  // stairs_cadence; the walker's defaults, checked by walkcycle::make_model.
  double max_turn_per_step = walkcycle::Settings{}.max_turn_per_step;
  double soft_reach = walkcycle::Settings{}.soft_reach;
  double stairs_cadence = walkcycle::Settings{}.stairs_cadence;
};

class Method {
 public:
  virtual ~Method() = default;
  // One frame in, one pose out (local rotations, root translation = world
  // position). Rejected leaves `out` untouched. Never throws.
  virtual UpdateStatus update(const TrackerFrame& frame, PoseRef out, InfoFields& info) = 0;
  // The output pose's skeleton (fixed for the method's lifetime).
  virtual const Skeleton& skeleton() const = 0;
};

// Builds a method; throws legwork::Error with a message fit for the client
// ("unknown method 'x' (available: ...)", "unknown class ...", "method
// 'accent' needs a database: start the server with --db FILE").
std::unique_ptr<Method> make_method(const Resources& res, const MethodOptions& opt);
// Methods this server can run with these resources, in the protocol's order.
std::vector<std::string> available_methods(const Resources& res);
// Every method name the protocol knows.
const std::vector<std::string>& known_methods();

}  // namespace legwork::serve
