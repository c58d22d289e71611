#pragma once
// The per-frame contract shared by every legwork runtime (accent, wip, ik,
// walkcycle's walker):
//
//   Model  - immutable, built offline by make_model(...) (may allocate and
//            throw legwork::Error); shareable across threads and avatars.
//   State  - one per avatar, built from a Model (State(model)); holds only
//            what the avatar remembers between frames, never settings or inputs.
//   update(model, frame, state, out[, info]) -> UpdateStatus
//            one TrackerFrame in, one pose out; never allocates, throws or
//            does I/O. A frame with a non-finite, absurd or non-increasing
//            time is Rejected: state and output are left as they were.
//
// TrackerFrame is the one input type: absolute time in seconds plus up to five
// tracked devices (head, two hands, two feet/ankles), each with its own
// validity flag, in legwork's world frame (metres, right-handed, y up, the
// user faces +z at heading 0, +x is the user's left).
#include <legwork/core/types.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace legwork {

// Side indices used by every module: 0 = left, 1 = right.
inline constexpr int kLeft = 0;
inline constexpr int kRight = 1;

// Devices of a TrackerFrame, in storage order.
enum class Device : std::uint8_t { Head = 0, LeftHand = 1, RightHand = 2, LeftFoot = 3, RightFoot = 4 };
inline constexpr int kDeviceCount = 5;
const char* device_name(Device d);  // "head", "left_hand", ... (the tracker CSV point names)

// One tracked device this frame. Position and rotation are world-space.
// Head: the head joint (between the eyes is the app's offset to remove);
// identity rotation looks along +z with y up. Hands: the wrists (a
// controller-to-wrist offset is the app's). Feet: the ankles.
struct DevicePose {
  Vec3 position = Vec3::Zero();      // metres, world
  Quat rotation = Quat::Identity();  // world
  bool valid = false;                // false: not tracked this frame; position/rotation ignored
};

// Largest coordinate (metres) a usable device sample may have; beyond it the
// sample is treated as lost tracking (a finite 1e30 must not poison filters).
inline constexpr double kMaxCoordinate = 1.0e4;

// True when the device is valid, finite, within kMaxCoordinate and its
// rotation is a usable (non-degenerate) quaternion.
bool usable(const DevicePose& d);

struct TrackerFrame {
  double time = 0;  // absolute seconds of the stream's clock, strictly increasing
  std::array<DevicePose, kDeviceCount> devices{};

  DevicePose& operator[](Device d) { return devices[static_cast<std::size_t>(d)]; }
  const DevicePose& operator[](Device d) const { return devices[static_cast<std::size_t>(d)]; }
  DevicePose& head() { return (*this)[Device::Head]; }
  const DevicePose& head() const { return (*this)[Device::Head]; }
  // side: kLeft or kRight.
  DevicePose& hand(int side) { return devices[static_cast<std::size_t>(1 + side)]; }
  const DevicePose& hand(int side) const { return devices[static_cast<std::size_t>(1 + side)]; }
  DevicePose& foot(int side) { return devices[static_cast<std::size_t>(3 + side)]; }
  const DevicePose& foot(int side) const { return devices[static_cast<std::size_t>(3 + side)]; }
};

// What one update() did with its frame.
enum class UpdateStatus : std::uint8_t {
  Ok,        // consumed; every device the runtime needs was usable
  Degraded,  // consumed; some device it needs was missing or unusable (held / faded)
  Rejected,  // not consumed: time not finite, absurd or not after the last frame; nothing changed
  Restarted, // the stream's clock restarted (see FrameClock); the avatar was reset and the frame consumed
};
const char* status_name(UpdateStatus s);

// The time rules every runtime applies, in one place.
//  - A time that is not finite or whose magnitude exceeds kMaxTime is rejected.
//  - The first accepted frame starts the clock (dt = 0).
//  - A time at or before the last accepted one is rejected...
//  - ...unless kRestartFrames such frames in a row are themselves increasing:
//    the source's clock restarted (or the last accepted time was a bogus
//    far-future spike), so the stream restarts from the newest frame. One bad
//    timestamp therefore never freezes a stream for good.
//  - A forward gap longer than kMaxGap seconds restarts the stream as well
//    (filters must not integrate across minutes of missing data).
class FrameClock {
 public:
  static constexpr double kMaxTime = 1.0e9;  // seconds (~31 years of stream clock)
  static constexpr double kMaxGap = 5.0;     // seconds
  static constexpr int kRestartFrames = 8;

  enum class Verdict : std::uint8_t { Accept, Reject, Restart };
  struct Step {
    Verdict verdict = Verdict::Reject;
    double dt = 0;  // seconds since the last accepted frame (0 on the first and on a restart)
  };

  // Classifies `time`, and on Accept/Restart makes it the last accepted time.
  Step advance(double time);
  void reset();
  bool started() const { return started_; }
  double last_time() const { return last_; }

 private:
  double last_ = 0;
  bool started_ = false;
  double pending_last_ = 0;  // newest of the rejected-but-increasing run
  int pending_ = 0;          // length of that run
};

}  // namespace legwork

// ---- offline helpers (allocate, may throw) -------------------------------

namespace legwork {
class Motion;

// Tracker frames from a motion's joints acting as the devices: head = the
// Head joint (model position and rotation), hands = the wrist joints, feet =
// the ankle joints; a device whose role the skeleton lacks stays invalid.
// rate = 0: one frame per motion frame (time = frame / fps); rate > 0: the
// motion sampled at that rate over its duration (interpolated). Throws
// legwork::Error for a non-positive or absurd rate or an output over
// max_frames frames.
std::vector<TrackerFrame> tracker_frames_from_motion(const Motion& m, double rate = 0, std::size_t max_frames = 50'000'000);

}  // namespace legwork
