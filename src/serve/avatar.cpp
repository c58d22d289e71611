// One live avatar and the worker threads that run avatars (see avatar.hpp).
#include <legwork/serve/avatar.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/tracker_csv.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>

namespace legwork::serve {

Avatar::Avatar(std::string id, const Resources& res, std::unique_ptr<Method> method, const Hello& hello,
               std::vector<int> joints, Sink sink, RecordSpec record)
    : id_(std::move(id)),
      res_(res),
      options_(hello.method),
      method_(std::move(method)),
      joints_(std::move(joints)),
      format_(hello.format),
      sink_(std::move(sink)),
      record_(std::move(record)),
      pose_(method_->skeleton()),
      world_(static_cast<std::size_t>(method_->skeleton().joint_count())) {}

Avatar::~Avatar() = default;

void Avatar::set_listener(PoseListener l) {
  std::lock_guard lock(mu_);
  listener_ = std::move(l);
}

bool Avatar::push(const TrackerFrame& f, std::uint64_t seq, SteadyClock::time_point received) {
  std::lock_guard lock(mu_);
  if (closing_) return false;
  ++stats_.received;
  if (queue_size_ == kQueueCapacity) {  // latest sample wins: the oldest waiting frame goes
    queue_head_ = (queue_head_ + 1) % kQueueCapacity;
    --queue_size_;
    ++stats_.skipped;
  }
  queue_[(queue_head_ + queue_size_++) % kQueueCapacity] = {f, seq, received};
  if (scheduled_) return false;
  scheduled_ = true;
  return true;
}

bool Avatar::push_options(const OptionsUpdate& o) {
  std::lock_guard lock(mu_);
  if (closing_) return false;
  pending_options_.push_back(o);
  if (scheduled_) return false;
  scheduled_ = true;
  return true;
}

bool Avatar::close() {
  std::lock_guard lock(mu_);
  if (closing_) return false;
  closing_ = true;
  queue_size_ = 0;
  pending_options_.clear();
  if (scheduled_) return false;
  scheduled_ = true;
  return true;
}

bool Avatar::finished() const {
  std::lock_guard lock(mu_);
  return finished_;
}

AvatarStats Avatar::stats() const {
  std::lock_guard lock(mu_);
  return stats_;
}

std::vector<std::string> Avatar::recorded_files() const {
  std::lock_guard lock(mu_);
  return recorded_;
}

bool Avatar::process_one() {
  Item item;
  std::optional<OptionsUpdate> opts;
  bool closing = false;
  {
    std::lock_guard lock(mu_);
    if (!pending_options_.empty()) {
      opts = pending_options_.front();
      pending_options_.pop_front();
    } else if (queue_size_ > 0) {
      item = queue_[queue_head_];
      queue_head_ = (queue_head_ + 1) % kQueueCapacity;
      --queue_size_;
    } else if (closing_ && !finished_) {
      closing = true;
    } else {
      scheduled_ = false;
      return false;
    }
  }
  if (opts) {
    apply_options(*opts);
  } else if (closing) {
    write_recording();
    std::lock_guard lock(mu_);
    finished_ = true;
  } else {
    run_frame(item);
  }
  std::lock_guard lock(mu_);
  if (queue_size_ == 0 && pending_options_.empty() && (!closing_ || finished_)) {
    scheduled_ = false;
    return false;
  }
  return true;
}

void Avatar::apply_options(const OptionsUpdate& o) {
  MethodOptions next = options_;
  if (o.exaggeration) next.exaggeration = *o.exaggeration;
  if (o.classes) next.classes = *o.classes;
  if (o.recognize_class) next.recognize_class = *o.recognize_class;
  try {
    std::unique_ptr<Method> m = make_method(res_, next);
    if (m->skeleton().joint_count() != method_->skeleton().joint_count())
      throw Error("options would change the avatar skeleton; start a new session instead");
    method_ = std::move(m);
    options_ = next;
    have_time_ = false;
  } catch (const std::exception& e) {
    sink_({format_error("bad_value", std::string("options not applied: ") + e.what()), false, false});
  }
}

void Avatar::run_frame(const Item& it) {
  InfoFields info;
  const UpdateStatus status = method_->update(it.frame, pose_.ref(), info);
  if (status == UpdateStatus::Rejected) {
    {
      std::lock_guard lock(mu_);
      ++stats_.rejected;
    }
    char msg[200];
    if (have_time_ && it.frame.time <= last_time_)
      std::snprintf(msg, sizeof msg, "frame rejected: t = %.6f s is not after the last accepted frame's t = %.6f s",
                    it.frame.time, last_time_);
    else
      std::snprintf(msg, sizeof msg, "frame rejected at t = %.6f s (time out of range or head not tracked yet)", it.frame.time);
    sink_({format_error("bad_value", msg, it.seq, it.frame.time), false, false});
    return;
  }
  have_time_ = true;
  last_time_ = it.frame.time;
  have_pose_ = true;
  const Skeleton& skel = method_->skeleton();
  forward_positions(skel, pose_.ref(), world_);
  if (!record_.dir.empty() && (rec_in_.empty() || it.frame.time - rec_in_.front().time <= record_.max_seconds) &&
      (rec_in_.empty() || it.frame.time > rec_in_.back().time)) {
    rec_in_.push_back(it.frame);
    rec_out_.push_back(pose_);
  }
  PoseListener listener;
  {
    std::lock_guard lock(mu_);
    ++stats_.processed;
    listener = listener_;
  }
  if (listener) listener(skel, pose_.ref(), world_);
  PoseMessage m;
  m.seq = it.seq;
  m.t = it.frame.time;
  m.status = status;
  m.pose = pose_.ref();
  m.world = world_;
  m.joints = joints_;
  m.info = &info;
  m.server_us = std::chrono::duration<double, std::micro>(SteadyClock::now() - it.received).count();
  if (format_ == Format::Binary)
    format_pose_binary(buffer_, m);
  else
    format_pose_json(buffer_, m);
  sink_({buffer_, format_ == Format::Binary, true, status == UpdateStatus::Restarted});
}

void Avatar::write_recording() {
  if (record_.dir.empty() || rec_in_.size() < 2) return;
  std::vector<std::string> files;
  try {
    std::filesystem::create_directories(record_.dir);
    char stamp[32];
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&now, &tm);
    std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &tm);
    const std::string base = (std::filesystem::path(record_.dir) / (std::string(stamp) + "-" + id_)).string();
    io::write_tracker_csv(base + "-input.csv", io::table_from_frames(rec_in_));
    files.push_back(base + "-input.csv");
    // Output at the input's median rate (poses are stored per consumed frame).
    std::vector<double> dt;
    for (std::size_t i = 1; i < rec_in_.size(); ++i) dt.push_back(rec_in_[i].time - rec_in_[i - 1].time);
    std::nth_element(dt.begin(), dt.begin() + static_cast<std::ptrdiff_t>(dt.size() / 2), dt.end());
    const double med = dt[dt.size() / 2];
    Motion out(method_->skeleton(), med > 0 ? std::clamp(1.0 / med, 1.0, 1000.0) : 90.0, 0);
    for (const Pose& p : rec_out_) out.push_back(p.ref());
    io::write_bvh(base + "-" + options_.method + ".bvh", out);
    files.push_back(base + "-" + options_.method + ".bvh");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "legwork serve: session %s: recording not written: %s\n", id_.c_str(), e.what());
  }
  std::lock_guard lock(mu_);
  recorded_ = files;
}

