// legwork.core: TrackerFrame, Device, UpdateStatus, tracker frames from arrays.
#include "bindings.hpp"

#include <cmath>

namespace legwork::py {
namespace {
namespace tracker_binding {

using namespace pybind11::literals;

bool finite_row(const double* p, int n) {
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(p[i])) return false;
  return true;
}

void set_device(TrackerFrame& f, Device d, const pb::handle& position, const pb::handle& rotation, bool valid) {
  const Array p = require_array(position, "position", {3}, "(3,) metres", false);
  DevicePose& dev = f[d];
  dev.position = Vec3(p.at(0), p.at(1), p.at(2));
  dev.rotation = Quat::Identity();
  if (!rotation.is_none()) {
    const Array r = require_array(rotation, "rotation", {4}, "(4,) w,x,y,z", false);
    dev.rotation = Quat(r.at(0), r.at(1), r.at(2), r.at(3));
  }
  dev.valid = valid;
}

pb::tuple get_device(const TrackerFrame& f, Device d) {
  const DevicePose& dev = f[d];
  Array p = new_array({3});
  Array r = new_array({4});
  for (int i = 0; i < 3; ++i) p.mutable_data()[i] = dev.position[i];
  quats_to_wxyz({&dev.rotation, 1}, r.mutable_data());
  return pb::make_tuple(p, r, dev.valid);
}

// Fills device d of every frame from (frames, 3) positions and optional (frames, 4) rotations.
void fill_device(std::vector<TrackerFrame>& frames, Device d, const pb::handle& pos, const pb::handle& rot, const char* pos_name,
                 const char* rot_name) {
  if (pos.is_none()) return;
  const auto n = static_cast<pb::ssize_t>(frames.size());
  const Array p = require_array(pos, pos_name, {n, 3}, "(frames, 3) metres, frames as head_position", false);
  const bool has_rot = !rot.is_none();
  Array r;
  if (has_rot) r = require_array(rot, rot_name, {n, 4}, "(frames, 4) w,x,y,z, frames as head_position", false);
  for (pb::ssize_t i = 0; i < n; ++i) {
    DevicePose& dev = frames[static_cast<std::size_t>(i)][d];
    const double* pi = p.data() + 3 * i;
    dev.position = Vec3(pi[0], pi[1], pi[2]);
    dev.valid = finite_row(pi, 3);
    if (has_rot) {
      const double* ri = r.data() + 4 * i;
      dev.rotation = Quat(ri[0], ri[1], ri[2], ri[3]);
      dev.valid = dev.valid && finite_row(ri, 4);
    }
  }
}

}  // namespace tracker_binding
}  // namespace

std::vector<TrackerFrame> frames_from_arrays(double fps, const pb::handle& head_position, const pb::handle& head_rotation,
                                             const pb::handle& left_hand, const pb::handle& right_hand,
                                             const pb::handle& left_foot, const pb::handle& right_foot, double start_time) {
  using namespace tracker_binding;  // its helpers and the module names they use
  require_rate(fps, "fps");
  if (!std::isfinite(start_time)) value_error("start_time: expected a finite time in seconds");
  const Array h = require_array(head_position, "head_position", {kAny, 3}, "(frames, 3) metres", false);
  std::vector<TrackerFrame> frames(static_cast<std::size_t>(h.shape(0)));
  for (std::size_t i = 0; i < frames.size(); ++i) frames[i].time = start_time + static_cast<double>(i) / fps;
  fill_device(frames, Device::Head, head_position, head_rotation, "head_position", "head_rotation");
  fill_device(frames, Device::LeftHand, left_hand, pb::none(), "left_hand", "");
  fill_device(frames, Device::RightHand, right_hand, pb::none(), "right_hand", "");
  fill_device(frames, Device::LeftFoot, left_foot, pb::none(), "left_foot", "");
  fill_device(frames, Device::RightFoot, right_foot, pb::none(), "right_foot", "");
  return frames;
}

void bind_tracker(pb::module_& m) {
  using namespace tracker_binding;  // its helpers and the module names they use
  pb::enum_<Device>(m, "Device", "Tracked devices of a TrackerFrame.")
      .value("Head", Device::Head)
      .value("LeftHand", Device::LeftHand)
      .value("RightHand", Device::RightHand)
      .value("LeftFoot", Device::LeftFoot)
      .value("RightFoot", Device::RightFoot);
  pb::enum_<UpdateStatus>(m, "UpdateStatus", "What one update() did with its frame.")
      .value("Ok", UpdateStatus::Ok)
      .value("Degraded", UpdateStatus::Degraded)
      .value("Rejected", UpdateStatus::Rejected)
      .value("Restarted", UpdateStatus::Restarted);
  pb::class_<TrackerFrame>(m, "TrackerFrame",
                           "One frame of tracker input: absolute time (s) and five devices (world position metres, "
                           "rotation w,x,y,z, valid flag) in legwork's frame (right-handed, y up, faces +z).")
      .def(pb::init([](double t) {
             TrackerFrame f;
             f.time = t;
             return f;
           }),
           "time"_a = 0.0)
      .def_readwrite("time", &TrackerFrame::time, "absolute seconds, strictly increasing")
      .def("set", &set_device, "device"_a, "position"_a, "rotation"_a = pb::none(), "valid"_a = true,
           "Sets a device: position float64 (3,) metres, rotation float64 (4,) w,x,y,z (None = identity). "
           "NaN/inf values are passed on: the runtime treats them as lost tracking.")
      .def("get", &get_device, "device"_a, "(position (3,), rotation (4,) w,x,y,z, valid) of a device");
  m.def("tracker_frames", &frames_from_arrays, "fps"_a, "head_position"_a, "head_rotation"_a, "left_hand"_a, "right_hand"_a,
        "left_foot"_a = pb::none(), "right_foot"_a = pb::none(), "start_time"_a = 0.0,
        "List of TrackerFrame at time start_time + i / fps from float64 arrays: head_position (frames, 3) metres, "
        "head_rotation (frames, 4) w,x,y,z, hands/feet (frames, 3) metres (None = not tracked). A row with NaN "
        "marks that device as lost for that frame.");
  m.def("tracker_frames_from_motion", &tracker_frames_from_motion, "motion"_a, "rate"_a = 0.0, "max_frames"_a = 50'000'000,
        "Tracker frames from a motion's head, wrists and ankles (rate 0 = one per motion frame, time = frame / fps).");
  m.def(
      "usable", [](const TrackerFrame& f, Device d) { return usable(f[d]); }, "frame"_a, "device"_a,
      "True when the device is valid, finite, within 10 km and has a usable rotation.");
}

}  // namespace legwork::py
