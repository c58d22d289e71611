#pragma once
// A two-joint BVH (root + spine with an End Site) whose header the reader and
// error tests share; each test appends its own two motion lines.
// Line numbers:  1 HIERARCHY, 2 ROOT, 4 OFFSET, 5 CHANNELS, 6 JOINT Spine,
// 8 OFFSET, 9 CHANNELS, 10 End Site, 12 OFFSET, 16 MOTION, 17 Frames,
// 18 Frame Time, 19-20 motion lines.
#include <legwork/io/bvh.hpp>

#include <string>

namespace legwork::testdata {
inline const std::string kTinyBvhHeader =
    "HIERARCHY\n"
    "ROOT Hips\n"
    "{\n"
    "  OFFSET 0 0 0\n"
    "  CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation\n"
    "  JOINT Spine\n"
    "  {\n"
    "    OFFSET 0 0.5 0\n"
    "    CHANNELS 3 Zrotation Yrotation Xrotation\n"
    "    End Site\n"
    "    {\n"
    "      OFFSET 0 0.5 0\n"
    "    }\n"
    "  }\n"
    "}\n"
    "MOTION\n"
    "Frames: 2\n"
    "Frame Time: 0.1\n";

// Reads the tiny file as metres: the toy skeleton is 1 m tall, so no unit guessing.
inline io::BvhReadOptions metres() {
  io::BvhReadOptions o;
  o.scale = 1.0;
  return o;
}
}  // namespace legwork::testdata
