// The HTTP side of legwork serve without a socket (src/serve/http_api.cpp):
// static files that never leave the web folder, the JSON API's info, trial
// list and trial replay (equal to the trial's own tracker frames), and JSON
// errors with the right status.
#include "../../src/serve/http_api.hpp"

#include <legwork/core/measure.hpp>
#include <legwork/core/tracker.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/serve/protocol.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "cmu_sample.hpp"
#include "testdata.hpp"

namespace legwork::serve {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// A web folder with an index and a script, and a secret file next to it.
struct Site {
  fs::path root = fs::temp_directory_path() / ("legwork-http-api-" + std::to_string(::getpid()));
  ApiContext ctx;
  Site() {
    fs::remove_all(root);
    fs::create_directories(root / "web" / "js");
    std::ofstream(root / "web" / "index.html") << "<html>legwork</html>";
    std::ofstream(root / "web" / "js" / "app.js") << "console.log(1)";
    std::ofstream(root / "web" / ".hidden") << "no";
    std::ofstream(root / "secret.txt") << "secret";
    ctx.web_dir = (root / "web").string();
    ctx.trials_dir = testdata::sample("cmu/bvh").string();
    ctx.resources.skeleton = &testdata::sample_skeleton();
    ctx.resources.database_name = "none";
    ctx.classes = {"walking"};
  }
  ~Site() { fs::remove_all(root); }
  HttpReply get(std::string_view target) const { return handle_http(ctx, "GET", target); }
};

// The error reply's code and message (and that it is JSON with status `status`).
std::pair<std::string, std::string> error_of(const HttpReply& r, unsigned status) {
  EXPECT_EQ(r.status, status) << r.body;
  EXPECT_EQ(r.content_type, "application/json");
  const json j = json::parse(r.body);
  EXPECT_EQ(j["type"], "error");
  return {j["code"], j["message"]};
}

TEST(HttpApi, StaticFilesWithTheirTypes) {
  const Site s;
  HttpReply r = s.get("/");
  EXPECT_EQ(r.status, 200u);
  EXPECT_EQ(r.body, "<html>legwork</html>");
  EXPECT_EQ(r.content_type, "text/html; charset=utf-8");
  r = s.get("/js/app.js?v=3");
  EXPECT_EQ(r.body, "console.log(1)");
  EXPECT_EQ(r.content_type, "text/javascript; charset=utf-8");
  EXPECT_EQ(handle_http(s.ctx, "HEAD", "/js/app.js").status, 200u);
  EXPECT_EQ(error_of(s.get("/missing.css"), 404), std::make_pair(std::string("not_found"), std::string("no such file: /missing.css")));
  ApiContext no_web = s.ctx;
  no_web.web_dir.clear();
  EXPECT_EQ(error_of(handle_http(no_web, "GET", "/"), 404).second,
            "no viewer: start the server with --web DIR (the built web/dist)");
}

TEST(HttpApi, NothingOutsideTheWebFolderIsServed) {
  const Site s;
  for (const char* t : {"/../secret.txt", "/%2e%2e/secret.txt", "/js/../../secret.txt", "/js/%2E%2E/%2E%2E/secret.txt",
                        "/.hidden", "//etc/passwd", "/js\\..\\..\\secret.txt"}) {
    const HttpReply r = s.get(t);
    EXPECT_EQ(r.status, 404u) << t;
    EXPECT_EQ(r.body.find("secret"), std::string::npos) << t;
  }
  // A symbolic link inside the folder that points out of it is refused too.
  fs::create_symlink(s.root / "secret.txt", s.root / "web" / "link.txt");
  EXPECT_EQ(s.get("/link.txt").status, 404u);
  EXPECT_EQ(error_of(s.get("/%zz"), 400), std::make_pair(std::string("bad_message"), std::string("malformed request path")));
  EXPECT_EQ(error_of(s.get("/a%00b"), 400).first, "bad_message");
  EXPECT_EQ(error_of(handle_http(s.ctx, "POST", "/"), 405),
            std::make_pair(std::string("bad_message"), std::string("only GET and HEAD are served")));
}

TEST(HttpApi, InfoAndTrialList) {
  const Site s;
  const json info = json::parse(s.get("/api/info").body);
  EXPECT_EQ(info["version"], kProtocolVersion);
  EXPECT_EQ(info["methods"], json(available_methods(s.ctx.resources)));
  EXPECT_EQ(info["classes"], json({"walking"}));
  EXPECT_EQ(info["database"], "none");
  // Every .bvh under the trials folder, as class/name, sorted.
  std::vector<std::string> want;
  for (const auto& e : fs::recursive_directory_iterator(s.ctx.trials_dir))
    if (e.path().extension() == ".bvh")
      want.push_back(fs::relative(e.path(), s.ctx.trials_dir).replace_extension().generic_string());
  std::sort(want.begin(), want.end());
  ASSERT_FALSE(want.empty());
  EXPECT_EQ(list_trials(s.ctx.trials_dir), want);
  EXPECT_EQ(json::parse(s.get("/api/trials").body)["trials"], json(want));
  EXPECT_TRUE(list_trials("").empty());
  EXPECT_TRUE(list_trials((s.root / "nope").string()).empty());
  EXPECT_EQ(error_of(s.get("/api/nope"), 404).second, "no API endpoint /api/nope (have /api/info, /api/trials, /api/trial)");
}

TEST(HttpApi, TrialReplayIsTheTrialsTrackerFramesAndPositions) {
  const Site s;
  const HttpReply r = s.get("/api/trial?name=walking%2F07_02&rate=60");
  ASSERT_EQ(r.status, 200u) << r.body;
  const json t = json::parse(r.body);
  const Motion m = testdata::load_sample("cmu/bvh/walking/07_02.bvh");
  const auto frames = tracker_frames_from_motion(m, 60.0);
  EXPECT_EQ(t["name"], "walking/07_02");
  EXPECT_EQ(t["fps"], 60.0);
  ASSERT_EQ(t["frames"].size(), frames.size());
  for (std::size_t i = 0; i < frames.size(); i += 17) {
    const json& f = t["frames"][i];
    EXPECT_EQ(f["t"].get<double>(), frames[i].time);
    const json& p = f["left"]["p"];
    EXPECT_EQ(Vec3(p[0].get<double>(), p[1].get<double>(), p[2].get<double>()), frames[i].hand(kLeft).position);
    const json& q = f["head"]["q"];
    EXPECT_EQ(q[0].get<double>(), frames[i].head().rotation.w());
  }
  EXPECT_EQ(t["truth"]["names"], json(m.skeleton.names));
  ASSERT_EQ(t["truth"]["positions"].size(), frames.size());
  EXPECT_EQ(t["truth"]["positions"][0].size(), 3u * static_cast<std::size_t>(m.joint_count()));
  // The truth's root at t = 0 is the first frame's root (rounded to 10 micrometres).
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(t["truth"]["positions"][0][k].get<double>(), m.frame(0).translations[0][k], 6e-6);
  EXPECT_NEAR(t["height"].get<double>(), measure_body(m.skeleton).standing_height, 5e-4);  // to the millimetre
}

TEST(HttpApi, TrialRequestErrors) {
  const Site s;
  const std::string need = "/api/trial needs name=<trial> from /api/trials (e.g. walking/07_02)";
  EXPECT_EQ(error_of(s.get("/api/trial"), 400), std::make_pair(std::string("bad_value"), need));
  EXPECT_EQ(error_of(s.get("/api/trial?name=../../etc/passwd"), 400).second, need);
  EXPECT_EQ(error_of(s.get("/api/trial?name=walking/99_99"), 404),
            std::make_pair(std::string("not_found"), std::string("no trial 'walking/99_99' (see /api/trials)")));
  for (const char* rate : {"1000", "0.5", "fast", "", "90x"})
    EXPECT_EQ(error_of(s.get(std::string("/api/trial?name=walking/07_02&rate=") + rate), 400).second,
              std::string("rate must be a number of Hz in [1, 240] (got '") + rate + "')");
}

}  // namespace
}  // namespace legwork::serve
