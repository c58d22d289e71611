// Engine frame conversions and humanoid bone names (see engine.hpp).
#include <legwork/core/engine.hpp>

#include <array>

namespace legwork {

Vec3 to_engine(Engine e, const Vec3& p) {
  switch (e) {
    case Engine::Legwork: return p;
    case Engine::Unity: return {-p.x(), p.y(), p.z()};
    case Engine::Unreal: return 100.0 * Vec3(p.z(), -p.x(), p.y());
    case Engine::Godot: return {-p.x(), p.y(), -p.z()};
  }
  return p;
}

Quat to_engine(Engine e, const Quat& q) {
  switch (e) {
    case Engine::Legwork: return q;
    case Engine::Unity: return {q.w(), q.x(), -q.y(), -q.z()};
    case Engine::Unreal: return {q.w(), -q.z(), q.x(), -q.y()};
    case Engine::Godot: return {q.w(), -q.x(), q.y(), -q.z()};
  }
  return q;
}

Vec3 from_engine(Engine e, const Vec3& p) {
  switch (e) {
    case Engine::Legwork: return p;
    case Engine::Unity: return {-p.x(), p.y(), p.z()};
    case Engine::Unreal: return 0.01 * Vec3(-p.y(), p.z(), p.x());
    case Engine::Godot: return {-p.x(), p.y(), -p.z()};
  }
  return p;
}

Quat from_engine(Engine e, const Quat& q) {
  switch (e) {
    case Engine::Legwork: return q;
    case Engine::Unity: return {q.w(), q.x(), -q.y(), -q.z()};
    case Engine::Unreal: return {q.w(), q.y(), -q.z(), -q.x()};
    case Engine::Godot: return {q.w(), -q.x(), q.y(), -q.z()};
  }
  return q;
}

std::string_view engine_name(Engine e) {
  switch (e) {
    case Engine::Legwork: return "legwork";
    case Engine::Unity: return "unity";
    case Engine::Unreal: return "unreal";
    case Engine::Godot: return "godot";
  }
  return "?";
}

bool parse_engine(std::string_view name, Engine& out) {
  for (Engine e : {Engine::Legwork, Engine::Unity, Engine::Unreal, Engine::Godot})
    if (name == engine_name(e)) {
      out = e;
      return true;
    }
  return false;
}

std::string_view humanoid_bone(Role r, Humanoid naming) {
  static constexpr std::array<std::string_view, kRoleCount> unity = {
      "Hips",         "Spine",        "Chest",        "Neck",         "Head",         "LeftShoulder", "LeftUpperArm",
      "LeftLowerArm", "LeftHand",     "RightShoulder", "RightUpperArm", "RightLowerArm", "RightHand",  "LeftUpperLeg",
      "LeftLowerLeg", "LeftFoot",     "LeftToes",     "RightUpperLeg", "RightLowerLeg", "RightFoot",  "RightToes"};
  static constexpr std::array<std::string_view, kRoleCount> vrm = {
      "hips",         "spine",        "chest",        "neck",          "head",          "leftShoulder", "leftUpperArm",
      "leftLowerArm", "leftHand",     "rightShoulder", "rightUpperArm", "rightLowerArm", "rightHand",   "leftUpperLeg",
      "leftLowerLeg", "leftFoot",     "leftToes",     "rightUpperLeg", "rightLowerLeg", "rightFoot",   "rightToes"};
  const int i = static_cast<int>(r);
  if (i < 0 || i >= kRoleCount) return {};
  return naming == Humanoid::Vrm ? vrm[static_cast<std::size_t>(i)] : unity[static_cast<std::size_t>(i)];
}

}  // namespace legwork
