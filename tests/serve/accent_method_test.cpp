// legwork serve with an accent database: the accent method end to end.
#include "serve_testing.hpp"

#include "accent/accent_testing.hpp"

#include <legwork/accent/database.hpp>

#include <filesystem>
#include <unistd.h>

namespace legwork::serve {
namespace {

using namespace testing;

// A small database over the repo's sample trials, saved once per test run.
const std::string& sample_db() {
  static const std::string path = [] {
    const auto p = std::filesystem::temp_directory_path() / ("legwork-serve-" + std::to_string(::getpid()) + ".lwdb");
    accent::save_database(p.string(), accent::testing::indexed_database({"walking/07_01", "walking/05_01", "boxing/13_18"}));
    return p.string();
  }();
  static const struct Remove {
    ~Remove() { std::filesystem::remove(path); }
  } remove;
  return path;
}

ServeOptions db_options() {
  ServeOptions o = test_options();
  o.db_path = sample_db();
  o.skeleton_path.clear();
  return o;
}

TEST(ServeAccent, HelloChoosesClassesAndUnknownOnesAreNamed) {
  RunningServer srv(db_options());
  Client c(srv.port());
  const json w = c.hello({{"method", "accent"}, {"classes", {"walking"}}});
  EXPECT_EQ(w["method"], "accent");
  Client bad(srv.port());
  bad.send_text(R"({"type":"hello","version":1,"method":"accent","classes":["ballet"]})");
  const json e = bad.expect("error");
  EXPECT_EQ(e["code"], "bad_value");
  EXPECT_NE(e["message"].get<std::string>().find("ballet"), std::string::npos) << e.dump();
}

TEST(ServeAccent, StreamsATrialAndTheHandsFollow) {
  RunningServer srv(db_options());
  Client c(srv.port());
  const json w = c.hello({{"method", "accent"}, {"classes", {"walking"}}});
  const auto& names = w["skeleton"]["names"];
  const auto lh = static_cast<std::size_t>(std::find(names.begin(), names.end(), "LeftHand") - names.begin());
  io::BvhReadOptions ro;
  ro.drop_first_frame = true;
  const Motion m = io::load_bvh(source_dir() + "/data/cmu/bvh/walking/07_02.bvh", ro);
  const auto frames = tracker_frames_from_motion(m, 90.0);
  std::vector<double> err;
  int matched = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    c.send_text(json_frame(frames[i]));
    const json p = c.expect("pose");
    ASSERT_EQ(p["seq"], i + 1);
    EXPECT_NE(p["status"], "rejected");
    matched += p["info"]["match"] == "matched";
    // The hello allowed walking only: one class on a frame that searched, none
    // on one that continued its matches (search_interval).
    EXPECT_EQ(p["info"]["classes_searched"], p["info"]["searched"] == 1 ? 1 : 0) << "the hello allowed walking only";
    const auto& q = p["positions"][lh];
    err.push_back((Vec3(q[0], q[1], q[2]) - frames[i].hand(kLeft).position).norm());
  }
  std::sort(err.begin(), err.end());
  // Accentuation pins the wrists onto the controllers by two-bone IK (hand_ik = 1).
  EXPECT_LT(err[err.size() / 2], 0.01) << "median left wrist error";
  EXPECT_GT(matched, static_cast<int>(frames.size()) / 2) << "walking input should mostly match walking windows";
  // Options: a class switch is applied in-stream; an unknown class is an error naming it.
  c.send_text(R"({"type":"options","classes":["boxing"],"exaggeration":1.5})");
  TrackerFrame f = frames.back();
  f.time += 0.011;
  c.send_text(json_frame(f));
  EXPECT_EQ(c.expect("pose")["status"], "ok");
  c.send_text(R"({"type":"options","classes":["ballet"]})");
  const json e = c.expect("error");
  EXPECT_NE(e["message"].get<std::string>().find("options not applied"), std::string::npos) << e.dump();
  EXPECT_NE(e["message"].get<std::string>().find("ballet"), std::string::npos) << e.dump();
}

}  // namespace
}  // namespace legwork::serve
