// legwork serve end to end: a server on a free loopback port, Beast clients.
#include "serve_testing.hpp"

#include <legwork/serve/rate_limit.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/tracker.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/tracker_csv.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace legwork::serve {
namespace {

using namespace testing;

// Head + hands (+ ankles) of a real CMU trial at 90 Hz, T-pose dropped.
std::vector<TrackerFrame> trial_frames(const std::string& rel = "walking/07_02.bvh", bool feet = false, double hz = 90) {
  io::BvhReadOptions o;
  o.drop_first_frame = true;
  const Motion m = io::load_bvh(source_dir() + "/data/cmu/bvh/" + rel, o);
  auto frames = tracker_frames_from_motion(m, hz);
  if (!feet)
    for (auto& f : frames) f.foot(kLeft).valid = f.foot(kRight).valid = false;
  return frames;
}

Vec3 vec(const json& a) { return {a[0].get<double>(), a[1].get<double>(), a[2].get<double>()}; }

// Sends `text` and expects an error with `code` whose message contains `part`.
void expect_error(Client& c, const std::string& text, const std::string& code, const std::string& part) {
  c.send_text(text);
  const json e = c.expect("error");
  EXPECT_EQ(e["code"], code) << e.dump();
  EXPECT_NE(e["message"].get<std::string>().find(part), std::string::npos) << e.dump();
}

TEST(Serve, HandshakeSendsWelcomeWithTheSkeleton) {
  RunningServer srv;
  Client c(srv.port());
  const json w = c.hello();
  EXPECT_EQ(w["version"], 1);
  EXPECT_EQ(w["method"], "ik");
  EXPECT_EQ(w["session"].get<std::string>().substr(0, 1), "s");
  const auto& names = w["skeleton"]["names"];
  ASSERT_EQ(names.size(), w["skeleton"]["parents"].size());
  ASSERT_EQ(names.size(), w["skeleton"]["offsets"].size());
  EXPECT_EQ(names[0], "Hips");
  EXPECT_NE(std::find(names.begin(), names.end(), "LeftHand"), names.end());
  EXPECT_EQ(w["joints"].size(), names.size());
  EXPECT_EQ(w["max_rate_hz"], 1e6);
}

// Streams a trial lock-step; returns the largest wrist error (metres) and pose count.
std::pair<double, int> stream_trial(Client& c, const json& welcome, bool binary) {
  const auto& names = welcome["skeleton"]["names"];
  const auto index = [&](const char* n) { return static_cast<std::size_t>(std::find(names.begin(), names.end(), n) - names.begin()); };
  const std::size_t hand[2] = {index("LeftHand"), index("RightHand")};
  double worst = 0;
  int poses = 0;
  const auto frames = trial_frames();
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const TrackerFrame& f = frames[i];
    if (binary) c.send_binary(binary_frame(f));
    else c.send_text(json_frame(f));
    auto m = c.read();
    if (!m) {
      ADD_FAILURE() << "no answer to frame " << i;
      break;
    }
    std::vector<Vec3> pos;
    std::string status;
    std::uint64_t seq = 0;
    if (binary) {
      EXPECT_TRUE(m->binary);
      const BinaryPose p = parse_binary_pose(std::as_bytes(std::span(m->data.data(), m->data.size())));
      pos = p.positions;
      status = p.status == 0 ? "ok" : "other";
      seq = p.seq;
    } else {
      const json j = m->j();
      EXPECT_EQ(j["type"], "pose") << j.dump();
      for (const auto& p : j["positions"]) pos.push_back(vec(p));
      status = j["status"];
      seq = j["seq"];
      EXPECT_NEAR(j["t"].get<double>(), f.time, 1e-6);
    }
    EXPECT_EQ(seq, i + 1);
    EXPECT_EQ(status, "ok");
    for (int s = 0; s < 2; ++s) worst = std::max(worst, (pos[hand[s]] - f.hand(s).position).norm());
    ++poses;
  }
  return {worst, poses};
}

