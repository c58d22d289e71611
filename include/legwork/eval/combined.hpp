#pragma once
// One avatar, two sources, measured (`legwork eval combined`): over walking
// trials, the head and wrists act as headset + controllers and the ankles as
// foot trackers; the combined avatar (legwork::combined) is scored against the
// capture beside its upper-body method alone (the IK avatar; with a database
// also accentuation): full-body, lower-body and hand error, foot skating.
#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

namespace legwork::eval {

struct CombinedEvalRun {
  std::vector<std::string> files;  // walking trials (BVH)
  std::string database;            // optional .lwdb: also accentuation and combined(accent)
  double rate = 30;                // tracker rate, Hz (the database's rate when given)
  std::string video;               // optional .mp4: the first trial, truth beside each method
  // Optional learned walking-in-place table (`legwork wip learn`) for the
  // learned-mapping rows of every trial, e.g. one learned without the
  // evaluated subjects; empty: each trial's table is learned from the other
  // subjects in `files` (none when they are too few).
  std::string wip_table;
  std::function<void(int done, int total, const std::string& item)> progress;
};

// Per method: frames-weighted means over the trials of full_body_cm,
// lower_body_cm, left/right_hand_cm, foot_skating_cm, and the capture's own
// foot skating; per trial the same. Throws legwork::Error for no trials or an
// unreadable database; unreadable trials are listed under "skipped".
nlohmann::json evaluate_combined(const CombinedEvalRun& run);
// A Markdown table of the methods (rows) and figures (columns) of `report`.
std::string combined_table(const nlohmann::json& report);

}  // namespace legwork::eval
