#include <legwork/walkcycle/offline/path.hpp>

#include <legwork/io/text.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace legwork::walkcycle {

using nlohmann::json;

namespace {

Vec3 floor_point(double x, double z) { return Vec3(x, 0.0, z); }

Vec3 bezier(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, double u) {
  const double v = 1 - u;
  return v * v * v * p0 + 3 * v * v * u * p1 + 3 * v * u * u * p2 + u * u * u * p3;
}

// Samples k / samples, plus 0.1 % in from either end, so the polyline's first
// and last chords follow the curve's end tangents (where a walk starts facing
// and ends facing) to a fraction of a degree, not half a sample's turn.
void append_cubic(std::vector<Vec3>& out, const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, int samples) {
  const bool ends = samples >= 4;
  if (ends) out.push_back(bezier(p0, p1, p2, p3, 0.001));
  for (int k = 1; k <= samples; ++k) {
    if (ends && k == samples) out.push_back(bezier(p0, p1, p2, p3, 0.999));
    out.push_back(bezier(p0, p1, p2, p3, static_cast<double>(k) / samples));
  }
}

// Uniform Catmull-Rom through every point, as cubic Beziers.
std::vector<Vec3> catmull_rom(const std::vector<Vec3>& p, int samples) {
  std::vector<Vec3> out{p.front()};
  const std::size_t n = p.size();
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const Vec3 prev = i == 0 ? 2 * p[0] - p[1] : p[i - 1];
    const Vec3 next = i + 2 >= n ? 2 * p[n - 1] - p[n - 2] : p[i + 2];
    append_cubic(out, p[i], p[i] + (p[i + 1] - prev) / 6.0, p[i + 1] - (next - p[i]) / 6.0, p[i + 1], samples);
  }
  return out;
}

std::vector<Vec3> read_points(const json& a, std::string_view source, const std::string& field) {
  if (!a.is_array()) throw Error(std::string(source) + ": " + field + ": expected an array of [x, z] points");
  std::vector<Vec3> pts;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string f = field + "[" + std::to_string(i) + "]";
    const auto& p = a[i];
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
      throw Error(std::string(source) + ": " + f + ": expected [x, z] (metres)");
    const double x = p[0].get<double>(), z = p[1].get<double>();
    if (!std::isfinite(x) || !std::isfinite(z)) throw Error(std::string(source) + ": " + f + ": not finite");
    pts.push_back(floor_point(x, z));
  }
  return pts;
}

void check_no_repeats(const std::vector<Vec3>& pts, std::string_view what, const std::string& field) {
  for (std::size_t i = 1; i < pts.size(); ++i)
    if ((pts[i] - pts[i - 1]).norm() < 1e-9)
      throw Error(std::string(what) + ": " + field + ": point " + std::to_string(i) +
                  " repeats point " + std::to_string(i - 1) + " (a path needs distinct consecutive points)");
}

}  // namespace

Path make_path(const std::vector<Vec3>& points, std::string_view what) {
  if (points.size() < 2)
    throw Error(std::string(what) + ": a path needs at least 2 points (got " + std::to_string(points.size()) + ")");
  Path p;
  for (const auto& q : points) {
    if (!q.allFinite()) throw Error(std::string(what) + ": path point is not finite");
    // Beyond this, lengths can overflow to Inf (1e308 - -1e308); paths are metres on a floor.
    if (std::abs(q.x()) > kMaxPathCoordinate || std::abs(q.z()) > kMaxPathCoordinate) {
      char xz[64];
      std::snprintf(xz, sizeof xz, "(%g, %g)", q.x(), q.z());
      throw Error(std::string(what) + ": path point " + xz + " is beyond 1e6 m from the origin (coordinates are metres)");
    }
    p.points.push_back(Vec3(q.x(), 0.0, q.z()));
  }
  check_no_repeats(p.points, what, "points");
  p.cumulative.push_back(0.0);
  for (std::size_t i = 1; i < p.points.size(); ++i)
    p.cumulative.push_back(p.cumulative.back() + (p.points[i] - p.points[i - 1]).norm());
  return p;
}

Path straight_path(double metres) {
  if (!(metres > 0) || !std::isfinite(metres)) throw Error("--straight: distance must be positive metres");
  return make_path({Vec3::Zero(), Vec3(0, 0, metres)}, "straight path");
}

Vec3 Path::at(double s) const {
  s = std::clamp(s, 0.0, length());
  auto it = std::upper_bound(cumulative.begin(), cumulative.end(), s);
  std::size_t i = it == cumulative.begin() ? 0 : static_cast<std::size_t>(it - cumulative.begin()) - 1;
  if (i + 1 >= points.size()) return points.back();
  const double u = (s - cumulative[i]) / (cumulative[i + 1] - cumulative[i]);
  return points[i] + u * (points[i + 1] - points[i]);
}

