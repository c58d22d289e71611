// One live avatar without a network: frames in, poses (or errors) out through
// the sink, latest-sample-wins queueing, options, recording, and the worker
// pool (Workers(0) runs avatars inline on the caller's thread).
#include <legwork/serve/avatar.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/tracker_csv.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <atomic>
#include <deque>
#include <filesystem>
#include <unistd.h>

#include "cmu_sample.hpp"

namespace legwork::serve {
namespace {

using json = nlohmann::json;

const Skeleton& avatar_skeleton() { return testdata::sample_skeleton(); }

// Head + hands of a real trial of the avatar's subject, at 90 Hz.
const std::vector<TrackerFrame>& frames() {
  static const auto f = [] {
    auto out = tracker_frames_from_motion(testdata::load_sample("cmu/bvh/walking/07_02.bvh"), 90.0);
    for (auto& x : out) x.foot(kLeft).valid = x.foot(kRight).valid = false;
    return out;
  }();
  return f;
}

// An ik avatar whose sink collects every message.
struct Session {
  Resources res;
  std::vector<Outgoing> sent;
  std::shared_ptr<Avatar> avatar;

  explicit Session(RecordSpec record = {}, Format format = Format::Json) {
    res.skeleton = &avatar_skeleton();
    Hello hello;
    hello.method.method = "ik";
    hello.format = format;
    std::vector<int> all(static_cast<std::size_t>(avatar_skeleton().joint_count()));
    for (std::size_t j = 0; j < all.size(); ++j) all[j] = static_cast<int>(j);
    avatar = std::make_shared<Avatar>("s1", res, make_method(res, hello.method), hello, all,
                                      [this](Outgoing o) { sent.push_back(std::move(o)); }, std::move(record));
  }
  // Pushes frame i as sequence number seq and runs the avatar inline.
  void feed(Workers& w, std::size_t i, std::uint64_t seq) {
    if (avatar->push(frames()[i], seq, SteadyClock::now())) w.schedule(avatar);
  }
  json last() const { return json::parse(sent.back().data); }
};

TEST(Avatar, InlineWorkersAnswerEveryFrameWithAPose) {
  Session s;
  Workers inline_workers(0);
  const int hand = avatar_skeleton().require("LeftHand");
  for (std::size_t i = 0; i < 30; ++i) {
    s.feed(inline_workers, i, i + 1);
    ASSERT_EQ(s.sent.size(), i + 1) << "Workers(0) must answer before schedule() returns";
    const json p = s.last();
    EXPECT_TRUE(s.sent.back().droppable);
    EXPECT_FALSE(s.sent.back().binary);
    EXPECT_EQ(p["type"], "pose");
    EXPECT_EQ(p["seq"], i + 1);
    EXPECT_NEAR(p["t"].get<double>(), frames()[i].time, 1e-6);
    const auto& w = p["positions"][static_cast<std::size_t>(hand)];
    const Vec3 got(w[0].get<double>(), w[1].get<double>(), w[2].get<double>());
    EXPECT_LT((got - frames()[i].hand(kLeft).position).norm(), 0.01);
  }
  const AvatarStats st = s.avatar->stats();
  EXPECT_EQ(st.received, 30u);
  EXPECT_EQ(st.processed, 30u);
  EXPECT_EQ(st.skipped, 0u);
  EXPECT_EQ(st.rejected, 0u);
}

TEST(Avatar, LatestSampleWinsWhenTheQueueIsFull) {
  Session s;
  // Nothing runs the avatar while six frames arrive: only the first push asks to be scheduled.
  EXPECT_TRUE(s.avatar->push(frames()[0], 1, SteadyClock::now()));
  for (std::uint64_t i = 1; i < 6; ++i) EXPECT_FALSE(s.avatar->push(frames()[i], i + 1, SteadyClock::now()));
  while (s.avatar->process_one()) {
  }
  const AvatarStats st = s.avatar->stats();
  EXPECT_EQ(st.received, 6u);
  EXPECT_EQ(st.skipped, 6u - Avatar::kQueueCapacity);
  EXPECT_EQ(st.processed, Avatar::kQueueCapacity);
  // The oldest frames went; the newest kQueueCapacity were answered in order.
  ASSERT_EQ(s.sent.size(), Avatar::kQueueCapacity);
  for (std::size_t k = 0; k < s.sent.size(); ++k)
    EXPECT_EQ(json::parse(s.sent[k].data)["seq"], 6 - Avatar::kQueueCapacity + k + 1);
  // Idle again: the next push must be scheduled.
  EXPECT_TRUE(s.avatar->push(frames()[6], 7, SteadyClock::now()));
}

// A client that does not read: the queue keeps the newest kMaxWaitingPoses
// poses, the one being written and every error, and drops a restarted pose
// (the avatar was reset: the client must learn it) only when every waiting
// pose is one.
TEST(Avatar, ARestartedPoseIsTheLastPoseDroppedForAClientThatDoesNotRead) {
  Session s;
  Workers inline_workers(0);
  for (std::size_t i = 0; i < 30; ++i) {
    TrackerFrame f = frames()[i];
    if (i >= 10) f.time += 6.0;  // a jump forward past FrameClock::kMaxGap: the stream restarts
    if (s.avatar->push(f, i + 1, SteadyClock::now())) inline_workers.schedule(s.avatar);
  }
  ASSERT_EQ(s.sent.size(), 30u);
  EXPECT_EQ(json::parse(s.sent[10].data)["status"], "restarted");
  EXPECT_TRUE(s.sent[10].restarted);
  for (std::size_t i = 0; i < 30; ++i) {
    if (i != 10) {
      EXPECT_FALSE(s.sent[i].restarted) << i;
    }
  }

  std::deque<Outgoing> out;
  out.push_back({"being written", false, true, false});
  out.push_back({"an error", false, false, false});
  for (const Outgoing& o : s.sent) queue_for_client(out, 1, o);
  std::vector<std::string> statuses;
  int droppable = 0;
  for (std::size_t k = 2; k < out.size(); ++k) {
    statuses.push_back(json::parse(out[k].data)["status"]);
    droppable += out[k].droppable;
  }
  EXPECT_EQ(out[0].data, "being written");
  EXPECT_EQ(out[1].data, "an error");
  EXPECT_EQ(droppable + 1, kMaxWaitingPoses);  // + the one being written
  ASSERT_EQ(out.size(), 2u + static_cast<std::size_t>(kMaxWaitingPoses) - 1);
  EXPECT_EQ(statuses.front(), "restarted");  // kept, though 19 newer poses came after it
  EXPECT_EQ(json::parse(out.back().data)["seq"], 30);
  for (std::size_t k = 3; k < out.size(); ++k)  // the others are the newest, in order
    EXPECT_EQ(json::parse(out[k].data)["seq"].get<int>(), 30 - static_cast<int>(out.size() - 1 - k));

  // Only restarted poses waiting: the oldest of them goes, so the queue stays bounded.
  std::deque<Outgoing> resets;
  for (int i = 0; i < 3 * kMaxWaitingPoses; ++i) queue_for_client(resets, 0, {std::to_string(i), false, true, true});
  ASSERT_EQ(resets.size(), static_cast<std::size_t>(kMaxWaitingPoses));
  EXPECT_EQ(resets.front().data, std::to_string(2 * kMaxWaitingPoses));
}

TEST(Avatar, RejectedFramesAndBadOptionsGetErrors) {
  Session s;
  Workers w(0);
  s.feed(w, 10, 1);
  s.feed(w, 5, 2);  // earlier than the last accepted frame
  json e = s.last();
  EXPECT_FALSE(s.sent.back().droppable);
  EXPECT_EQ(e["type"], "error");
  EXPECT_EQ(e["code"], "bad_value");
  EXPECT_EQ(e["seq"], 2);
  char want[200];
  std::snprintf(want, sizeof want, "frame rejected: t = %.6f s is not after the last accepted frame's t = %.6f s",
                frames()[5].time, frames()[10].time);
  EXPECT_EQ(e["message"], want);
  EXPECT_EQ(s.avatar->stats().rejected, 1u);
  OptionsUpdate o;
  o.exaggeration = 9;
  if (s.avatar->push_options(o)) w.schedule(s.avatar);
  e = s.last();
  EXPECT_EQ(e["code"], "bad_value");
  EXPECT_EQ(e["message"], "options not applied: exaggeration 9.000000 is outside (0, 4]");
  // The avatar keeps going with its old method.
  s.feed(w, 11, 3);
  EXPECT_EQ(s.last()["type"], "pose");
}

TEST(Avatar, ListenerSeesEveryConsumedPoseAndItsWorldPositions) {
  Session s;
  Workers w(0);
  int calls = 0;
  double worst = 0;
  s.avatar->set_listener([&](const Skeleton& skel, ConstPoseRef pose, std::span<const Vec3> world) {
    ++calls;
    const auto fk = joint_positions(skel, pose);
    for (std::size_t j = 0; j < fk.size(); ++j) worst = std::max(worst, (fk[j] - world[j]).norm());
  });
  for (std::size_t i = 0; i < 5; ++i) s.feed(w, i, i + 1);
  s.feed(w, 1, 6);  // rejected: not consumed, not heard
  EXPECT_EQ(calls, 5);
  EXPECT_LT(worst, 1e-9);
}

TEST(Avatar, CloseWritesTheRecordingOfWhatWasConsumed) {
  const auto dir = std::filesystem::temp_directory_path() / ("legwork-avatar-rec-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  RecordSpec rec;
  rec.dir = dir.string();
  rec.max_seconds = 0.5;  // 46 frames at 90 Hz (0 .. 0.5 s)
  Session s(rec, Format::Binary);
  Workers w(0);
  for (std::size_t i = 0; i < 60; ++i) s.feed(w, i, i + 1);
  EXPECT_TRUE(s.sent.back().binary);
  EXPECT_FALSE(s.avatar->finished());
  if (s.avatar->close()) w.schedule(s.avatar);
  EXPECT_TRUE(s.avatar->finished());
  EXPECT_FALSE(s.avatar->push(frames()[61], 62, SteadyClock::now()));  // closed: input ignored
  EXPECT_EQ(s.avatar->stats().received, 60u);
  const auto files = s.avatar->recorded_files();
  ASSERT_EQ(files.size(), 2u);
  EXPECT_NE(files[0].find("-s1-input.csv"), std::string::npos) << files[0];
  EXPECT_NE(files[1].find("-s1-ik.bvh"), std::string::npos) << files[1];
  int kept = 0;
  for (std::size_t i = 0; i < 60; ++i) kept += frames()[i].time - frames()[0].time <= 0.5;
  const io::TrackerTable t = io::read_tracker_csv(files[0]);
  ASSERT_EQ(t.sample_count(), kept);
  EXPECT_NEAR(t.point("head").position[20].y(), frames()[20].head().position.y(), 1e-5);
  const Motion m = io::load_bvh(files[1]);
  EXPECT_EQ(m.frame_count(), kept);
  EXPECT_NEAR(m.fps, 90.0, 0.01);
  EXPECT_EQ(m.joint_count(), avatar_skeleton().joint_count());
  std::filesystem::remove_all(dir);
}

TEST(Avatar, ThreadedWorkersFinishQueuedAvatarsOnStop) {
  std::vector<std::unique_ptr<Session>> sessions;
  for (int k = 0; k < 3; ++k) sessions.push_back(std::make_unique<Session>());
  {
    Workers w(2);
    // One frame at a time per avatar, as a lock-step client would send.
    for (std::size_t i = 0; i < 20; ++i)
      for (auto& s : sessions) s->feed(w, i, i + 1);
    w.stop();
  }
  for (auto& s : sessions) {
    const AvatarStats st = s->avatar->stats();
    EXPECT_EQ(st.received, 20u);
    EXPECT_EQ(st.processed + st.skipped, 20u);  // every frame either answered or replaced by a newer one
    ASSERT_FALSE(s->sent.empty());
    EXPECT_EQ(json::parse(s->sent.back().data)["seq"], 20);  // the newest frame is always answered
  }
}

}  // namespace
}  // namespace legwork::serve
