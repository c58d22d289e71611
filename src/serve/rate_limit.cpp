// The per-session frame rate limit (see rate_limit.hpp).
#include <legwork/serve/rate_limit.hpp>

#include <algorithm>
#include <cmath>

namespace legwork::serve {

RateLimiter::RateLimiter(double max_rate_hz, Clock::time_point start)
    : rate_(max_rate_hz),
      stream_burst_(std::max(kMinBurst, max_rate_hz * kStreamBurstSeconds)),
      ceiling_burst_(std::max(kMinBurst, max_rate_hz * kCeilingBurstSeconds)),
      stream_tokens_(stream_burst_),
      ceiling_tokens_(ceiling_burst_),
      last_now_(start) {}

RateVerdict RateLimiter::admit(double t, Clock::time_point now) {
  // Stream time: only forward steps refill (a jump back gives nothing; the
  // avatar's clock decides whether the stream restarted).
  if (std::isfinite(t)) {
    if (have_time_ && t > last_t_) stream_tokens_ = std::min(stream_burst_, stream_tokens_ + (t - last_t_) * rate_);
    last_t_ = t;
    have_time_ = true;
  }
  if (now > last_now_) {
    const double wall = std::chrono::duration<double>(now - last_now_).count();
    ceiling_tokens_ = std::min(ceiling_burst_, ceiling_tokens_ + wall * rate_ * kCeilingFactor);
    last_now_ = now;
  }
  if (ceiling_tokens_ < 1) return RateVerdict::TooFastForTheClock;
  if (stream_tokens_ < 1) return RateVerdict::TooFastForItsTime;
  stream_tokens_ -= 1;
  ceiling_tokens_ -= 1;
  return RateVerdict::Accept;
}

}  // namespace legwork::serve