Vec3 Path::tangent(double s) const {
  s = std::clamp(s, 0.0, length());
  auto it = std::upper_bound(cumulative.begin(), cumulative.end(), s);
  std::size_t i = it == cumulative.begin() ? 0 : static_cast<std::size_t>(it - cumulative.begin()) - 1;
  i = std::min(i, points.size() - 2);
  return (points[i + 1] - points[i]).normalized();
}

double Path::project(const Vec3& p, int first_segment, double s_limit, int* segment, double* distance) const {
  const Vec3 q(p.x(), 0.0, p.z());
  double best = 1e300, best_s = 0;
  int best_i = first_segment;
  for (int i = std::max(0, first_segment); i + 1 < static_cast<int>(points.size()); ++i) {
    const auto iu = static_cast<std::size_t>(i);
    if (i > first_segment && cumulative[iu] > s_limit) break;
    const Vec3 d = points[iu + 1] - points[iu];
    const double len2 = d.squaredNorm();
    const double u = std::clamp((q - points[iu]).dot(d) / len2, 0.0, 1.0);
    const double dist = (points[iu] + u * d - q).norm();
    if (dist < best) {
      best = dist;
      best_s = cumulative[iu] + u * std::sqrt(len2);
      best_i = i;
    }
  }
  if (segment) *segment = best_i;
  if (distance) *distance = best;
  return best_s;
}

double Path::total_turning() const {
  double sum = 0;
  for (std::size_t i = 2; i < points.size(); ++i) {
    const Vec3 a = points[i - 1] - points[i - 2], b = points[i] - points[i - 1];
    sum += std::abs(std::atan2(a.z() * b.x() - a.x() * b.z(), a.dot(b)));
  }
  return sum;
}

Path parse_svg_path(std::string_view d, std::string_view source, int samples) {
  const std::string what = std::string(source) + ": svg path";
  std::vector<Vec3> pts;
  std::size_t pos = 0;
  auto skip = [&] {
    while (pos < d.size() && (std::isspace(static_cast<unsigned char>(d[pos])) || d[pos] == ',')) ++pos;
  };
  auto number = [&]() -> double {
    skip();
    const std::string rest(d.substr(pos, std::min<std::size_t>(64, d.size() - pos)));
    char* end = nullptr;
    const double v = std::strtod(rest.c_str(), &end);
    if (end == rest.c_str()) throw Error(what + ": expected a number at character " + std::to_string(pos));
    if (!std::isfinite(v)) throw Error(what + ": number at character " + std::to_string(pos) + " is not finite");
    pos += static_cast<std::size_t>(end - rest.c_str());
    return v;
  };
  auto has_number = [&] {
    skip();
    return pos < d.size() && (std::isdigit(static_cast<unsigned char>(d[pos])) || d[pos] == '-' || d[pos] == '+' || d[pos] == '.');
  };
  Vec3 cur = Vec3::Zero(), start = Vec3::Zero(), last_ctrl = Vec3::Zero();
  char prev_cmd = 0;
  bool started = false;
  while (true) {
    skip();
    if (pos >= d.size()) break;
    const char c = d[pos];
    if (!std::isalpha(static_cast<unsigned char>(c)))
      throw Error(what + ": expected a command letter at character " + std::to_string(pos) + ", found '" + c + "'");
    ++pos;
    const bool rel = std::islower(static_cast<unsigned char>(c));
    char cmd = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (cmd != 'M' && !started) throw Error(what + ": must start with M (moveto)");
    auto pt = [&]() {
      const double x = number();
      const double z = number();
      return rel ? Vec3(cur.x() + x, 0, cur.z() + z) : floor_point(x, z);
    };
    do {
      switch (cmd) {
        case 'M':
          if (started) throw Error(what + ": only one subpath (one M) is supported");
          cur = start = pt();
          pts.push_back(cur);
          started = true;
          cmd = 'L';  // further coordinate pairs are line-tos
          break;
        case 'L': cur = pt(); pts.push_back(cur); break;
        case 'H': { const double x = number(); cur = Vec3(rel ? cur.x() + x : x, 0, cur.z()); pts.push_back(cur); break; }
        case 'V': { const double z = number(); cur = Vec3(cur.x(), 0, rel ? cur.z() + z : z); pts.push_back(cur); break; }
        case 'C': {
          const Vec3 p1 = pt(), p2 = pt(), p3 = pt();
          append_cubic(pts, cur, p1, p2, p3, samples);
          last_ctrl = p2;
          cur = p3;
          break;
        }
        case 'S': {
          const Vec3 p1 = (prev_cmd == 'C' || prev_cmd == 'S') ? Vec3(2 * cur - last_ctrl) : cur;
          const Vec3 p2 = pt(), p3 = pt();
          append_cubic(pts, cur, p1, p2, p3, samples);
          last_ctrl = p2;
          cur = p3;
          break;
        }
        case 'Q': {
          const Vec3 q1 = pt(), p3 = pt();
          append_cubic(pts, cur, cur + 2.0 / 3.0 * (q1 - cur), p3 + 2.0 / 3.0 * (q1 - p3), p3, samples);
          cur = p3;
          break;
        }
        case 'Z': cur = start; pts.push_back(cur); break;
        default:
          throw Error(what + ": unsupported command '" + std::string(1, c) + "' (use M, L, H, V, C, S, Q, Z)");
      }
      prev_cmd = cmd;
    } while (cmd != 'Z' && has_number());
  }
  if (pts.size() < 2) throw Error(what + ": the path is empty (needs at least two points)");
  check_no_repeats(pts, what, "flattened points");
  return make_path(pts, what);
}

