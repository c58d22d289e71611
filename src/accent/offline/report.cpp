// Build reports of the accentuation database (see report.hpp).
#include <legwork/accent/offline/report.hpp>
#include <legwork/accent/features.hpp>

#include <cstdio>
#include <map>

namespace legwork::accent {

using nlohmann::json;

json build_report_json(const BuildReport& r, const Database& db, const BuildConfig& cfg, const std::string& database_path) {
  json j;
  j["database"] = database_path;
  j["windows"] = r.windows;
  j["poses"] = r.poses;
  j["bytes"] = r.bytes;
  j["build_seconds"] = r.seconds;
  j["skeleton_from"] = r.skeleton_from;
  j["height_m"] = db.height();
  j["typical_distance"] = db.typical_distance();
  j["settings"] = {{"fps", cfg.fps}, {"hop", cfg.hop}, {"correlation_threshold", cfg.correlation_threshold},
                   {"speeds", speed_factors(cfg)}, {"mirror", cfg.mirror}, {"group_weight", cfg.group_weight}};
  json trials = json::array();
  for (const auto& t : r.trials)
    trials.push_back({{"file", t.file}, {"class", t.cls}, {"kept", t.kept}, {"correlation", t.correlation}, {"windows", t.windows}, {"reason", t.reason}});
  j["trials"] = trials;
  return j;
}

std::string class_table(const BuildReport& r) {
  struct Row {
    int kept = 0, dropped = 0, windows = 0;
    std::map<std::string, int> why;
  };
  std::map<std::string, Row> rows;
  for (const auto& t : r.trials) {
    auto& row = rows[t.cls];
    if (t.kept) {
      ++row.kept;
      row.windows += t.windows;
    } else {
      ++row.dropped;
      std::string why = t.reason;
      if (why.rfind("hand-foot correlation", 0) == 0) why = "hand-foot correlation below threshold";
      ++row.why[why];
    }
  }
  std::string out;
  char buf[1024];
  std::snprintf(buf, sizeof buf, "%-18s %6s %8s %9s  ", "class", "kept", "dropped", "windows");
  out += std::string(buf) + "why dropped\n";
  for (const auto& [cls, row] : rows) {
    std::string why;
    for (const auto& [w, n] : row.why) why += (why.empty() ? "" : "; ") + std::to_string(n) + "x " + w;
    std::snprintf(buf, sizeof buf, "%-18s %6d %8d %9d  ", cls.c_str(), row.kept, row.dropped, row.windows);
    out += std::string(buf) + why + "\n";
  }
  for (const auto& t : r.trials)
    if (t.kept && t.reason.find("roles") != std::string::npos) out += "note: " + t.file + " " + t.reason + "\n";
  return out;
}

nlohmann::json database_info(const Database& db) {
  nlohmann::json classes = nlohmann::json::array();
  for (int c = 0; c < db.class_count(); ++c) {
    const auto [a, b] = db.class_range(c);
    int trials = 0;
    for (const auto& t : db.trials()) trials += t.cls == db.classes()[static_cast<std::size_t>(c)];
    classes.push_back({{"name", db.classes()[static_cast<std::size_t>(c)]}, {"windows", b - a}, {"trials", trials}});
  }
  nlohmann::json trials = nlohmann::json::array();
  for (const auto& t : db.trials())
    trials.push_back({{"file", t.file}, {"class", t.cls}, {"subject", t.subject}, {"trial", t.trial}, {"hand_foot_correlation", t.correlation}});
  const auto& s = db.settings();
  return {{"format", "legwork accent database"},
          {"format_version", kFormatVersion},
          {"bytes", db.bytes().size()},
          {"windows", db.window_count()},
          {"poses", db.pose_count()},
          {"joints", db.joint_count()},
          {"height_m", db.height()},
          {"fps", s.fps},
          {"hop", s.hop},
          {"window_samples", kWindow},
          {"window_stride", kStride},
          {"window_seconds", (kWindow - 1) * kStride / s.fps},
          {"speeds", s.speeds},
          {"mirrored", s.mirrored},
          {"correlation_threshold", s.correlation_threshold},
          {"typical_distance", db.typical_distance()},
          {"search_index", db.has_index()},
          {"classes", classes},
          {"trials", trials}};
}

}  // namespace legwork::accent
