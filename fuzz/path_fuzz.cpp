// libFuzzer target for floor paths (JSON polyline, bezier, catmull_rom or an
// SVG path string) and what consumes them: arc-length queries, projection and
// a short walk along the path with the repo's normal walk (data/walks).
// Any input ends in a path of finite points with increasing arc length, whose
// walk stays finite, or in a legwork::Error.
#include "fuzz_body.hpp"

#include <legwork/core/fk.hpp>
#include <legwork/walkcycle/cycle.hpp>
#include <legwork/walkcycle/offline/keys.hpp>
#include <legwork/walkcycle/offline/path.hpp>
#include <legwork/walkcycle/offline/walk.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

namespace {

using namespace legwork;

const walkcycle::CycleModel& normal_walk() {
  static const walkcycle::CycleModel m = [] {
    const Skeleton& skel = fuzz::sample_skeleton();
    return walkcycle::build_cycle(skel, walkcycle::read_walk_keys(std::string(LEGWORK_SOURCE_DIR) + "/data/walks/normal.json", skel));
  }();
  return m;
}

void check_path(const walkcycle::Path& p) {
  if (p.points.size() < 2 || p.cumulative.size() != p.points.size()) std::abort();
  for (std::size_t i = 0; i < p.points.size(); ++i) {
    if (!p.points[i].allFinite() || p.points[i].y() != 0) std::abort();
    if (i > 0 && !(p.cumulative[i] >= p.cumulative[i - 1])) std::abort();
  }
  if (!std::isfinite(p.length()) || !std::isfinite(p.total_turning())) std::abort();
  for (double s : {0.0, 0.5 * p.length(), p.length()}) {
    if (!p.at(s).allFinite() || !p.tangent(s).allFinite()) std::abort();
    int seg = -1;
    double dist = -1;
    const double back = p.project(p.at(s), 0, p.length(), &seg, &dist);
    if (!std::isfinite(back) || seg < 0 || !(dist >= 0)) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const walkcycle::Path p = walkcycle::parse_path_json(text, "fuzz.json");
    check_path(p);
    walkcycle::WalkOptions o;
    o.steps = 4;  // a bounded walk whatever the path's length
    const Motion m = walkcycle::walk_path(normal_walk(), p, o).motion;
    for (int f = 0; f < m.frame_count(); ++f)
      for (const Vec3& q : joint_positions(m.skeleton, m.frame(f)))
        if (!q.allFinite()) std::abort();
  } catch (const Error&) {
  }
  return 0;
}
