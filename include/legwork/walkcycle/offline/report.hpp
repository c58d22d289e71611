#pragma once
// Reports of the walk-cycle generator: the JSON fields `legwork walkcycle
// --report` and `walkcycle extract --report` write, and the summary lines
// printed with them. Figures rounded to 6 decimals (stable diffs).
#include <legwork/walkcycle/cycle.hpp>
#include <legwork/walkcycle/offline/extract.hpp>
#include <legwork/walkcycle/offline/measure.hpp>
#include <legwork/walkcycle/offline/walk.hpp>

#include <nlohmann/json.hpp>

#include <string>

namespace legwork::walkcycle {

// v rounded to 6 decimals (-0 becomes 0).
double round6(double v);

// The cycle's fields (walk, frames_per_cycle, fps, step length, loop seam,
// key frames and foot heights, floor contact); the printed lines are appended to `text`.
nlohmann::json cycle_report(const CycleModel& model, const std::string& name, std::string& text);

// Adds a walk's fields (steps, frames, stance slip, path figures, footsteps)
// to `report`; `ms` is how long walk_path took. Printed lines appended to `text`.
void add_walk_report(const CycleModel& model, const WalkResult& w, double ms, nlohmann::json& report, std::string& text);

// Adds the fields of the in-place cycle written instead of a walk.
void add_in_place_report(const Motion& cycle, nlohmann::json& report);

// A joint's arc over the cycle with its smoothness (1 and 4 samples per frame).
struct ArcFigures {
  int joint = -1;
  std::string name;
  Arc arc;   // one point per frame (the CSV)
  Arc fine;  // four points per frame (the pictures, the smoothness)
  ArcSmoothness smooth;
  bool jerky = false;  // jerk ratio > 5 on an arc wider than 10 cm
};
// `joint_name`: a joint or role name; throws legwork::Error naming --arc if unknown.
ArcFigures arc_figures(const CycleModel& model, const std::string& joint_name);
std::string arc_csv(const ArcFigures& a);      // frame,x,y,z,key per frame
std::string arc_title(const ArcFigures& a);    // picture title
std::string arc_summary(const ArcFigures& a);  // the printed line
nlohmann::json arc_report(const ArcFigures& a, const std::string& csv_path);

// The report of `walkcycle extract` on `clip` (read from `clip_path`).
nlohmann::json extraction_report(const Extraction& ex, const Motion& clip, const std::string& clip_path);
// Its printed summary (steps found, cycle, timing, resynthesis error).
std::string extraction_summary(const Extraction& ex, const WalkKeys& keys);

}  // namespace legwork::walkcycle