namespace {

Path parse_path_doc(const json& doc, std::string_view source) {
  int samples = 16;
  if (doc.contains("samples_per_segment")) {
    const auto& s = doc["samples_per_segment"];
    if (!s.is_number_integer() || s.get<int>() < 1 || s.get<int>() > 1000)
      throw Error(std::string(source) + ": samples_per_segment: expected a whole number from 1 to 1000");
    samples = s.get<int>();
  }
  int kinds = 0;
  for (auto it = doc.begin(); it != doc.end(); ++it) {
    const auto& k = it.key();
    if (k == "polyline" || k == "bezier" || k == "catmull_rom" || k == "svg") ++kinds;
    else if (k != "samples_per_segment" && k != "comment" && k != "name" && k != "ground")
      throw Error(std::string(source) + ": unknown field '" + k + "' (expected polyline, bezier, catmull_rom or svg)");
  }
  if (kinds != 1)
    throw Error(std::string(source) + ": give exactly one of polyline, bezier, catmull_rom, svg (found " + std::to_string(kinds) + ")");
  if (doc.contains("svg")) {
    if (!doc["svg"].is_string()) throw Error(std::string(source) + ": svg: expected a path string");
    return parse_svg_path(doc["svg"].get<std::string>(), source, samples);
  }
  if (doc.contains("polyline")) {
    auto pts = read_points(doc["polyline"], source, "polyline");
    if (pts.size() < 2) throw Error(std::string(source) + ": polyline: the path is empty (needs at least 2 points)");
    check_no_repeats(pts, source, "polyline");
    return make_path(pts, source);
  }
  if (doc.contains("catmull_rom")) {
    auto pts = read_points(doc["catmull_rom"], source, "catmull_rom");
    if (pts.size() < 2) throw Error(std::string(source) + ": catmull_rom: the path is empty (needs at least 2 points)");
    check_no_repeats(pts, source, "catmull_rom");
    return make_path(catmull_rom(pts, samples), source);
  }
  auto ctrl = read_points(doc["bezier"], source, "bezier");
  if (ctrl.size() < 4 || (ctrl.size() - 1) % 3 != 0)
    throw Error(std::string(source) + ": bezier: expected 3n+1 points (start, control, control, end, ...), got " +
                std::to_string(ctrl.size()));
  std::vector<Vec3> pts{ctrl[0]};
  for (std::size_t i = 0; i + 3 < ctrl.size(); i += 3) append_cubic(pts, ctrl[i], ctrl[i + 1], ctrl[i + 2], ctrl[i + 3], samples);
  check_no_repeats(pts, source, "bezier (flattened)");
  return make_path(pts, source);
}

}  // namespace

Path parse_path_json(std::string_view text, std::string_view source) {
  json doc;
  try {
    doc = json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {
    throw Error(std::string(source) + ": not valid JSON: " + e.what());
  }
  if (!doc.is_object()) throw Error(std::string(source) + ": expected an object with polyline, bezier, catmull_rom or svg");
  Path path = parse_path_doc(doc, source);
  if (doc.contains("ground")) path.ground = parse_ground_json(doc["ground"].dump(), std::string(source) + ": ground");
  return path;
}

Path read_path(const std::string& file) { return parse_path_json(io::read_text_file(file), file); }

}  // namespace legwork::walkcycle
