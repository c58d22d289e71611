// Uneven ground: slope and height field (see ground.hpp).
#include <legwork/walkcycle/offline/ground.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace legwork::walkcycle {

using nlohmann::json;

namespace {

constexpr double kMaxGrade = 0.3;  // rise per metre the feet can follow

[[noreturn]] void fail(std::string_view source, const std::string& what) { throw Error(std::string(source) + ": " + what); }

double number(const json& o, const char* field, std::string_view source) {
  if (!o.contains(field)) fail(source, std::string(field) + ": missing");
  const json& v = o[field];
  if (!v.is_number() || !std::isfinite(v.get<double>())) fail(source, std::string(field) + ": expected a finite number");
  return v.get<double>();
}

Vec3 point(const json& o, const char* field, std::string_view source) {
  if (!o.contains(field)) fail(source, std::string(field) + ": missing");
  const json& v = o[field];
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number() || !std::isfinite(v[0].get<double>()) ||
      !std::isfinite(v[1].get<double>()))
    fail(source, std::string(field) + ": expected [x, z] (metres)");
  return {v[0].get<double>(), 0.0, v[1].get<double>()};
}

void only_fields(const json& o, std::initializer_list<const char*> known, std::string_view source) {
  for (auto it = o.begin(); it != o.end(); ++it) {
    bool ok = false;
    for (const char* k : known) ok = ok || it.key() == k;
    if (!ok) fail(source, "unknown field '" + it.key() + "'");
  }
}

// A ground laid out along a direction from an origin (slope, stairs).
Ground directed(const json& o, Ground::Kind kind, std::string_view source) {
  Ground g;
  g.kind = kind;
  g.origin = point(o, "origin", source);
  g.direction = point(o, "direction", source);
  if (g.direction.norm() < 1e-9) fail(source, "direction: must not be [0, 0]");
  g.direction.normalize();
  return g;
}

Ground parse_slope(const json& o, std::string_view source) {
  if (!o.is_object()) fail(source, "expected an object with origin, direction, grade (and length)");
  only_fields(o, {"origin", "direction", "grade", "length"}, source);
  Ground g = directed(o, Ground::Kind::Slope, source);
  g.grade = number(o, "grade", source);
  if (std::abs(g.grade) > kMaxGrade)
    fail(source, "grade " + std::to_string(g.grade) + ": steeper than the walks can follow (at most 0.3, a 30 % grade)");
  if (o.contains("length")) {
    g.length = number(o, "length", source);
    if (!(g.length > 0)) fail(source, "length: expected metres > 0");
  }
  return g;
}

Ground parse_height_field(const json& o, std::string_view source) {
  if (!o.is_object()) fail(source, "expected an object with origin, cell, heights");
  only_fields(o, {"origin", "cell", "heights"}, source);
  Ground g;
  g.kind = Ground::Kind::HeightField;
  g.origin = point(o, "origin", source);
  g.cell = number(o, "cell", source);
  if (!(g.cell >= 0.05)) fail(source, "cell: expected metres >= 0.05");
  if (!o.contains("heights") || !o["heights"].is_array() || o["heights"].size() < 2)
    fail(source, "heights: expected at least 2 rows of heights (metres)");
  const json& rows = o["heights"];
  g.rows = static_cast<int>(rows.size());
  for (int r = 0; r < g.rows; ++r) {
    const json& row = rows[static_cast<std::size_t>(r)];
    const std::string at = "heights: row " + std::to_string(r);
    if (!row.is_array() || row.size() < 2) fail(source, at + ": expected at least 2 heights");
    if (r == 0) g.columns = static_cast<int>(row.size());
    if (static_cast<int>(row.size()) != g.columns)
      fail(source, at + ": " + std::to_string(row.size()) + " heights, row 0 has " + std::to_string(g.columns));
    for (std::size_t c = 0; c < row.size(); ++c) {
      if (!row[c].is_number() || !std::isfinite(row[c].get<double>()))
        fail(source, at + ", column " + std::to_string(c) + ": expected a finite height (metres)");
      g.heights.push_back(row[c].get<double>());
    }
  }
  auto h = [&](int r, int c) { return g.heights[static_cast<std::size_t>(r * g.columns + c)]; };
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.columns; ++c) {
      const double dx = c + 1 < g.columns ? std::abs(h(r, c + 1) - h(r, c)) : 0.0;
      const double dz = r + 1 < g.rows ? std::abs(h(r + 1, c) - h(r, c)) : 0.0;
      if (std::max(dx, dz) > kMaxGrade * g.cell + 1e-12)
        fail(source, "heights: row " + std::to_string(r) + ", column " + std::to_string(c) + ": rises " +
                         std::to_string(std::max(dx, dz)) + " m to its neighbour over a " + std::to_string(g.cell) +
                         " m cell, steeper than the walks can follow (at most 0.3 m per metre; steps are not supported)");
    }
  return g;
}

Ground parse_stairs(const json& o, std::string_view source) {
  if (!o.is_object()) fail(source, "expected an object with origin, direction, rise, run, count");
  only_fields(o, {"origin", "direction", "rise", "run", "count"}, source);
  Ground g = directed(o, Ground::Kind::Stairs, source);
  g.rise = number(o, "rise", source);
  if (!(std::abs(g.rise) > 0 && std::abs(g.rise) <= 0.2))
    fail(source, "rise " + std::to_string(g.rise) + ": expected metres, 0 < |rise| <= 0.2 (higher steps than the legs can take)");
  g.run = number(o, "run", source);
  if (!(g.run >= Ground::kMinRun && g.run <= Ground::kMaxRun)) {
    char run[32];
    std::snprintf(run, sizeof run, "%g", g.run);
    fail(source, std::string("run ") + run + ": expected metres, 0.2 to 5 (a tread a foot fits on; longer is a landing)");
  }
  const double count = number(o, "count", source);
  if (!(count >= 1 && count <= 50 && count == std::floor(count))) fail(source, "count: expected a whole number of steps, 1 to 50");
  g.count = static_cast<int>(count);
  return g;
}

}  // namespace

Ground parse_ground_json(std::string_view text, std::string_view source) {
  json doc;
  try {
    doc = json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {
    fail(source, std::string("not valid JSON: ") + e.what());
  }
  if (!doc.is_object() || doc.size() != 1 || !(doc.contains("slope") || doc.contains("heightfield") || doc.contains("stairs")))
    fail(source, "expected {\"slope\": {...}}, {\"heightfield\": {...}} or {\"stairs\": {...}}");
  if (doc.contains("slope")) return parse_slope(doc["slope"], std::string(source) + ": slope");
  if (doc.contains("stairs")) return parse_stairs(doc["stairs"], std::string(source) + ": stairs");
  return parse_height_field(doc["heightfield"], std::string(source) + ": heightfield");
}

}  // namespace legwork::walkcycle
