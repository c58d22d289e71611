// The IK baseline over a clip (see run.hpp).
#include <legwork/eval/run.hpp>

#include <legwork/ik/full_body.hpp>

#include <chrono>

namespace legwork::eval {

Motion run_ik_baseline(const Skeleton& skel, std::span<const TrackerFrame> frames, double fps, double* seconds) {
  const ik::Model model = ik::make_model(skel);
  ik::State state(model);
  Motion out(skel, fps, static_cast<int>(frames.size()));
  Pose pose(model.skeleton());
  double solver = 0;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const auto t0 = std::chrono::steady_clock::now();
    ik::update(model, frames[f], state, pose.ref());  // a rejected frame repeats the last pose
    solver += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    out.set_frame(static_cast<int>(f), pose);
  }
  if (seconds) *seconds += solver;
  return out;
}

}  // namespace legwork::eval