TEST(Serve, IkPosesFollowTheHandsOfARealTrialJson) {
  RunningServer srv;
  Client c(srv.port());
  const auto [worst, poses] = stream_trial(c, c.hello(), false);
  EXPECT_EQ(poses, static_cast<int>(trial_frames().size()));
  EXPECT_LT(worst, 0.01) << "wrists must be within 1 cm of the input hands";
}

TEST(Serve, IkPosesFollowTheHandsOfARealTrialBinary) {
  RunningServer srv;
  Client c(srv.port());
  const auto [worst, poses] = stream_trial(c, c.hello({{"format", "binary"}}), true);
  EXPECT_EQ(poses, static_cast<int>(trial_frames().size()));
  EXPECT_LT(worst, 0.01);
}

TEST(Serve, OutputJointSubset) {
  RunningServer srv;
  Client c(srv.port());
  const json w = c.hello({{"joints", {"Head", "LeftHand"}}});
  EXPECT_EQ(w["joints"], json({"Head", "LeftHand"}));
  const auto f = trial_frames()[0];
  c.send_text(json_frame(f));
  const json p = c.expect("pose");
  ASSERT_EQ(p["positions"].size(), 2u);
  EXPECT_LT((vec(p["positions"][1]) - f.hand(kLeft).position).norm(), 0.01);
  Client bad(srv.port());
  bad.send_text(R"({"type":"hello","version":1,"method":"ik","joints":["Tail"]})");
  const json e = bad.expect("error");
  EXPECT_EQ(e["code"], "bad_value");
  EXPECT_NE(e["message"].get<std::string>().find("no joint 'Tail'"), std::string::npos) << e.dump();
}

// One valid frame after a failure must still be answered with a pose.
void expect_alive(Client& c, double t) {
  TrackerFrame f = trial_frames()[0];
  f.time = t;
  c.send_text(json_frame(f));
  const json p = c.expect("pose");
  EXPECT_NEAR(p["t"].get<double>(), t, 1e-9);
}

TEST(Serve, MalformedJsonGetsAnErrorAndTheSessionSurvives) {
  RunningServer srv;
  Client c(srv.port());
  c.hello();
  c.send_text("{\"type\":\"frame\",\"t\":0.1,");
  json e = c.expect("error");
  EXPECT_EQ(e["code"], "bad_json");
  EXPECT_NE(e["message"].get<std::string>().find("not valid JSON"), std::string::npos) << e.dump();
  expect_error(c, R"({"type":"dance"})", "bad_message", "unknown message type 'dance'");
  expect_error(c, R"({"type":"frame","t":0.2,"head":{"p":[0,1.6]}})", "bad_message", "frame.head.p must be an array of 3 numbers");
  expect_alive(c, 0.3);
}

TEST(Serve, WrongVersionIsRefusedWithAnError) {
  RunningServer srv;
  Client c(srv.port());
  expect_error(c, R"({"type":"hello","version":2,"method":"ik"})", "bad_version", "unsupported protocol version 2: this server speaks version 1");
  expect_error(c, R"({"type":"frame","t":0.1})", "bad_message", "send hello before frames");
  c.hello();  // the session survives: a correct hello still works
  expect_alive(c, 0.5);
}

TEST(Serve, UnknownMethodAndMissingDatabaseAreExplained) {
  RunningServer srv;
  Client c(srv.port());
  expect_error(c, R"({"type":"hello","version":1,"method":"teleport"})", "bad_value",
               "unknown method 'teleport' (known: accent, ik, wip, combined, walker)");
  expect_error(c, R"({"type":"hello","version":1,"method":"accent"})", "bad_value",
               "method 'accent' needs a database: start the server with --db FILE");
}