// ---- Workers ---------------------------------------------------------------

Workers::Workers(int threads) : inline_(threads <= 0) {
  for (int i = 0; i < threads; ++i) threads_.emplace_back([this] { loop(); });
}

Workers::~Workers() { stop(); }

void Workers::schedule(std::shared_ptr<Avatar> a) {
  if (inline_) {  // no threads: run on the caller's (network) thread
    while (a->process_one()) {
    }
    return;
  }
  {
    std::lock_guard lock(mu_);
    ready_.push_back(std::move(a));
  }
  cv_.notify_one();
}

void Workers::stop() {
  {
    std::lock_guard lock(mu_);
    if (stopping_ && threads_.empty()) return;
    stopping_ = true;
  }
  cv_.notify_all();
  for (auto& t : threads_) t.join();
  threads_.clear();
}

void Workers::loop() {
  for (;;) {
    std::shared_ptr<Avatar> a;
    {
      std::unique_lock lock(mu_);
      cv_.wait(lock, [&] { return stopping_ || !ready_.empty(); });
      if (ready_.empty()) return;  // stopping and drained
      a = std::move(ready_.front());
      ready_.pop_front();
    }
    if (a->process_one()) schedule(std::move(a));
  }
}

void queue_for_client(std::deque<Outgoing>& out, std::size_t first, Outgoing o) {
  if (o.droppable) {
    int waiting = 0;
    for (const auto& x : out) waiting += x.droppable;
    if (waiting >= kMaxWaitingPoses && first <= out.size()) {
      const auto from = out.begin() + static_cast<std::ptrdiff_t>(first);
      auto victim = std::find_if(from, out.end(), [](const Outgoing& x) { return x.droppable && !x.restarted; });
      if (victim == out.end()) victim = std::find_if(from, out.end(), [](const Outgoing& x) { return x.droppable; });
      if (victim != out.end()) out.erase(victim);
    }
  }
  out.push_back(std::move(o));
}

}  // namespace legwork::serve
