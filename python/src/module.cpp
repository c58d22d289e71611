// The _legwork extension: one submodule per C++ module (core, io, accent,
// ik, wip, walkcycle, eval), legwork::Error as legwork.Error.
#include "bindings.hpp"

#include <legwork/core/types.hpp>

#include <cmath>
#include <sstream>

namespace legwork::py {

void value_error(const std::string& message) { throw pb::value_error(message); }

namespace {

std::string shape_string(const pb::array& a) {
  std::ostringstream s;
  s << "(";
  for (pb::ssize_t i = 0; i < a.ndim(); ++i) s << (i ? ", " : "") << a.shape(i);
  s << (a.ndim() == 1 ? ",)" : ")");
  return s.str();
}

}  // namespace

Array require_array(const pb::handle& obj, const char* name, std::initializer_list<pb::ssize_t> shape,
                    const char* shape_text, bool finite) {
  const std::string expected = std::string(name) + ": expected a C-contiguous float64 numpy array of shape " + shape_text;
  if (!pb::isinstance<pb::array>(obj))
    value_error(expected + ", got a " + std::string(pb::str(pb::type::of(obj).attr("__name__"))));
  const auto a = pb::reinterpret_borrow<pb::array>(obj);
  if (!a.dtype().is(pb::dtype::of<double>()))
    value_error(expected + ", got dtype " + std::string(pb::str(a.dtype())) + " (convert with .astype(numpy.float64))");
  bool ok = a.ndim() == static_cast<pb::ssize_t>(shape.size());
  pb::ssize_t axis = 0;
  for (const pb::ssize_t s : shape) {
    ok = ok && (s == kAny || a.shape(axis) == s);
    ++axis;
  }
  if (!ok) value_error(expected + ", got shape " + shape_string(a));
  if (!(a.flags() & pb::array::c_style))
    value_error(expected + ", got a non-contiguous array (use numpy.ascontiguousarray)");
  Array out = pb::reinterpret_borrow<Array>(obj);
  if (finite) {
    const double* p = out.data();
    for (pb::ssize_t i = 0; i < out.size(); ++i)
      if (!std::isfinite(p[i]))
        value_error(std::string(name) + ": element " + std::to_string(i) + " is not finite (" + std::to_string(p[i]) + ")");
  }
  return out;
}

Array new_array(std::initializer_list<pb::ssize_t> shape) { return Array(std::vector<pb::ssize_t>(shape)); }

pb::array view(const double* data, std::initializer_list<pb::ssize_t> shape, const pb::handle& owner, bool writable) {
  pb::array a(pb::dtype::of<double>(), std::vector<pb::ssize_t>(shape), {}, data, owner);
  if (!writable) pb::detail::array_proxy(a.ptr())->flags &= ~pb::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

void quats_to_wxyz(std::span<const Quat> q, double* out) {
  for (const Quat& r : q) {
    *out++ = r.w();
    *out++ = r.x();
    *out++ = r.y();
    *out++ = r.z();
  }
}

void wxyz_to_quats(const double* in, std::span<Quat> q) {
  for (Quat& r : q) {
    r = Quat(in[0], in[1], in[2], in[3]);
    in += 4;
  }
}

void require_pose(const Skeleton& skel, const Pose& out) {
  if (out.joint_count() != skel.joint_count())
    value_error("out: a Pose of the model's skeleton (" + std::to_string(skel.joint_count()) + " joints) expected, got " +
                std::to_string(out.joint_count()) + " joints");
}

void require_seconds(double seconds, const char* name) {
  if (!(std::isfinite(seconds) && seconds > 0))
    value_error(std::string(name) + ": expected a positive number of seconds, got " + std::to_string(seconds));
}

void require_rate(double fps, const char* name) {
  if (!(std::isfinite(fps) && fps > 0 && fps < 1e6))
    value_error(std::string(name) + ": expected a finite frame rate in Hz (0 < fps < 1e6), got " + std::to_string(fps));
}

}  // namespace legwork::py

PYBIND11_MODULE(_legwork, m) {
  namespace lp = legwork::py;
  m.doc() = "legwork's compiled core; use the legwork package (legwork.core, legwork.io, ...).";
  pybind11::register_exception<legwork::Error>(m, "Error", PyExc_RuntimeError);
  struct Submodule {
    const char* name;
    const char* doc;
    void (*bind)(pybind11::module_&);
  };
  // Innermost first: later modules use the core types.
  const Submodule submodules[] = {
      {"core", "Skeleton, poses, motions, forward kinematics, resampling, mirroring, tracker frames.", &lp::bind_core},
      {"io", "BVH reading and writing into numpy arrays.", &lp::bind_io},
      {"ik", "Full-body IK avatar (the VRIK-style baseline) on the per-frame contract.", &lp::bind_ik},
      {"wip", "Walking-in-place legs on the per-frame contract.", &lp::bind_wip},
      {"walkcycle", "Walk cycles from key poses; the frame-by-frame walker.", &lp::bind_walkcycle},
      {"accent", "Accentuation: full body from a headset and two controllers.", &lp::bind_accent},
      {"combined", "One avatar, two sources: accentuated (or IK) upper body, walking-in-place legs.", &lp::bind_combined},
      {"eval", "Evaluation metrics: MPJPE, MPJVE, jitter, foot skating, step detection F1.", &lp::bind_eval},
  };
  for (const Submodule& sub : submodules) {
    auto child = m.def_submodule(sub.name, sub.doc);
    sub.bind(child);
  }
}