TEST(Serve, OversizedMessageClosesWith1009AndOthersKeepGoing) {
  RunningServer srv;
  Client other(srv.port());
  other.hello();
  Client c(srv.port());
  c.hello();
  c.send_text(std::string(64 * 1024 + 1, ' '));
  EXPECT_FALSE(c.read());
  EXPECT_EQ(c.close_code(), 1009) << c.error().message();
  expect_alive(other, 1.0);
  // Exactly 64 KiB is still a message (here: malformed JSON, answered with an error).
  Client edge(srv.port());
  edge.hello();
  edge.send_text(std::string(64 * 1024, ' '));
  EXPECT_EQ(edge.expect("error")["code"], "bad_json");
}

TEST(Serve, NanValuesGetAnErrorNamingTheField) {
  RunningServer srv;
  Client c(srv.port());
  c.hello();
  c.send_text(R"({"type":"frame","t":0.1,"head":{"p":[null,1.6,0],"q":[1,0,0,0]}})");  // JSON.stringify(NaN) is null
  json e = c.expect("error");
  EXPECT_EQ(e["code"], "bad_value");
  EXPECT_NE(e["message"].get<std::string>().find("frame.head.p[0] is not a number"), std::string::npos) << e.dump();
  c.send_text(R"({"type":"frame","t":NaN})");
  EXPECT_EQ(c.expect("error")["code"], "bad_json");
  TrackerFrame f = trial_frames()[0];
  f.hand(kRight).position.y() = std::numeric_limits<double>::quiet_NaN();
  c.send_binary(binary_frame(f));
  e = c.expect("error");
  EXPECT_EQ(e["code"], "bad_value");
  EXPECT_NE(e["message"].get<std::string>().find("frame.right has a non-finite value"), std::string::npos) << e.dump();
  f.time = std::numeric_limits<double>::infinity();
  f.hand(kRight).position.y() = 1;
  c.send_binary(binary_frame(f));
  EXPECT_NE(c.expect("error")["message"].get<std::string>().find("frame.t is not finite"), std::string::npos);
  expect_alive(c, 0.2);
}

TEST(Serve, TimeGoingBackwardsIsRejectedWithAnError) {
  RunningServer srv;
  Client c(srv.port());
  c.hello();
  expect_alive(c, 2.0);
  TrackerFrame f = trial_frames()[1];
  f.time = 1.5;
  c.send_text(json_frame(f));
  const json e = c.expect("error");
  EXPECT_EQ(e["code"], "bad_value");
  EXPECT_EQ(e["seq"], 2);
  EXPECT_NE(e["message"].get<std::string>().find("t = 1.500000 s is not after the last accepted frame's t = 2.000000 s"),
            std::string::npos)
      << e.dump();
  expect_alive(c, 2.1);
}

TEST(Serve, LostDevicesGiveDegradedPoses) {
  RunningServer srv;
  Client c(srv.port());
  c.hello();
  expect_alive(c, 0.1);
  TrackerFrame f = trial_frames()[1];
  f.time = 0.2;
  f.hand(kLeft).valid = false;
  c.send_text(json_frame(f));
  EXPECT_EQ(c.expect("pose")["status"], "degraded");
}

