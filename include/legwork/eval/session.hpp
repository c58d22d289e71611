#pragma once
// Figures of one accentuated session (`legwork accent run`): match statuses,
// speed, per-frame match statistics and, when the input was a full-body trial,
// the error of the result (and of the IK baseline) against the ground truth.
#include <legwork/accent/offline/run.hpp>

#include <nlohmann/json.hpp>

#include <map>
#include <span>
#include <string>

namespace legwork::eval {

struct SessionFigures {
  std::map<std::string, int> statuses;  // match status name -> frames
  double mean_match_weight = 0;
  double frames_per_second = 0;  // of update()
};
SessionFigures session_figures(const accent::AccentRun& run);

// Error against the ground truth, cm: left_hand_cm, right_hand_cm, full_body_cm,
// lower_body_cm, foot_skating_cm (cm per frame).
nlohmann::json truth_error(const Motion& output, const Motion& truth);
// "LABEL full body .. cm, lower body .. cm, hands .. / .. cm, foot skating .. cm/frame\n"
std::string describe_truth_error(const char* label, const nlohmann::json& e);

// One entry per frame: status, match_weight, fallback, matches, best_distance.
nlohmann::json session_per_frame(const accent::AccentRun& run);

// Side-by-side MP4 of a session: the input devices, the accentuated body, then
// the IK baseline and the ground truth when given (null = left out).
void render_session_video(std::span<const TrackerFrame> frames, double fps, const Motion& accentuated, const Motion* ik,
                          const Motion* truth, const std::string& title, const std::string& path);

}  // namespace legwork::eval
