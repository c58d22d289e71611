#pragma once
// Conversions at the boundary to game engines, and humanoid bone names.
//
// legwork: metres, right-handed, y up, the character faces +z, +x is its left.
//   Unity:  metres, left-handed, y up, faces +z, +x is its right:
//           p = (-x, y, z);          q = (w, x, -y, -z)
//   Unreal: centimetres, left-handed, z up, faces +x, +y is its right:
//           p = 100 (z, -x, y);      q = (w, -qz, qx, -qy)
//   Godot:  metres, right-handed, y up, faces -z, +x is its right:
//           p = (-x, y, -z);         q = (w, -qx, qy, -qz)
// Rotations: a quaternion's vector part is an axial vector, so under a
// reflection M (det -1: Unity, Unreal) it maps to -M v; under a rotation
// (Godot) to M v; w is unchanged. Positions and rotations converted this way
// compose: convert(q) * convert(p) == convert(q * p) (tested).
#include <legwork/core/skeleton.hpp>

#include <string_view>

namespace legwork {

enum class Engine : int { Legwork = 0, Unity = 1, Unreal = 2, Godot = 3 };

Vec3 to_engine(Engine e, const Vec3& p);
Quat to_engine(Engine e, const Quat& q);
Vec3 from_engine(Engine e, const Vec3& p);
Quat from_engine(Engine e, const Quat& q);
// "legwork", "unity", "unreal", "godot"; parse returns false for other names.
std::string_view engine_name(Engine e);
bool parse_engine(std::string_view name, Engine& out);

// Humanoid bone names of a joint role: Unity's HumanBodyBones ("Hips",
// "LeftUpperArm", ...; also the VMC protocol's bone names) or VRM 0.x/1.0
// humanoid names ("hips", "leftUpperArm", ...).
enum class Humanoid : int { Unity = 0, Vrm = 1 };
std::string_view humanoid_bone(Role r, Humanoid naming = Humanoid::Unity);

}  // namespace legwork