TEST(Serve, ClientVanishingMidStreamDoesNotDisturbOthers) {
  RunningServer srv;
  Client keeper(srv.port());
  keeper.hello();
  {
    Client gone(srv.port());
    gone.hello();
    const auto frames = trial_frames();
    for (std::size_t i = 0; i < 50; ++i) gone.send_text(json_frame(frames[i]));  // never reads its poses
    gone.vanish();
  }
  expect_alive(keeper, 0.1);
  for (int i = 0; i < 200 && srv.server().stats().live_sessions > 1; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_EQ(srv.server().stats().live_sessions, 1);
  EXPECT_EQ(srv.server().stats().sessions_closed, 1u);
  expect_alive(keeper, 0.2);
}

// --idle-timeout: a client that sends nothing and answers no ping (gone without closing
// its TCP connection) is closed; one that streams, and one that only listens (its
// WebSocket answers the server's ping, as a paused browser's does), stay.
TEST(Serve, SilentConnectionsArePingedThenClosedAfterTheIdleTimeout) {
  ServeOptions o = test_options();
  o.idle_timeout_seconds = 1.0;
  RunningServer srv(o);
  Client silent(srv.port()), listening(srv.port()), streaming(srv.port());
  silent.hello();
  listening.hello();
  streaming.hello();
  std::optional<Client::Message> heard;
  std::thread listener([&] { heard = listening.read(std::chrono::milliseconds(20000)); });
  const auto frames = trial_frames();
  const auto start = std::chrono::steady_clock::now();
  std::optional<std::uint64_t> closed_at_half;  // sessions closed at half the idle timeout
  for (std::size_t i = 0; std::chrono::steady_clock::now() - start < std::chrono::milliseconds(3000); ++i) {
    streaming.send_text(json_frame(frames[i]));
    streaming.expect("pose");
    if (!closed_at_half && std::chrono::steady_clock::now() - start > std::chrono::milliseconds(500))
      closed_at_half = srv.server().stats().sessions_closed;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const ServerStats st = srv.server().stats();
  EXPECT_EQ(closed_at_half, std::optional<std::uint64_t>(0)) << "a session closed within half the idle timeout";
  EXPECT_EQ(st.sessions_closed, 1u);
  EXPECT_EQ(st.live_sessions, 2);
  expect_alive(streaming, 100.0);
  EXPECT_FALSE(silent.read(std::chrono::milliseconds(1000)));
  EXPECT_TRUE(silent.error()) << "the silent client's connection is still open";
  srv.stop();  // the listening client's read ends with the server's close (going away)
  listener.join();
  EXPECT_FALSE(heard) << "the listening client got a message: " << heard->data;
  EXPECT_EQ(listening.close_code(), static_cast<int>(websocket::close_code::going_away));
}

TEST(Serve, ThousandConnectDisconnectCyclesWhileAnotherClientStreams) {
  RunningServer srv;
  Client keeper(srv.port());
  keeper.hello();
  const auto frames = trial_frames();
  int answered = 0;
  for (int i = 0; i < 1000; ++i) {
    {
      Client c(srv.port());
      if (i % 2 == 0) {
        c.hello();
        c.send_text(json_frame(frames[0]));
      }
      if (i % 3 == 0) c.vanish();
      else c.close();
    }
    if (i % 10 == 0) {
      TrackerFrame f = frames[static_cast<std::size_t>(i / 10) % frames.size()];
      f.time = 1.0 + i * 0.001;
      keeper.send_text(json_frame(f));
      const json p = keeper.expect("pose");
      answered += p.value("type", "") == "pose";
    }
  }
  EXPECT_EQ(answered, 100);
  // The last cycles' accepts and closes may still be in flight.
  for (int i = 0; i < 300 && (srv.server().stats().live_sessions > 1 || srv.server().stats().sessions_opened < 1001); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_EQ(srv.server().stats().live_sessions, 1);
  EXPECT_EQ(srv.server().stats().sessions_opened, 1001u);
}

// Sends `frames` as fast as the socket takes them, then reads until the server
// is quiet; returns the last `rate` error, or if there was none the last
// other error (so a test expecting none sees it), or an empty object. (Which
// error comes last depends on the machine's speed: with timestamps going back
// in time, frames the ceiling let through are then refused as out of order.)
json send_all_and_drain(Client& c, const std::vector<TrackerFrame>& frames) {
  for (const TrackerFrame& f : frames) c.send_binary(binary_frame(f));
  json rate = json::object(), other = json::object();
  while (auto m = c.read(std::chrono::milliseconds(500)))
    if (!m->binary && m->j()["type"] == "error") (m->j().value("code", "") == "rate" ? rate : other) = m->j();
  return rate.empty() ? other : rate;
}

ServeOptions rate_limited(double hz) {
  ServeOptions o = test_options();
  o.max_rate_hz = hz;
  o.workers = 0;
  return o;
}

// A 90 Hz stream whose last 2 s arrive at once (what the socket delivers after
// the server's thread stalled, e.g. on a loaded machine): every frame is kept.
TEST(Serve, RateLimitKeepsAnHonestBacklogDeliveredAtOnce) {
  RunningServer srv(rate_limited(120));
  Client c(srv.port());
  c.hello();
  const auto frames = trial_frames();
  ASSERT_GE(frames.size(), 240U);
  const std::size_t paced = frames.size() - 180;
  for (std::size_t i = 0; i < paced; ++i) {  // in step with the frames' times
    c.send_binary(binary_frame(frames[i]));
    std::this_thread::sleep_for(std::chrono::microseconds(11111));
  }
  const json rate = send_all_and_drain(c, {frames.begin() + static_cast<std::ptrdiff_t>(paced), frames.end()});
  EXPECT_TRUE(rate.empty()) << rate.dump();
  EXPECT_EQ(srv.server().stats().frames, frames.size());
  EXPECT_EQ(srv.server().stats().rate_dropped, 0U);
}

// A client stamping its frames at 240 Hz (sent as fast as the socket takes
// them) keeps the quarter-second burst and then 120 Hz of its own time.
TEST(Serve, RateLimitDropsAClientSendingAboveMaxRateInItsOwnTime) {
  RunningServer srv(rate_limited(120));
  Client c(srv.port());
  c.hello();
  auto frames = trial_frames("walking/07_02.bvh", false, 240);
  ASSERT_GE(frames.size(), 400U);
  frames.resize(400);
  const json rate = send_all_and_drain(c, frames);
  ASSERT_EQ(rate.value("code", ""), "rate") << rate.dump();
  EXPECT_NE(rate["message"].get<std::string>().find("frames above 120 Hz are dropped"), std::string::npos) << rate.dump();
  const double kept = 120 * RateLimiter::kStreamBurstSeconds + 120 * (frames.back().time - frames.front().time);
  EXPECT_NEAR(static_cast<double>(frames.size() - srv.server().stats().rate_dropped), kept, 1.0);
}

// A client whose timestamps run ahead of real time (a second per frame, 600
// frames as fast as it can) is held by the wall-clock ceiling: two seconds of
// 120 Hz, then 240 frames per second of the server's clock.
TEST(Serve, RateLimitBoundsAClientWithFakeTimestamps) {
  const auto t0 = std::chrono::steady_clock::now();
  RunningServer srv(rate_limited(120));
  Client c(srv.port());
  c.hello();
  auto frames = trial_frames();
  frames.resize(200);
  for (std::size_t i = 0; i < frames.size(); ++i) frames[i].time = static_cast<double>(i);
  for (int k = 0; k < 2; ++k) frames.insert(frames.end(), frames.begin(), frames.begin() + 200);  // and back in time, twice
  const json rate = send_all_and_drain(c, frames);
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::uint64_t dropped = srv.server().stats().rate_dropped;
  const auto kept = static_cast<double>(frames.size() - dropped);
  EXPECT_LE(kept, 120 * RateLimiter::kCeilingBurstSeconds + 240 * elapsed + 1) << "in " << elapsed << " s";
  EXPECT_GE(kept, 120 * RateLimiter::kCeilingBurstSeconds);
  // The ceiling is wall-clock: on a machine too slow to send faster than 240 Hz (e.g. under
  // ThreadSanitizer) nothing is over it, and the bound above is all there is to check.
  if (dropped > 0) {
    ASSERT_EQ(rate.value("code", ""), "rate") << rate.dump();
    EXPECT_NE(rate["message"].get<std::string>().find("frames arriving above 240 Hz of the server's clock are dropped"),
              std::string::npos)
        << rate.dump();
  } else {
    std::printf("[serve] %zu frames in %.2f s: never above the wall-clock ceiling\n", frames.size(), elapsed);
  }
}

TEST(Serve, SessionLimitRefusesWithBusy) {
  ServeOptions o = test_options();
  o.max_sessions = 2;
  RunningServer srv(o);
  Client a(srv.port()), b(srv.port());
  a.hello();
  b.hello();
  Client c(srv.port());
  const json e = c.expect("error");
  EXPECT_EQ(e["code"], "busy");
  EXPECT_NE(e["message"].get<std::string>().find("server full (2 sessions)"), std::string::npos);
  EXPECT_FALSE(c.read());
  EXPECT_EQ(c.close_code(), 1013);
  expect_alive(a, 0.1);
}

TEST(Serve, OptionsBeforeHelloAndBadOptionsAreErrors) {
  RunningServer srv;
  Client c(srv.port());
  c.send_text(R"({"type":"options","exaggeration":1.5})");
  EXPECT_NE(c.expect("error")["message"].get<std::string>().find("send hello before options"), std::string::npos);
  c.hello();
  c.send_text(R"({"type":"options","exaggeration":-1})");
  const json e = c.expect("error");
  EXPECT_NE(e["message"].get<std::string>().find("options not applied: exaggeration -1"), std::string::npos) << e.dump();
  expect_alive(c, 0.1);
}

TEST(Serve, WorkersZeroSynthesizesOnTheNetworkThreadWithTheSameAnswers) {
  ServeOptions o = test_options();
  o.workers = 0;
  RunningServer srv(o);
  Client c(srv.port());
  const auto [worst, poses] = stream_trial(c, c.hello({{"format", "binary"}}), true);
  EXPECT_EQ(poses, static_cast<int>(trial_frames().size()));
  EXPECT_LT(worst, 0.01) << "wrists must be within 1 cm of the input hands";
  Client other(srv.port());  // a second session after the first streamed
  other.hello();
  other.send_text(json_frame(trial_frames()[0]));
  EXPECT_EQ(other.expect("pose")["seq"], 1);
}

TEST(Serve, RecordsInputAsTrackerCsvAndOutputAsBvh) {
  const auto dir = std::filesystem::temp_directory_path() / ("legwork-serve-rec-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  ServeOptions o = test_options();
  o.record_dir = dir.string();
  const auto frames = trial_frames();
  {
    RunningServer srv(o);
    Client c(srv.port());
    EXPECT_TRUE(c.hello()["recording"].get<bool>());
    for (std::size_t i = 0; i < 90; ++i) {
      c.send_text(json_frame(frames[i]));
      c.expect("pose");
    }
    c.close();
  }
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir)) files.push_back(e.path());
  std::sort(files.begin(), files.end(), [](const auto& a, const auto& b) { return a.extension() > b.extension(); });
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0].extension(), ".csv");
  EXPECT_EQ(files[1].extension(), ".bvh");
  const io::TrackerTable t = io::read_tracker_csv(files[0].string());
  ASSERT_EQ(t.sample_count(), 90);
  EXPECT_NEAR(t.point("left_hand").position[45].x(), frames[45].hand(kLeft).position.x(), 1e-5);
  const Motion m = io::load_bvh(files[1].string());
  EXPECT_EQ(m.frame_count(), 90);
  EXPECT_NEAR(m.fps, 90.0, 0.01);
  std::filesystem::remove_all(dir);
}

