// legwork.core: Skeleton, Pose, Motion, FK, resampling, mirroring, tracker frames.
#include "bindings.hpp"

#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/core/mirror.hpp>

#include <cmath>

namespace legwork::py {
namespace {
namespace core_binding {

using namespace pybind11::literals;

pb::array_t<int> int_array(const std::vector<int>& v) {
  pb::array_t<int> a(static_cast<pb::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

Skeleton make_skeleton(const std::vector<std::string>& names, const std::vector<int>& parents, const pb::handle& offsets) {
  const auto n = static_cast<pb::ssize_t>(names.size());
  if (static_cast<pb::ssize_t>(parents.size()) != n)
    value_error("parents: expected " + std::to_string(n) + " entries (one per name), got " + std::to_string(parents.size()));
  const Array off = require_array(offsets, "offsets", {n, 3}, "(joints, 3)");
  Skeleton s;
  for (pb::ssize_t j = 0; j < n; ++j) {
    const int p = parents[static_cast<std::size_t>(j)];
    if (p >= j || p < -1 || (j == 0) != (p == -1))
      value_error("parents: joint " + std::to_string(j) + " ('" + names[static_cast<std::size_t>(j)] + "') has parent " +
                  std::to_string(p) + "; expected -1 for joint 0 and a smaller index otherwise (depth-first order)");
    s.add_joint(names[static_cast<std::size_t>(j)], p, Vec3(off.at(j, 0), off.at(j, 1), off.at(j, 2)));
  }
  s.validate();
  resolve_roles(s);
  return s;
}

pb::dict role_dict(const Skeleton& s) {
  pb::dict d;
  for (int r = 0; r < kRoleCount; ++r)
    if (s.roles.has(static_cast<Role>(r))) d[pb::str(std::string(role_name(static_cast<Role>(r))))] = s.roles[static_cast<Role>(r)];
  return d;
}

void bind_skeleton(pb::module_& m) {
  pb::class_<Skeleton>(m, "Skeleton",
                       "Joint hierarchy: names, parents (depth-first, root -1), rest offsets (metres, parent frame), roles.")
      .def(pb::init(&make_skeleton), "names"_a, "parents"_a, "offsets"_a,
           "Skeleton(names: list[str], parents: list[int], offsets: float64 (joints, 3) metres); roles resolved from names.")
      .def_property_readonly("names", [](const Skeleton& s) { return s.names; }, "joint names, list[str]")
      .def_property_readonly("parents", [](const Skeleton& s) { return int_array(s.parents); }, "int32 (joints,), -1 for the root")
      .def_property_readonly(
          "offsets",
          [](const pb::object& self) {
            const auto& s = self.cast<const Skeleton&>();
            return view(s.rest_offsets.empty() ? nullptr : s.rest_offsets.front().data(), {s.joint_count(), 3}, self, false);
          },
          "rest offsets, float64 (joints, 3), metres in the parent's frame (read-only view)")
      .def_property_readonly("roles", &role_dict, "dict role name ('pelvis', 'left_hand', ...) -> joint index (resolved roles only)")
      .def_property_readonly("mirror", [](const Skeleton& s) { return int_array(s.mirror); }, "int32 (joints,): left/right counterpart")
      .def_property_readonly("joint_count", &Skeleton::joint_count)
      .def("__len__", &Skeleton::joint_count)
      .def("find", [](const Skeleton& s, const std::string& n) { return s.find(n); }, "name"_a, "index of a joint by name, or -1")
      .def("children", &Skeleton::children, "joint"_a)
      .def("__repr__", [](const Skeleton& s) { return "<legwork.core.Skeleton " + std::to_string(s.joint_count()) + " joints>"; });
  m.def(
      "measure_body",
      [](const Skeleton& s) {
        const BodyMeasures b = measure_body(s);
        return pb::dict("standing_height"_a = b.standing_height, "hip_height"_a = b.hip_height, "leg_length"_a = b.leg_length,
                        "arm_length"_a = b.arm_length);
      },
      "skeleton"_a, "Rest-pose body measures in metres: standing_height, hip_height, leg_length, arm_length.");
}

// Rotations (frames, joints, 4) wxyz + translations (frames, joints, 3) -> Motion.
Motion make_motion(const Skeleton& skel, double fps, const pb::handle& rotations, const pb::handle& translations) {
  require_rate(fps, "fps");
  const pb::ssize_t j = skel.joint_count();
  const Array r = require_array(rotations, "rotations", {kAny, j, 4}, "(frames, joints, 4) wxyz");
  const Array t = require_array(translations, "translations", {r.shape(0), j, 3}, "(frames, joints, 3) metres, same frames as rotations");
  Motion m(skel, fps, static_cast<int>(r.shape(0)));
  wxyz_to_quats(r.data(), m.all_rotations());
  for (Quat& q : m.all_rotations()) {
    const double n = q.norm();
    if (n < 1e-9) value_error("rotations: a quaternion has zero length (expected unit quaternions w, x, y, z)");
    if (std::abs(n - 1.0) > 1e-12) q.normalize();  // unit input is kept bit for bit
  }
  std::copy(t.data(), t.data() + t.size(), m.all_translations().front().data());
  return m;
}

Array motion_rotations(const Motion& m) {
  Array a = new_array({m.frame_count(), m.joint_count(), 4});
  quats_to_wxyz(m.all_rotations(), a.mutable_data());
  return a;
}

// (positions (frames, joints, 3), rotations (frames, joints, 4) wxyz), model space.
pb::tuple motion_fk(const Motion& m) {
  std::vector<Transform> tf(static_cast<std::size_t>(m.frame_count()) * static_cast<std::size_t>(m.joint_count()));
  forward_kinematics(m, tf);
  Array pos = new_array({m.frame_count(), m.joint_count(), 3});
  Array rot = new_array({m.frame_count(), m.joint_count(), 4});
  double* p = pos.mutable_data();
  double* r = rot.mutable_data();
  for (const Transform& x : tf) {
    for (int i = 0; i < 3; ++i) *p++ = x.translation[i];
    quats_to_wxyz({&x.rotation, 1}, r);
    r += 4;
  }
  return pb::make_tuple(pos, rot);
}

Array motion_positions(const Motion& m) {
  Array pos = new_array({m.frame_count(), m.joint_count(), 3});
  forward_positions(m, {reinterpret_cast<Vec3*>(pos.mutable_data()), static_cast<std::size_t>(pos.size() / 3)});
  return pos;
}

void bind_motion(pb::module_& m) {
  pb::class_<Motion>(m, "Motion", "A sampled motion: skeleton, frame rate (Hz) and frames of local joint rotations/translations.")
      .def(pb::init(&make_motion), "skeleton"_a, "fps"_a, "rotations"_a, "translations"_a,
           "Motion(skeleton, fps: Hz, rotations: float64 (frames, joints, 4) local w,x,y,z, translations: float64 "
           "(frames, joints, 3) local metres; the root's is its world position)")
      .def_readonly("skeleton", &Motion::skeleton)
      .def_readonly("fps", &Motion::fps, "frames per second (Hz)")
      .def_property_readonly("frame_count", &Motion::frame_count)
      .def_property_readonly("joint_count", &Motion::joint_count)
      .def_property_readonly("duration", &Motion::duration, "seconds from the first to the last frame")
      .def_property_readonly("rotations", &motion_rotations, "local rotations, float64 (frames, joints, 4) w,x,y,z (a copy)")
      .def_property_readonly(
          "translations",
          [](const pb::object& self) {
            auto& mo = self.cast<Motion&>();
            return view(mo.all_translations().empty() ? nullptr : mo.all_translations().front().data(),
                        {mo.frame_count(), mo.joint_count(), 3}, self, true);
          },
          "local translations, float64 (frames, joints, 3) metres; a writable view into the motion (no copy)")
      .def("positions", &motion_positions, "model-space joint positions, float64 (frames, joints, 3) metres (FK)")
      .def("__len__", &Motion::frame_count)
      .def("__repr__", [](const Motion& mo) {
        return "<legwork.core.Motion " + std::to_string(mo.frame_count()) + " frames x " + std::to_string(mo.joint_count()) +
               " joints at " + std::to_string(mo.fps) + " Hz>";
      });
  m.def("forward_kinematics", &motion_fk, "motion"_a,
        "Model-space (positions float64 (frames, joints, 3) metres, rotations float64 (frames, joints, 4) w,x,y,z).");
  m.def("joint_positions", &motion_positions, "motion"_a, "Model-space joint positions, float64 (frames, joints, 3) metres.");
  m.def(
      "resample", [](const Motion& mo, double fps) { require_rate(fps, "fps"); return resample(mo, fps); }, "motion"_a, "fps"_a,
      "The motion at `fps` Hz, same duration (slerp rotations, lerp translations).");
  m.def("trim", &trim, "motion"_a, "first"_a, "last"_a, "Frames [first, last] inclusive; legwork.Error if out of range.");
  m.def("concatenate", &concatenate, "a"_a, "b"_a, "b appended after a (same joints and fps).");
  m.def("mirror_motion", &mirror_motion, "motion"_a, "Mirrored about the sagittal plane (x -> -x), left/right joints swapped.");
}

void bind_pose(pb::module_& m) {
  pb::class_<Pose>(m, "Pose", "One pose: local rotations (joints, 4) w,x,y,z and local translations (joints, 3) metres.")
      .def(pb::init<const Skeleton&>(), "skeleton"_a, "The rest pose of `skeleton`.")
      .def_property(
          "rotations",
          [](const Pose& p) {
            Array a = new_array({p.joint_count(), 4});
            quats_to_wxyz(p.rotations, a.mutable_data());
            return a;
          },
          [](Pose& p, const pb::handle& a) {
            const Array r = require_array(a, "rotations", {p.joint_count(), 4}, "(joints, 4) w,x,y,z");
            wxyz_to_quats(r.data(), p.rotations);
          },
          "local rotations, float64 (joints, 4) w,x,y,z (a copy; assign to set)")
      .def_property_readonly(
          "translations",
          [](const pb::object& self) {
            auto& p = self.cast<Pose&>();
            return view(p.translations.empty() ? nullptr : p.translations.front().data(), {p.joint_count(), 3}, self, true);
          },
          "local translations, float64 (joints, 3) metres (the root's = world position); a writable view")
      .def(
          "positions",
          [](const Pose& p, const Skeleton& s) {
            if (s.joint_count() != p.joint_count()) value_error("skeleton: has " + std::to_string(s.joint_count()) + " joints, the pose " + std::to_string(p.joint_count()));
            // forward_kinematics (not forward_positions), as the C API's lw_avatar_pose: bit-identical figures.
            std::vector<Transform> tf(static_cast<std::size_t>(p.joint_count()));
            forward_kinematics(s, p.ref(), tf);
            Array a = new_array({p.joint_count(), 3});
            double* o = a.mutable_data();
            for (const Transform& x : tf)
              for (int i = 0; i < 3; ++i) *o++ = x.translation[i];
            return a;
          },
          "skeleton"_a, "model-space joint positions, float64 (joints, 3) metres")
      .def_property_readonly("joint_count", &Pose::joint_count);
}

}  // namespace core_binding
}  // namespace

void bind_core(pb::module_& m) {
  using namespace core_binding;  // its helpers and the module names they use
  bind_skeleton(m);
  bind_motion(m);
  bind_pose(m);
  bind_tracker(m);
}

}  // namespace legwork::py
