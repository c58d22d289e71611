#pragma once
// One live avatar: a Method, a bounded latest-sample-wins input queue, the
// pose output and an optional recording. Network threads push frames; worker
// threads (Workers) run the synthesis, so a slow client never delays others.
#include <legwork/core/motion.hpp>
#include <legwork/serve/methods.hpp>
#include <legwork/serve/protocol.hpp>

#include <array>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace legwork::serve {

using SteadyClock = std::chrono::steady_clock;

// One message for the client: a pose (droppable when the client lags) or an error.
struct Outgoing {
  std::string data;
  bool binary = false;
  bool droppable = false;  // poses: a newer one may replace it
  bool restarted = false;  // a restarted pose: the last droppable one to go (the client learns of the reset)
};
using Sink = std::function<void(Outgoing)>;

// Most poses that wait for a client that does not read them (docs/protocol.md, Flow).
inline constexpr int kMaxWaitingPoses = 8;
// Queues `o` for a client. A pose that would make more than kMaxWaitingPoses
// wait first removes the oldest waiting pose from out[first...] (`first`
// skips a message being written), a restarted pose only when every waiting
// one is restarted: the client still learns that its avatar was reset.
void queue_for_client(std::deque<Outgoing>& out, std::size_t first, Outgoing o);
// Called on the worker after each consumed frame (VMC output).
using PoseListener = std::function<void(const Skeleton&, ConstPoseRef, std::span<const Vec3> world)>;

struct RecordSpec {
  std::string dir;            // empty: no recording
  double max_seconds = 300;   // input beyond this is not recorded
};

struct AvatarStats {
  std::uint64_t received = 0, processed = 0, skipped = 0, rejected = 0;
};

class Avatar {
 public:
  static constexpr std::size_t kQueueCapacity = 4;

  Avatar(std::string id, const Resources& res, std::unique_ptr<Method> method, const Hello& hello,
         std::vector<int> joints, Sink sink, RecordSpec record = {});
  ~Avatar();

  const std::string& id() const { return id_; }
  const Skeleton& skeleton() const { return method_->skeleton(); }
  void set_listener(PoseListener l);

  // Network side. Each returns true when the avatar must be scheduled on a worker.
  bool push(const TrackerFrame& f, std::uint64_t seq, SteadyClock::time_point received);
  bool push_options(const OptionsUpdate& o);
  bool close();  // no more input: finish (write the recording) on a worker

  // Worker side: handles one queued item; true when more remain (reschedule).
  bool process_one();
  // Paths written by the recording (after close has been processed).
  std::vector<std::string> recorded_files() const;
  AvatarStats stats() const;
  bool finished() const;

 private:
  struct Item {
    TrackerFrame frame;
    std::uint64_t seq = 0;
    SteadyClock::time_point received;
  };
  void run_frame(const Item& it);
  void apply_options(const OptionsUpdate& o);
  void write_recording();

  const std::string id_;
  const Resources res_;
  MethodOptions options_;
  std::unique_ptr<Method> method_;
  std::vector<int> joints_;
  Format format_;
  Sink sink_;
  PoseListener listener_;
  RecordSpec record_;

  mutable std::mutex mu_;
  // The waiting frames: a ring of kQueueCapacity (no allocation per frame).
  std::array<Item, kQueueCapacity> queue_{};
  std::size_t queue_head_ = 0, queue_size_ = 0;
  std::deque<OptionsUpdate> pending_options_;
  bool scheduled_ = false, closing_ = false, finished_ = false;
  AvatarStats stats_;
  std::vector<std::string> recorded_;

  // Worker-only state.
  Pose pose_;
  std::vector<Vec3> world_;
  std::string buffer_;
  bool have_pose_ = false, have_time_ = false;
  double last_time_ = 0;
  std::vector<TrackerFrame> rec_in_;
  std::vector<Pose> rec_out_;
};

// Worker threads running Avatars (FIFO over avatars: each gets one frame per turn).
// With 0 threads, schedule() runs the avatar at once on the calling thread: no
// hand-off between threads, the cheapest choice for one process per core.
class Workers {
 public:
  explicit Workers(int threads);
  ~Workers();
  void schedule(std::shared_ptr<Avatar> a);
  void stop();  // finishes queued work, joins

 private:
  void loop();
  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<std::shared_ptr<Avatar>> ready_;
  bool stopping_ = false;
  bool inline_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace legwork::serve