// The server hands HTTP requests to handle_http (tests/serve/http_api_test.cpp
// checks the API and the static files themselves) with the raw target.
TEST(Serve, HttpRequestsReachTheApiAndTheWebFolder) {
  const auto web = std::filesystem::temp_directory_path() / ("legwork-serve-web-" + std::to_string(::getpid()));
  std::filesystem::create_directories(web);
  std::ofstream(web / "index.html") << "<html>legwork</html>";
  ServeOptions o = test_options();
  o.web_dir = web.string();
  RunningServer srv(o);
  net::io_context ioc;
  const auto get = [&](const std::string& target) {
    beast::tcp_stream s(ioc);
    tcp::resolver r(ioc);
    s.connect(r.resolve("127.0.0.1", std::to_string(srv.port())));
    beast::http::request<beast::http::empty_body> req{beast::http::verb::get, target, 11};
    req.set(beast::http::field::host, "127.0.0.1");
    beast::http::write(s, req);
    beast::flat_buffer b;
    beast::http::response<beast::http::string_body> res;
    beast::http::read(s, b, res);
    return std::make_pair(res.result_int(), res.body());
  };
  EXPECT_EQ(get("/").second, "<html>legwork</html>");
  EXPECT_EQ(get("/%2e%2e/%2e%2e/etc/passwd").first, 404u);
  const json info = json::parse(get("/api/info").second);
  EXPECT_EQ(info["version"], 1);
  EXPECT_EQ(info["methods"], json({"ik", "wip", "combined"}));
  const auto [code, body] = get("/api/trial?name=walking/07_02&rate=90");
  ASSERT_EQ(code, 200u);
  EXPECT_EQ(json::parse(body)["frames"].size(), trial_frames("walking/07_02.bvh", true).size());
  EXPECT_EQ(get("/api/trial?name=walking/07_02&rate=1000").first, 400u);
  std::filesystem::remove_all(web);
}

}  // namespace
}  // namespace legwork::serve

