#pragma once
// Offline: what `legwork accent build` reports about a database build: the
// JSON report (settings, per-trial verdicts) and the per-class table.
#include <legwork/accent/database.hpp>
#include <legwork/accent/offline/builder.hpp>

#include <nlohmann/json.hpp>

#include <string>

namespace legwork::accent {

// database path, windows, poses, bytes, build seconds, skeleton, height,
// typical distance, settings and one entry per trial (file, class, kept, correlation, windows, reason).
nlohmann::json build_report_json(const BuildReport& r, const Database& db, const BuildConfig& cfg,
                                 const std::string& database_path);

// Per class: trials kept and dropped, windows, and why trials were dropped
// (plus a note per kept trial whose roles were guessed). Lines end in '\n'.
std::string class_table(const BuildReport& r);

}  // namespace legwork::accent
