#pragma once
// VMC input decoding (private to legwork serve; fuzz/vmc_fuzz.cpp uses it
// too): OSC device messages /VMC/Ext/Hmd/Pos, /VMC/Ext/Con/Pos and
// /VMC/Ext/Tra/Pos (serial, position xyz, quaternion xyzw; float or double;
// Unity's frame) -> the latest pose per device -> one TrackerFrame per tick.
// Malformed messages (too few or mistyped arguments, non-finite numbers) are
// ignored; positions beyond kMaxCoordinate and zero quaternions count as lost
// tracking (usable() is false), never as a pose.
#include <legwork/core/tracker.hpp>

#include <chrono>
#include <map>
#include <string>

namespace legwork::serve {

struct VmcInput {
  struct Track {
    DevicePose pose;
    double heard = -1;  // seconds (t0-relative) of the last message
  };
  std::string left_serial, right_serial;  // --vmc-left / --vmc-right: controllers by serial
  Track head;
  std::map<std::string, Track> controllers, trackers;
  std::map<std::string, int> side;  // serial -> kLeft / kRight (controllers and trackers)
  bool fresh = false;
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();

  double now() const;
  // Registers the device paths on a liblo server (`lo_server`), this object as their user data.
  void listen(void* lo_server);
  // One device message (what liblo's handler receives).
  void on(const char* path, const std::string& serial, const Vec3& unity_position, const Quat& unity_rotation);
  // The frame to feed the avatar, if a message arrived since the last one and the headset is tracking.
  bool frame(TrackerFrame& f);

 private:
  int side_of(const Vec3& p) const;
  int assign(const std::string& serial, const Vec3& p, bool controller);
};

}  // namespace legwork::serve