namespace legwork::serve {
namespace {

using namespace testing;

TEST(ServeWip, WalkingInPlaceLegsFromTheAnklesOfARealWalk) {
  RunningServer srv;
  Client c(srv.port());
  const json w = c.hello({{"method", "wip"}});
  EXPECT_EQ(w["method"], "wip");
  // A real walk's ankles (and head for the heading) as in-place trackers: the
  // feet rise and fall, so the legs must start stepping.
  const auto frames = trial_frames("walking/07_02.bvh", true);
  int walking = 0, poses = 0;
  for (const TrackerFrame& f : frames) {
    c.send_text(json_frame(f));
    const json p = c.expect("pose");
    poses += p["type"] == "pose";
    walking += p["info"]["walking"].get<double>() > 0;
  }
  EXPECT_EQ(poses, static_cast<int>(frames.size()));
  EXPECT_GT(walking, 0) << "the wip legs never started walking on a real walk's ankles";
  // Without feet the legs cannot be driven: degraded.
  TrackerFrame f = frames.back();
  f.time += 0.011;
  f.foot(kLeft).valid = f.foot(kRight).valid = false;
  c.send_text(json_frame(f));
  EXPECT_EQ(c.expect("pose")["status"], "degraded");
}

}  // namespace
}  // namespace legwork::serve

