// The IK baseline over a clip (see run.hpp).
#include <legwork/eval/run.hpp>

#include <legwork/ik/full_body.hpp>

#include <chrono>

namespace legwork::eval {

Motion run_ik_baseline(const Skeleton& skel, std::span<const TrackerFrame> frames, double fps, double* seconds) {
  const ik::FullBodyModel model(skel);
  ik::FullBodyState state(model);
  Motion out(skel, fps, static_cast<int>(frames.size()));
  Pose pose(skel);
  double solver = 0;
  double last = 0;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const TrackerFrame& fr = frames[f];
    ik::TrackerFrame in;
    in.head_position = fr.head().position;
    in.head_rotation = fr.head().rotation;
    in.hand_position = {fr.hand(kLeft).position, fr.hand(kRight).position};
    in.hand_rotation = {fr.hand(kLeft).rotation, fr.hand(kRight).rotation};
    in.hand_valid = {usable(fr.hand(kLeft)), usable(fr.hand(kRight))};
    const auto t0 = std::chrono::steady_clock::now();
    ik::solve_full_body(model, in, f > 0 ? fr.time - last : 1.0 / fps, state, pose.ref());
    solver += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    last = fr.time;
    out.set_frame(static_cast<int>(f), pose);
  }
  if (seconds) *seconds += solver;
  return out;
}

}  // namespace legwork::eval
