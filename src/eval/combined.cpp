#include <legwork/eval/combined.hpp>

#include <legwork/accent/database.hpp>
#include <legwork/accent/offline/run.hpp>
#include <legwork/combined/combined.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/eval/metrics.hpp>
#include <legwork/eval/run.hpp>
#include <legwork/eval/session.hpp>
#include <legwork/eval/wip.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/render/render.hpp>

#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>

namespace legwork::eval {

namespace {

using json = nlohmann::json;
const char* const kFigures[] = {"full_body_cm", "lower_body_cm", "left_hand_cm", "right_hand_cm", "foot_skating_cm"};

Motion run_combined(const combined::Model& model, std::span<const TrackerFrame> frames, double fps) {
  combined::State state(model);
  Motion out(model.skeleton(), fps, static_cast<int>(frames.size()));
  Pose pose(model.skeleton());
  for (std::size_t f = 0; f < frames.size(); ++f) {
    combined::update(model, frames[f], state, pose.ref());  // a rejected frame repeats the last pose
    out.set_frame(static_cast<int>(f), pose);
  }
  return out;
}

struct Sum {
  std::map<std::string, double> total;
  long frames = 0;
  void add(const json& e, int n) {
    for (const char* k : kFigures) total[k] += e[k].get<double>() * n;
    frames += n;
  }
  json mean() const {
    json j;
    for (const char* k : kFigures) j[k] = frames ? total.at(k) / static_cast<double>(frames) : 0.0;
    j["frames"] = frames;
    return j;
  }
};

Motion load_truth(const std::string& file, double rate) {
  io::BvhReadOptions o;
  o.drop_first_frame = true;
  return resample(io::load_bvh(file, o), rate);
}

// The learned leg mapping for each held-out subject, built the way `wip eval`
// builds it: from the other subjects' trials only (unreadable trials are
// left out here and listed as skipped by the main loop).
using TablesBySubject = std::map<std::string, std::optional<wip::LearnedMapping>>;
TablesBySubject held_out_tables(const CombinedEvalRun& run, double rate) {
  WipEvalOptions opt;
  opt.settings.signal.rate = rate;
  std::map<std::string, std::vector<wip::LearnSample>> by_subject;
  for (const auto& file : run.files) {
    const std::string name = std::filesystem::path(file).stem().string();
    try {
      const auto samples = trial_learning_samples(load_truth(file, rate), opt);
      auto& all = by_subject[subject_of(name)];
      all.insert(all.end(), samples.begin(), samples.end());
    } catch (const Error&) {
    }
  }
  return learned_tables_by_subject(by_subject);
}

// The first trial as a video: truth beside each method, in place.
void write_video(const std::string& path, const std::string& name, const Motion& truth,
                 const std::map<std::string, Motion>& outputs) {
  const int n = truth.frame_count();
  std::vector<Motion> shown{truth};
  std::vector<std::string> labels{"capture (truth)"};
  for (const auto& [method, motion] : outputs) shown.push_back(motion), labels.push_back(method);
  for (Motion& m : shown)
    for (int f = 0; f < n; ++f) {
      const Vec3 travel = truth.frame(f).translations[0];
      m.frame(f).translations[0] -= Vec3(travel.x(), 0, travel.z());
    }
  std::vector<const Motion*> panels;
  for (const Motion& m : shown) panels.push_back(&m);
  render::VideoOptions vo;
  vo.fps = 30;
  vo.camera.width = 1280;
  vo.camera.height = 540;
  vo.camera.view = render::View::ThreeQuarter;
  vo.title = "one avatar, two sources: " + name;
  render::render_video_side_by_side(panels, labels, vo, path);
}

}  // namespace

json evaluate_combined(const CombinedEvalRun& run) {
  if (run.files.empty()) throw Error("eval combined: no walking trials given");
  std::optional<accent::Database> db;
  if (!run.database.empty()) db.emplace(accent::load_database(run.database));
  const double rate = db ? db->feature_space().fps : run.rate;
  combined::Settings settings;
  settings.wip.signal.rate = rate;
  std::map<std::string, Sum> sums;
  json trials = json::array(), skipped = json::array();
  double truth_skating = 0;
  long truth_frames = 0;
  int done = 0;
  std::optional<wip::LearnedMapping> given;
  if (!run.wip_table.empty()) given = wip::read_learned_mapping(run.wip_table);
  const auto tables = given ? TablesBySubject{} : held_out_tables(run, rate);
  for (const auto& file : run.files) {
    const std::string name = std::filesystem::path(file).stem().string();
    if (run.progress) run.progress(done++, static_cast<int>(run.files.size()), name);
    try {
      const Motion truth = load_truth(file, rate);
      const auto frames = tracker_frames_from_motion(truth);
      const int n = truth.frame_count();
      json row{{"trial", name}, {"frames", n}};
      std::map<std::string, Motion> outputs;
      // The learned legs: a table built without this trial's subject (none when the others are too few).
      const auto held = tables.find(subject_of(name));
      const wip::LearnedMapping* table = given ? &*given : held != tables.end() && held->second ? &*held->second : nullptr;
      combined::Settings learned = settings;
      learned.wip.mapping.depth = wip::DepthMapping::Learned;
      combined::Settings s = settings;
      s.accent.user_height = learned.accent.user_height = measure_body(truth.skeleton).standing_height;
      // Every method gets the same information: with a database, the IK bodies too run on its skeleton
      // at the user's height (as `eval accent`'s baseline); without one, on the trial's own skeleton.
      std::optional<accent::Model> accent_model;  // built once: its skeleton serves the IK bodies
      if (db) accent_model.emplace(accent::make_model(*db, s.accent));
      const Skeleton& body = accent_model ? accent_model->skeleton() : truth.skeleton;
      outputs.emplace("ik", run_ik_baseline(body, frames, rate));
      outputs.emplace("combined_ik", run_combined(combined::make_model(body, settings), frames, rate));
      if (table)
        outputs.emplace("combined_ik_learned", run_combined(combined::make_model(body, learned, table), frames, rate));
      if (db) {
        outputs.emplace("accent", accent::accentuate(*accent_model, frames, rate).output);
        outputs.emplace("combined_accent", run_combined(combined::make_model(*db, s), frames, rate));
        if (table) outputs.emplace("combined_accent_learned", run_combined(combined::make_model(*db, learned, table), frames, rate));
      }
      if (!run.video.empty() && trials.empty()) write_video(run.video, name, truth, outputs);
      for (const auto& [method, motion] : outputs) {
        row[method] = truth_error(motion, truth);
        sums[method].add(row[method], n);
      }
      const TrialMetrics own = evaluate_trial(role_track(truth), role_track(truth));
      row["truth_foot_skating_cm"] = own.foot_skating_cm;
      truth_skating += own.foot_skating_cm * n;
      truth_frames += n;
      trials.push_back(row);
    } catch (const Error& e) {
      skipped.push_back({{"trial", name}, {"reason", e.what()}});
    }
  }
  if (run.progress) run.progress(done, static_cast<int>(run.files.size()), "");
  if (trials.empty()) throw Error("eval combined: no trial could be evaluated (first: " + skipped[0]["reason"].get<std::string>() + ")");
  json report;
  report["rate_hz"] = rate;
  report["database"] = run.database.empty() ? json(nullptr) : json(run.database);
  report["wip_table"] = run.wip_table.empty() ? json(nullptr) : json(run.wip_table);  // null: learned per trial from the other subjects
  report["ik_skeleton"] = db ? "database skeleton at the user's height" : "each trial's own skeleton";
  report["blend_time_s"] = settings.blend_time;
  report["methods"] = json::object();
  for (const auto& [method, sum] : sums) report["methods"][method] = sum.mean();
  report["truth_foot_skating_cm"] = truth_frames ? truth_skating / static_cast<double>(truth_frames) : 0.0;
  report["trials"] = trials;
  report["skipped"] = skipped;
  return report;
}

std::string combined_table(const json& report) {
  static const std::map<std::string, std::string> label{
      {"ik", "IK avatar alone"},
      {"combined_ik", "combined: IK upper body + walking-in-place legs (document's mapping)"},
      {"combined_ik_learned", "combined: IK upper body + walking-in-place legs (learned mapping, without the trial's subject)"},
      {"accent", "accentuation alone"},
      {"combined_accent", "combined: accentuated upper body + walking-in-place legs (document's mapping)"},
      {"combined_accent_learned",
       "combined: accentuated upper body + walking-in-place legs (learned mapping, without the trial's subject)"}};
  const bool given = report.contains("wip_table") && report["wip_table"].is_string();
  std::string s = "| method | full body cm | lower body cm | hands cm (L / R) | foot skating cm/frame |\n|---|---|---|---|---|\n";
  char buf[256];
  for (const char* m : {"ik", "combined_ik", "combined_ik_learned", "accent", "combined_accent", "combined_accent_learned"}) {
    if (!report["methods"].contains(m)) continue;
    const json& e = report["methods"][m];
    std::string name = label.at(m);
    if (given && name.find("without the trial's subject") != std::string::npos)
      name.replace(name.find("without the trial's subject"), std::string("without the trial's subject").size(), "the given table");
    std::snprintf(buf, sizeof buf, "| %s | %.1f | %.1f | %.1f / %.1f | %.2f |\n", name.c_str(), e["full_body_cm"].get<double>(),
                  e["lower_body_cm"].get<double>(), e["left_hand_cm"].get<double>(), e["right_hand_cm"].get<double>(),
                  e["foot_skating_cm"].get<double>());
    s += buf;
  }
  std::snprintf(buf, sizeof buf, "| the capture itself | 0 | 0 | 0 / 0 | %.2f |\n", report["truth_foot_skating_cm"].get<double>());
  return s + buf;
}

}  // namespace legwork::eval