namespace legwork::serve {
namespace {

using namespace testing;

// The learned depth mapping (issue 13) through the server: a session asks for
// it in hello; its feet move fore-aft otherwise than the document's equations
// on the same real walk; without a table, or with an unknown name, hello gets
// an error naming the option.
TEST(ServeWip, LearnedMappingIsASessionOption) {
  ServeOptions o = test_options();
  o.wip_table = source_dir() + "/data/wip/learned_mapping.txt";
  RunningServer srv(o);
  const auto frames = trial_frames("walking/07_02.bvh", true);
  std::vector<std::vector<double>> depth(2);  // left ankle's fore-aft offset from the hips, per pose
  for (int learned = 0; learned < 2; ++learned) {
    Client c(srv.port());
    const json w = c.hello({{"method", "wip"}, {"mapping", learned ? "learned" : "document"}});
    const auto& names = w["skeleton"]["names"];
    const auto foot = static_cast<std::size_t>(std::find(names.begin(), names.end(), "LeftFoot") - names.begin());
    for (const TrackerFrame& f : frames) {
      c.send_text(json_frame(f));
      const json p = c.expect("pose");
      const Vec3 hips = vec(p["positions"][0]), ankle = vec(p["positions"][foot]);
      depth[static_cast<std::size_t>(learned)].push_back(ankle.z() - hips.z());
    }
  }
  ASSERT_EQ(depth[0].size(), depth[1].size());
  double most = 0;
  for (std::size_t i = 0; i < depth[0].size(); ++i) {
    EXPECT_TRUE(std::isfinite(depth[1][i])) << "pose " << i;
    most = std::max(most, std::abs(depth[1][i] - depth[0][i]));
  }
  EXPECT_GT(most, 0.02) << "the learned mapping moved the foot like the document's";

  Client bad(srv.port());
  bad.send_text(R"({"type":"hello","version":1,"method":"wip","mapping":"magic"})");
  EXPECT_EQ(bad.expect("error")["message"], "mapping 'magic' is not one of: document, learned");
  // A --wip-table that is not a table stops the server at start, naming the file and line.
  ServeOptions wrong = test_options();
  wrong.wip_table = source_dir() + "/data/cmu/MANIFEST.tsv";
  try {
    Server refused(wrong);
    ADD_FAILURE() << "a server started with a bad --wip-table";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("MANIFEST.tsv:1: not a learned walking-in-place mapping"), std::string::npos) << e.what();
  }
  RunningServer plain;  // no --wip-table
  Client none(plain.port());
  none.send_text(R"({"type":"hello","version":1,"method":"combined","mapping":"learned"})");
  EXPECT_EQ(none.expect("error")["message"].get<std::string>().rfind("mapping 'learned' needs the learned table: start the server with --wip-table FILE", 0), 0u);
}

// The step detector (issue 13 item 2) is a session option: on the same real
// walk the adaptive detector lifts the left foot (leaves double support)
// earlier than the document's thresholds; an unknown name is refused, named.
TEST(ServeWip, StepDetectorIsASessionOption) {
  RunningServer srv;
  const auto frames = trial_frames("walking/07_02.bvh", true);
  int first_swing[2] = {-1, -1};
  for (int adaptive = 0; adaptive < 2; ++adaptive) {
    Client c(srv.port());
    c.hello({{"method", "wip"}, {"detector", adaptive ? "adaptive" : "document"}});
    for (std::size_t i = 0; i < frames.size(); ++i) {
      c.send_text(json_frame(frames[i]));
      const json p = c.expect("pose");
      if (first_swing[adaptive] < 0 && p["info"]["phase_left"] != "double_support") first_swing[adaptive] = static_cast<int>(i);
    }
  }
  ASSERT_GE(first_swing[0], 0) << "the document's detector saw no left step";
  ASSERT_GE(first_swing[1], 0) << "the adaptive detector saw no left step";
  EXPECT_LT(first_swing[1], first_swing[0]) << "the adaptive detector did not lift the foot earlier";
  Client bad(srv.port());
  bad.send_text(R"({"type":"hello","version":1,"method":"wip","detector":"psychic"})");
  EXPECT_EQ(bad.expect("error")["message"], "detector 'psychic' is not one of: document, adaptive");
}

TEST(ServeCombined, UpperBodyFollowsTheHandsAndTheLegsComeFromWip) {
  RunningServer srv;
  Client c(srv.port());
  const json w = c.hello({{"method", "combined"}});
  const auto& names = w["skeleton"]["names"];
  const auto lh = static_cast<std::size_t>(std::find(names.begin(), names.end(), "LeftHand") - names.begin());
  const auto frames = trial_frames("walking/07_02.bvh", true);
  double worst = 0;
  for (const TrackerFrame& f : frames) {
    c.send_text(json_frame(f));
    const json p = c.expect("pose");
    ASSERT_EQ(p["status"], "ok") << p.dump();
    EXPECT_EQ(p["info"]["legs"], "wip");
    const auto& q = p["positions"][lh];
    worst = std::max(worst, (Vec3(q[0], q[1], q[2]) - f.hand(kLeft).position).norm());
  }
  EXPECT_LT(worst, 0.01) << "the legs must not move the upper body's wrists off the controllers";
  TrackerFrame f = frames.back();
  f.time += 0.011;
  f.foot(kRight).valid = false;
  c.send_text(json_frame(f));
  const json p = c.expect("pose");
  EXPECT_EQ(p["status"], "degraded");
  EXPECT_EQ(p["info"]["legs"], "upper");
}

}  // namespace
}  // namespace legwork::serve
