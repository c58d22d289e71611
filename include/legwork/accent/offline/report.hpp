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

// What a database holds (`legwork info FILE.lwdb --json`, Python
// `Database.info()`): format version, bytes, windows, poses, joints, height,
// build settings (fps, hop, window samples and stride, speeds, mirrored,
// correlation threshold), typical distance, whether the search index is
// stored, and per class (name, windows, trials) and per trial (file, class,
// subject, trial, hand-foot correlation).
nlohmann::json database_info(const Database& db);

}  // namespace legwork::accent
