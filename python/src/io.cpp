// legwork.io: BVH reading and writing (legwork.core.Motion <-> files).
#include "bindings.hpp"

#include <legwork/io/bvh.hpp>

namespace legwork::py {
namespace {
namespace io_binding {

using namespace pybind11::literals;

pb::dict report_dict(const io::BvhReport& r) {
  std::vector<std::string> missing;
  for (const Role role : r.missing_roles) missing.emplace_back(role_name(role));
  return pb::dict("scale"_a = r.scale, "scale_reason"_a = r.scale_reason, "declared_frames"_a = r.declared_frames,
                  "repaired_zero_frames"_a = r.repaired_zero_frames, "dropped_first_frame"_a = r.dropped_first_frame,
                  "missing_roles"_a = missing, "warnings"_a = r.warnings);
}

pb::object read(const std::string& path, double scale, bool drop_first, bool lenient, bool with_report) {
  if (!(scale >= 0)) value_error("scale: expected file units -> metres > 0, or 0 to detect, got " + std::to_string(scale));
  io::BvhReadOptions opt;
  opt.scale = scale;
  opt.drop_first_frame = drop_first;
  opt.strict_frame_count = !lenient;
  io::BvhFile f = io::read_bvh(path, opt);
  if (!with_report) return pb::cast(std::move(f.motion));
  pb::dict rep = report_dict(f.report);
  return pb::make_tuple(std::move(f.motion), rep);
}

}  // namespace io_binding
}  // namespace

void bind_io(pb::module_& m) {
  using namespace io_binding;  // its helpers and the module names they use
  m.def("read_bvh", &read, "path"_a, "scale"_a = 0.0, "drop_first"_a = false, "lenient"_a = false, "report"_a = false,
        "Reads a BVH file into a legwork.core.Motion (metres; Euler channels -> quaternions).\n"
        "scale: file units -> metres (0 = detect from the rest height); drop_first: drop frame 0 (the CMU T-pose);\n"
        "lenient: accept more motion lines than 'Frames:' declares. report=True returns (motion, dict) with the\n"
        "scale chosen and why, repaired frames, missing roles and warnings. Arrays: motion.rotations\n"
        "(frames, joints, 4) w,x,y,z, motion.translations / motion.positions() (frames, joints, 3) metres,\n"
        "motion.skeleton.parents / names, motion.fps (Hz). Raises legwork.Error naming file and line.");
  m.def(
      "write_bvh",
      [](const std::string& path, const Motion& mo, double scale) {
        if (!(scale > 0)) value_error("scale: expected metres -> file units > 0, got " + std::to_string(scale));
        io::BvhWriteOptions opt;
        opt.scale = scale;
        io::write_bvh(path, mo, opt);
      },
      "path"_a, "motion"_a, "scale"_a = 1.0,
      "Writes a motion as BVH (scale: metres -> file units; ZYX Euler channels, 6 decimals).");
  m.def(
      "format_bvh", [](const Motion& mo) { return io::format_bvh(mo); }, "motion"_a, "The BVH text of a motion (metres).");
}

}  // namespace legwork::py
