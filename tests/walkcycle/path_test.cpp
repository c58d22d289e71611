// Floor paths (offline/path.cpp): formats and bad paths.
#include <legwork/core/fk.hpp>
#include <legwork/core/mirror.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/walkcycle/offline/keys.hpp>
#include <legwork/walkcycle/offline/measure.hpp>

#include "testdata.hpp"
#include "walk_samples.hpp"

#include <cstdio>

using namespace legwork;
using namespace legwork::walkcycle;
using namespace legwork::walkcycle::samples;

TEST(Paths, FormatsAndBadPaths) {
  const Path poly = parse_path_json(R"({"polyline": [[0,0],[0,1],[1,1]]})", "p");
  EXPECT_NEAR(poly.length(), 2.0, 1e-12);
  EXPECT_NEAR(poly.total_turning(), kPi / 2, 1e-12);
  const Path svg = parse_svg_path("M 0 0 L 0 2 C 0 3 1 4 2 4", "svg");
  EXPECT_NEAR(svg.points.back().x(), 2.0, 1e-12);
  EXPECT_NEAR(svg.points.back().z(), 4.0, 1e-12);
  const Path rel = parse_svg_path("m 0 0 l 0 2 h 1 v 1", "svg");
  EXPECT_NEAR(rel.length(), 4.0, 1e-12);
  const Path cr = parse_path_json(R"({"catmull_rom": [[0,0],[0,2],[2,3]]})", "c");
  EXPECT_NEAR(cr.points.back().x(), 2.0, 1e-12);
  EXPECT_NEAR(quarter_turn().total_turning(), kPi / 2, 0.02);

  auto msg = expect_error([] { parse_path_json(R"({"polyline": []})", "empty.json"); });
  EXPECT_NE(msg.find("empty"), std::string::npos) << msg;
  msg = expect_error([] { parse_path_json(R"({"polyline": [[0,0],[1,1],[1,1],[2,2]]})", "rep.json"); });
  EXPECT_NE(msg.find("point 2 repeats point 1"), std::string::npos) << msg;
  msg = expect_error([] { parse_svg_path("", "svg"); });
  EXPECT_NE(msg.find("empty"), std::string::npos) << msg;
  msg = expect_error([] { parse_svg_path("M 0 0 A 1 1 0 0 1 2 2", "svg"); });
  EXPECT_NE(msg.find("unsupported command 'A'"), std::string::npos) << msg;
  msg = expect_error([] { parse_path_json(R"({"bezier": [[0,0],[0,1],[0,2]]})", "b.json"); });
  EXPECT_NE(msg.find("3n+1"), std::string::npos) << msg;
  // Finite but absurd: the length overflowed to Inf (1e308 - -1e308) before the bound.
  msg = expect_error([] { parse_path_json(R"({"polyline": [[0,0],[1e308,0],[-1e308,0]]})", "far.json"); });
  EXPECT_EQ(msg, "far.json: path point (1e+308, 0) is beyond 1e6 m from the origin (coordinates are metres)");
  EXPECT_NEAR(parse_path_json(R"({"polyline": [[0,0],[1e6,0]]})", "p").length(), 1e6, 1e-6);
}
