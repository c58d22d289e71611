#pragma once
// Basic math types shared by every legwork module.
// Conventions everywhere: metres, seconds, right-handed, y up, the character
// faces +z and +x points to the character's left (glTF's convention).
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <stdexcept>
#include <string>

namespace legwork {

using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;

// A rigid transform: rotate, then translate. Used for model-space joint frames.
struct Transform {
  Quat rotation = Quat::Identity();
  Vec3 translation = Vec3::Zero();

  Vec3 apply(const Vec3& p) const { return rotation * p + translation; }
  Transform operator*(const Transform& child) const {
    return {rotation * child.rotation, rotation * child.translation + translation};
  }
};

// Thrown by offline code (file I/O, builders, CLI) with a message that names
// the file, line or field at fault. Per-frame runtime code never throws.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

constexpr double kPi = 3.14159265358979323846;
inline double deg2rad(double d) { return d * kPi / 180.0; }
inline double rad2deg(double r) { return r * 180.0 / kPi; }

}  // namespace legwork
