#pragma once
// The accentuation tool (`legwork accent run`) as a library call: a session
// (a BVH trial whose head and wrists act as headset + controllers, or a
// headset CSV) through a database -> the accentuated motion (optionally
// retargeted), its figures against the ground truth and the IK baseline, a
// JSON report and a side-by-side video. Prints its figures and the files it
// writes to stdout as the command line does; throws legwork::Error naming the option.
#include <legwork/accent/accent.hpp>
#include <legwork/io/motion_file.hpp>

#include <string>

namespace legwork::eval {

// Everything `legwork accent run` is asked for (file paths empty = not written).
struct AccentJob {
  std::string input, db, out, video, json_path, classes, mode = "fast", target, save_session;
  io::MotionReadOptions input_options;  // of a .bvh input
  bool compare_ik = false, no_align = false, no_smooth = false, no_limits = false, no_class_recognition = false;
  double class_hold = accent::Settings{}.class_hold_seconds, class_margin = accent::Settings{}.class_margin;
  int k = accent::Settings{}.k_left, k_left = -1, k_right = -1;
  double threshold = 6.0, height = 0, exaggerate = 1.0, hand_ik = accent::Settings{}.hand_ik, max_tilt = accent::Settings{}.max_head_tilt_deg;
  double smooth_halflife = accent::Settings{}.smooth_halflife;
  double smooth_feedforward = accent::Settings{}.smooth_feedforward;
  double lying_root_smoothing = accent::Settings{}.lying_root_smoothing;
  double lying_crown = accent::Settings{}.lying_crown;
  double other_class_cost = accent::Settings{}.other_class_cost;
  double search_interval = accent::Settings{}.search_interval;
  double foot_lift_height = accent::Settings{}.foot_lift_height;
  double foot_lock_slack = accent::Settings{}.foot_lock_slack;
  double foot_lock_hold = accent::Settings{}.foot_lock_hold_seconds;
  double foot_swing_speed = accent::Settings{}.foot_swing_speed;
  double travel_weight = accent::Settings{}.travel_weight;
  double max_head_height_diff = accent::Settings{}.max_head_height_diff;
  bool no_floor = false;
  double floor_height = accent::Settings{}.floor_height;
};

// "fast", "exact", "brute" -> the search mode; throws naming --mode otherwise.
accent::SearchMode parse_search_mode(const std::string& mode);
void run_accent_job(const AccentJob& job);

}  // namespace legwork::eval
