// VMC input decoding (see vmc_input.hpp).
#include "vmc_input.hpp"

#include <legwork/core/engine.hpp>

#include <lo/lo.h>

#include <cmath>
#include <cstring>
#include <string_view>

namespace legwork::serve {

namespace {
constexpr double kStaleSeconds = 0.5;  // a device not heard from for this long counts as lost

// liblo's arguments point into the packet at 4-byte boundaries, but lo_arg
// (a union with 8-byte members) asks for 8: reading a->f or a->d there is
// undefined behaviour (UBSan: misaligned member access, found by
// fuzz/vmc_fuzz.cpp). The bytes are copied out instead.
double arg_number(char type, const void* a) {
  if (type == 'f') {
    float f;
    std::memcpy(&f, a, sizeof f);
    return f;
  }
  if (type == 'd') {
    double d;
    std::memcpy(&d, a, sizeof d);
    return d;
  }
  return NAN;
}

int on_device(const char* path, const char* types, lo_arg** argv, int argc, lo_message, void* user) {
  if (argc < 8 || types[0] != 's') return 0;
  double v[7];
  for (int i = 0; i < 7; ++i) {
    v[i] = arg_number(types[i + 1], static_cast<const void*>(argv[i + 1]));
    if (!std::isfinite(v[i])) return 0;  // a malformed sample is ignored
  }
  const char* serial = static_cast<const char*>(static_cast<const void*>(argv[0]));
  static_cast<VmcInput*>(user)->on(path, serial, Vec3(v[0], v[1], v[2]), Quat(v[6], v[3], v[4], v[5]));
  return 0;
}
}  // namespace

double VmcInput::now() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); }

void VmcInput::listen(void* server) {
  for (const char* p : {"/VMC/Ext/Hmd/Pos", "/VMC/Ext/Con/Pos", "/VMC/Ext/Tra/Pos"})
    lo_server_add_method(static_cast<lo_server>(server), p, nullptr, on_device, this);
}

// The side of a device at `p`, by where it is relative to the headset's heading.
int VmcInput::side_of(const Vec3& p) const {
  const Vec3 fwd = head.pose.rotation * Vec3::UnitZ();
  const double yaw = std::atan2(fwd.x(), fwd.z());
  const Vec3 d = p - head.pose.position;
  const double local_x = std::cos(yaw) * d.x() - std::sin(yaw) * d.z();  // +x = the user's left
  return local_x >= 0 ? kLeft : kRight;
}

int VmcInput::assign(const std::string& serial, const Vec3& p, bool controller) {
  if (controller && serial == left_serial) return kLeft;
  if (controller && serial == right_serial) return kRight;
  const auto it = side.find(serial);
  if (it != side.end()) return it->second;
  if (head.heard < 0) return -1;  // decided once the headset is tracking
  const int s = side_of(p);
  side[serial] = s;
  return s;
}

void VmcInput::on(const char* path, const std::string& serial, const Vec3& p, const Quat& q) {
  const std::string_view pth(path);
  Track t{DevicePose{from_engine(Engine::Unity, p), from_engine(Engine::Unity, q).normalized(), true}, now()};
  if (pth == "/VMC/Ext/Hmd/Pos") head = t;
  else if (pth == "/VMC/Ext/Con/Pos") controllers[serial] = t;
  else trackers[serial] = t;
  fresh = true;
}

bool VmcInput::frame(TrackerFrame& f) {
  const double t = now();
  if (!fresh || head.heard < 0) return false;
  fresh = false;
  f = TrackerFrame{};
  f.time = t;
  const auto live = [&](const Track& tr) { return tr.heard >= 0 && t - tr.heard < kStaleSeconds; };
  if (live(head)) f.head() = head.pose;
  for (auto& [serial, tr] : controllers) {
    const int s = assign(serial, tr.pose.position, true);
    if (s >= 0 && live(tr)) f.hand(s) = tr.pose;
  }
  for (auto& [serial, tr] : trackers) {
    const int s = assign(serial, tr.pose.position, false);
    if (s >= 0 && live(tr)) f.foot(s) = tr.pose;
  }
  return true;
}

}  // namespace legwork::serve
