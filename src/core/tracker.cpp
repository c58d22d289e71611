// The shared per-frame input and time rules (see tracker.hpp).
#include <legwork/core/tracker.hpp>

namespace legwork {

const char* device_name(Device d) {
  switch (d) {
    case Device::Head: return "head";
    case Device::LeftHand: return "left_hand";
    case Device::RightHand: return "right_hand";
    case Device::LeftFoot: return "left_foot";
    case Device::RightFoot: return "right_foot";
  }
  return "?";
}

bool usable(const DevicePose& d) {
  if (!d.valid) return false;
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(d.position[i]) || std::abs(d.position[i]) > kMaxCoordinate) return false;
  const auto& c = d.rotation.coeffs();
  for (int i = 0; i < 4; ++i)
    if (!std::isfinite(c[i])) return false;
  const double n = c.squaredNorm();
  return n > 1e-6 && n < 1e6;
}

const char* status_name(UpdateStatus s) {
  switch (s) {
    case UpdateStatus::Ok: return "ok";
    case UpdateStatus::Degraded: return "degraded";
    case UpdateStatus::Rejected: return "rejected";
    case UpdateStatus::Restarted: return "restarted";
  }
  return "?";
}

FrameClock::Step FrameClock::advance(double time) {
  if (!std::isfinite(time) || std::abs(time) > kMaxTime) return {Verdict::Reject, 0};
  if (!started_) {
    started_ = true;
    last_ = time;
    pending_ = 0;
    return {Verdict::Accept, 0};
  }
  if (time > last_) {
    const double dt = time - last_;
    last_ = time;
    pending_ = 0;
    if (dt > kMaxGap) return {Verdict::Restart, 0};
    return {Verdict::Accept, dt};
  }
  // At or before the last accepted time: count a run of increasing rejects.
  if (pending_ > 0 && time > pending_last_) {
    ++pending_;
  } else {
    pending_ = 1;
  }
  pending_last_ = time;
  if (pending_ >= kRestartFrames) {
    last_ = time;
    pending_ = 0;
    return {Verdict::Restart, 0};
  }
  return {Verdict::Reject, 0};
}

void FrameClock::reset() {
  started_ = false;
  last_ = 0;
  pending_ = 0;
  pending_last_ = 0;
}

}  // namespace legwork
