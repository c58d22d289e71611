#pragma once
// The evaluation report: report.json (figures per protocol, method and class,
// mean and SD across folds), report.md (tables with the document's published
// figures beside ours, targets met or not, computed from the run) and charts
// (per-body-part bars like the document's Figure 4 A, per-class bars,
// ablation bars) as PNG and SVG. Offline code: throws legwork::Error when a
// file cannot be written.
#include <legwork/eval/run.hpp>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace legwork::eval {

// Metric keys of report.json, in table order, with their units.
struct MetricKey {
  const char* key;
  const char* label;
  const char* unit;
};
const std::vector<MetricKey>& metric_keys();
// The value of metric `key` in one fold's metrics.
double metric_value(const TrialMetrics& m, const std::string& key);

// report.json as an object:
//   { "meta": {...}, "paper": {...}, "targets": [...],
//     "cross_subject": { "folds": n, "skipped_classes": {...},
//                        "accent": { <metric>: mean, <metric>_sd: sd, "frames_per_second": x,
//                                    "folds": n, "classes": { "<class>": { <metric>: ..., ... } },
//                                    "class_mean": { <metric>: mean over classes } },
//                        "ik": {...}, "ablation": { "<variant>": {...} } },
//     "cross_trial": {...}, "cross_dataset": {...} }
nlohmann::json report_json(const EvalResult& r);
std::string report_markdown(const nlohmann::json& report);
// The printed summary of report.json: per protocol the engine's and the IK
// baseline's figures, the ablation, and each target met or not.
std::string report_summary(const nlohmann::json& report);
// Writes report.json, report.md, body_parts.{png,svg}, classes.{png,svg},
// ablation.{png,svg} (when there is an ablation) into dir (created).
// Returns the files written.
std::vector<std::string> write_report(const EvalResult& r, const std::string& dir);
// compare.mp4 in dir: ground truth, engine and IK baseline side by side on
// the speed pass's held-out trial (first `seconds`). Needs the ffmpeg
// program (throws legwork::Error if it is missing). Returns the path.
std::string write_comparison_video(const EvalResult& r, const std::string& dir, double seconds = 12.0);

}  // namespace legwork::eval
