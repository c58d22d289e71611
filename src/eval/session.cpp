// Figures of one accentuated session (see session.hpp).
#include <legwork/eval/session.hpp>

#include <legwork/eval/metrics.hpp>
#include <legwork/render/render.hpp>

#include <algorithm>
#include <cstdio>

namespace legwork::eval {

using nlohmann::json;

SessionFigures session_figures(const accent::AccentRun& run) {
  SessionFigures f;
  double weight = 0;
  for (const auto& i : run.info) {
    ++f.statuses[accent::status_name(i.match)];
    weight += i.match_weight;
  }
  f.mean_match_weight = weight / run.info.size();
  f.frames_per_second = run.output.frame_count() / std::max(run.seconds, 1e-9);
  return f;
}

json truth_error(const Motion& output, const Motion& truth) {
  const TrialMetrics t = evaluate_trial(role_track(output), role_track(truth));
  return json{{"left_hand_cm", t.part_cm[0]}, {"right_hand_cm", t.part_cm[1]}, {"full_body_cm", t.mpjpe_cm},
              {"lower_body_cm", t.part_cm[3]}, {"foot_skating_cm", t.foot_skating_cm}};
}

std::string describe_truth_error(const char* label, const json& e) {
  char buf[512];
  std::snprintf(buf, sizeof buf, "%-12s full body %.1f cm, lower body %.1f cm, hands %.1f / %.1f cm, foot skating %.2f cm/frame\n",
                label, e["full_body_cm"].get<double>(), e["lower_body_cm"].get<double>(), e["left_hand_cm"].get<double>(),
                e["right_hand_cm"].get<double>(), e["foot_skating_cm"].get<double>());
  return buf;
}

json session_per_frame(const accent::AccentRun& run) {
  json per = json::array();
  for (const auto& i : run.info)
    per.push_back({{"status", accent::status_name(i.match)}, {"match_weight", i.match_weight}, {"fallback", i.fallback},
                   {"matches", i.matches}, {"best_distance", i.best_distance}});
  return per;
}

void render_session_video(std::span<const TrackerFrame> frames, double fps, const Motion& accentuated, const Motion* ik,
                          const Motion* truth, const std::string& title, const std::string& path) {
  const Motion input = accent::input_markers(frames, fps);
  std::vector<const Motion*> panels{&input, &accentuated};
  std::vector<std::string> labels{"input (head, hands)", "accentuated"};
  if (ik) {
    panels.push_back(ik);
    labels.push_back("IK baseline");
  }
  if (truth) {
    panels.push_back(truth);
    labels.push_back("ground truth");
  }
  render::VideoOptions vo;
  vo.fps = 30;
  vo.camera.view = render::View::ThreeQuarter;
  vo.follow = true;  // bodies fill their panels
  vo.camera.width = 280 * static_cast<int>(panels.size());
  vo.camera.height = 420;
  vo.title = title;
  render::render_video_side_by_side(panels, labels, vo, path);
}

}  // namespace legwork::eval
