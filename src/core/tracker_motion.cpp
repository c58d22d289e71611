// Motion -> tracker frames (offline helper; see tracker.hpp).
#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/motion.hpp>
#include <legwork/core/tracker.hpp>

#include <string>

namespace legwork {

std::vector<TrackerFrame> tracker_frames_from_motion(const Motion& m, double rate, std::size_t max_frames) {
  if (!std::isfinite(rate) || rate < 0 || rate > 10'000)
    throw Error("tracker frames: rate must be 0 (the motion's own) or in (0, 10000] Hz, got " + std::to_string(rate));
  const auto& r = m.skeleton.roles;
  const Role roles[kDeviceCount] = {Role::Head, Role::LeftHand, Role::RightHand, Role::LeftAnkle, Role::RightAnkle};
  double n_real = rate > 0 ? std::floor(m.duration() * rate + 1e-9) + 1 : m.frame_count();
  if (m.frame_count() == 0) n_real = 0;
  if (!(n_real <= static_cast<double>(max_frames)))
    throw Error("tracker frames: " + std::to_string(n_real) + " frames at " + std::to_string(rate) + " Hz exceed the limit of " +
                std::to_string(max_frames));
  const auto n = static_cast<std::size_t>(n_real);
  std::vector<TrackerFrame> out(n);
  std::vector<Transform> model(static_cast<std::size_t>(m.joint_count()));
  Pose pose(m.skeleton);
  for (std::size_t i = 0; i < n; ++i) {
    auto& f = out[i];
    if (rate > 0) {
      f.time = static_cast<double>(i) / rate;
      sample_motion(m, f.time, pose.ref());
      forward_kinematics(m.skeleton, pose, model);
    } else {
      f.time = static_cast<double>(i) / m.fps;
      forward_kinematics(m.skeleton, m.frame(static_cast<int>(i)), model);
    }
    for (int d = 0; d < kDeviceCount; ++d) {
      if (!r.has(roles[d])) continue;
      const auto& t = model[static_cast<std::size_t>(r[roles[d]])];
      f.devices[static_cast<std::size_t>(d)] = {t.translation, t.rotation, true};
    }
  }
  return out;
}

}  // namespace legwork
