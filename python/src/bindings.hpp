#pragma once
// Shared helpers of the legwork Python extension (_legwork): numpy argument
// checks with messages naming the argument and the expected shape, and the
// conversions between legwork's types and numpy arrays.
//
// Conventions at this boundary: float64 arrays, C-contiguous, quaternions as
// (w, x, y, z) in the last axis, positions in metres, times in seconds.
#include <legwork/core/info_fields.hpp>
#include <legwork/core/motion.hpp>
#include <legwork/core/tracker.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <initializer_list>
#include <utility>
#include <string>
#include <vector>

namespace legwork::py {

namespace pb = pybind11;
using Array = pb::array_t<double, pb::array::c_style>;

// One expected axis: a fixed size, or any size (kAny) named in the message.
inline constexpr pb::ssize_t kAny = -1;

// Checks that `obj` is a numpy float64, C-contiguous array whose shape
// matches `shape` (kAny = any length), and (finite = true) holds no NaN or
// infinity. Throws ValueError "name: expected ... of shape (frames, 3), got ..."
// naming `name` and `shape_text`. Returns the array (no copy).
Array require_array(const pb::handle& obj, const char* name, std::initializer_list<pb::ssize_t> shape,
                    const char* shape_text, bool finite = true);
// ValueError with `message`.
[[noreturn]] void value_error(const std::string& message);

// A new uninitialised float64 array of the given shape.
Array new_array(std::initializer_list<pb::ssize_t> shape);
// A numpy view of `data` (rows x cols doubles) owned by `owner` (kept alive).
pb::array view(const double* data, std::initializer_list<pb::ssize_t> shape, const pb::handle& owner, bool writable);

// Quaternion rows (w, x, y, z) <-> Eigen quaternions.
void quats_to_wxyz(std::span<const Quat> q, double* out);
void wxyz_to_quats(const double* in, std::span<Quat> q);

// A duration: finite and positive (ValueError naming `name`).
void require_seconds(double seconds, const char* name);

// Frame rate check: finite and positive (ValueError naming `name`).
void require_rate(double fps, const char* name);

// ValueError unless `out` is a pose of `skel` (same joint count).
void require_pose(const Skeleton& skel, const Pose& out);

// Defines `update(model, frame, state, out, info=None) -> UpdateStatus` of one
// runtime module: the C++ update() with the output pose's size checked.
// `pose_optional`: out=None passes an empty pose (PoseRef{}), for a runtime
// whose update() then advances without solving a body (legwork::wip);
// otherwise None is refused by name.
template <class M, class S, class I>
void def_update(pb::module_& m, UpdateStatus (*fn)(const M&, const TrackerFrame&, S&, PoseRef, I*), const char* doc,
                bool pose_optional = false) {
  using namespace pybind11::literals;
  m.def(
      "update",
      [fn, pose_optional](const M& model, const TrackerFrame& frame, S& state, Pose* out, I* info) {
        if (!out && !pose_optional)
          value_error("out: a Pose of the model's skeleton (" + std::to_string(model.skeleton().joint_count()) +
                      " joints) expected, got None");
        if (!out) return fn(model, frame, state, PoseRef{}, info);
        require_pose(model.skeleton(), *out);
        return fn(model, frame, state, out->ref(), info);
      },
      "model"_a, "frame"_a, "state"_a, "out"_a, "info"_a = nullptr, doc);
}

// Info.fields() -> dict: the frame's figures under the names of the server's
// pose "info" object and the C API's lw_avatar_info_field (docs/protocol.md),
// from the runtime's own describe(): numbers as float, texts as str.
template <class I>
void def_fields(pb::class_<I> info) {
  info.def(
      "fields",
      [](const I& i) {
        InfoFields f;
        describe(i, f);
        pb::dict d;
        for (int k = 0; k < f.count; ++k) {
          const InfoFields::Item& it = f.items[static_cast<std::size_t>(k)];
          if (it.text)
            d[it.key] = pb::str(it.text);
          else
            d[it.key] = pb::float_(it.number);
        }
        return d;
      },
      "the frame's figures as a dict, under the names of the server's pose 'info' and the C API's "
      "lw_avatar_info_field (docs/protocol.md)");
}

// Binds a runtime's Model (skeleton(), settings()), State(model) and
// reset(model, state); returns both classes for module-specific extras.
template <class M, class S>
std::pair<pb::class_<M>, pb::class_<S>> def_model_state(pb::module_& m, void (*reset_fn)(const M&, S&), const char* model_doc, const char* state_doc) {
  using namespace pybind11::literals;
  pb::class_<S> state(m, "State", state_doc);
  state.def(pb::init<const M&>(), "model"_a);
  m.def("reset", reset_fn, "model"_a, "state"_a, "Resets one avatar (calibrations such as a WIP floor are kept).");
  pb::class_<M> model(m, "Model", model_doc);
  model.def("skeleton", &M::skeleton, pb::return_value_policy::reference_internal, "the output pose's skeleton")
      .def("settings", &M::settings, pb::return_value_policy::reference_internal);
  return {model, state};
}

void bind_core(pb::module_& m);
void bind_tracker(pb::module_& m);  // part of legwork.core
// Tracker frames from arrays (NaN rows = lost tracking): see legwork.core.tracker_frames.
std::vector<TrackerFrame> frames_from_arrays(double fps, const pb::handle& head_position, const pb::handle& head_rotation,
                                             const pb::handle& left_hand, const pb::handle& right_hand,
                                             const pb::handle& left_foot, const pb::handle& right_foot, double start_time);
void bind_io(pb::module_& m);
void bind_accent(pb::module_& m);
void bind_eval(pb::module_& m);
void bind_ik(pb::module_& m);
void bind_wip(pb::module_& m);
void bind_walkcycle(pb::module_& m);
void bind_combined(pb::module_& m);

}  // namespace legwork::py
