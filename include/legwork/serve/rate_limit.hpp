#pragma once
// Per-session frame rate limit of `legwork serve` (docs/protocol.md, "Rate").
//
// Two token buckets, both must allow a frame:
//  - the stream bucket refills by the frames' own timestamps: a client may send
//    at most `max_rate_hz` of *its* time, with a burst of a quarter second. A
//    backlog of honest frames that arrives together (a network hiccup, or the
//    server's own thread stalled while they waited in the socket) passes,
//    because their timestamps are as far apart as when they were sent.
//  - the wall-clock ceiling refills by the server's clock at twice
//    `max_rate_hz` with a burst of two seconds of `max_rate_hz`: a client whose
//    timestamps lie (jumping ahead, or back and forth) is still bounded, and a
//    stall of up to about two seconds is absorbed.
// Frames that are dropped still advance the stream's time: a client sending at
// 200 Hz of its time keeps 120 Hz of its newest frames.
#include <chrono>

namespace legwork::serve {

enum class RateVerdict {
  Accept,
  TooFastForItsTime,   // above max_rate_hz by the frames' own timestamps
  TooFastForTheClock,  // above the wall-clock ceiling (timestamps not believable)
};

class RateLimiter {
 public:
  using Clock = std::chrono::steady_clock;

  static constexpr double kStreamBurstSeconds = 0.25;  // of max_rate_hz, at least kMinBurst frames
  static constexpr double kCeilingFactor = 2.0;       // wall-clock ceiling = 2 x max_rate_hz
  static constexpr double kCeilingBurstSeconds = 2.0; // of max_rate_hz
  static constexpr double kMinBurst = 4.0;

  // max_rate_hz > 0 (the server checks --max-rate). `start` = when the session began.
  RateLimiter(double max_rate_hz, Clock::time_point start);

  // One arriving frame with timestamp t (seconds, the frame's own time) at
  // server time `now`: Accept consumes a token from both buckets.
  RateVerdict admit(double t, Clock::time_point now);

  double max_rate_hz() const { return rate_; }
  double ceiling_hz() const { return rate_ * kCeilingFactor; }

 private:
  double rate_;
  double stream_burst_, ceiling_burst_;
  double stream_tokens_, ceiling_tokens_;
  bool have_time_ = false;
  double last_t_ = 0;
  Clock::time_point last_now_;
};

}  // namespace legwork::serve
