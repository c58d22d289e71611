// Whole-clip accentuation (offline helper; see offline/run.hpp).
#include <legwork/accent/offline/run.hpp>

#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/core/rotation.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

namespace legwork::accent {

AccentRun accentuate(const Model& model, std::span<const TrackerFrame> frames, double fps) {
  State state(model);
  AccentRun run;
  run.output = Motion(model.skeleton(), fps, static_cast<int>(frames.size()));
  run.info.resize(frames.size());
  run.status.resize(frames.size());
  run.frame_seconds.resize(frames.size());
  Pose pose = model.neutral();
  double seconds = 0;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const auto t0 = std::chrono::steady_clock::now();
    run.status[f] = update(model, frames[f], state, pose.ref(), &run.info[f]);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    run.frame_seconds[f] = static_cast<float>(s);
    seconds += s;
    run.output.set_frame(static_cast<int>(f), pose);
  }
  run.seconds = seconds;
  const auto count = [&](MatchStatus s) { return std::count_if(run.info.begin(), run.info.end(), [s](const Info& i) { return i.match == s; }); };
  const auto unmatched = count(MatchStatus::Unmatched);
  if (unmatched > 0 && count(MatchStatus::Matched) + count(MatchStatus::Partial) == 0)
    run.warnings.push_back("no frame matched the database (" + std::to_string(unmatched) + " of " + std::to_string(frames.size()) +
                           " frames unmatched): the body is only the direct mapping of the head and hands. Is the user "
                           "height or the exaggeration far from the user's, or is this motion absent from the database?");
  return run;
}

AccentRun accentuate_motion(const Database& db, Settings settings, const Motion& input) {
  for (Role need : {Role::Head, Role::LeftHand, Role::RightHand})
    if (!input.skeleton.roles.has(need))
      throw Error("accent: the input skeleton has no " + std::string(role_name(need)) + " joint (needed as a tracked device)");
  const double fps = db.feature_space().fps;
  const Motion m = std::abs(input.fps - fps) > 1e-9 ? resample(input, fps) : input;
  if (settings.user_height <= 0) settings.user_height = measure_body(m.skeleton).standing_height;
  const Model model = make_model(db, settings);
  const auto frames = tracker_frames_from_motion(m);
  return accentuate(model, frames, fps);
}

Motion input_markers(std::span<const TrackerFrame> frames, double fps) {
  // Drawn as a head (circle through the head and its tip) and two
  // controllers (a short stub forward from each hand, in the side colours).
  Skeleton s;
  s.add_joint("Head", -1, Vec3::Zero());
  s.add_joint("LeftHand", 0, Vec3(0.2, -0.5, 0));
  s.add_joint("RightHand", 0, Vec3(-0.2, -0.5, 0));
  s.end_sites[0] = Vec3(0, 0.12, 0);
  for (std::size_t j = 0; j < 3; ++j) {
    if (j > 0) s.end_sites[j] = Vec3(0, 0, 0.08);
    s.has_end_site[j] = 1;
  }
  resolve_roles(s);
  Motion m(s, fps, static_cast<int>(frames.size()));
  Vec3 head = Vec3::Zero(), hand[2] = {Vec3(0.2, -0.5, 0), Vec3(-0.2, -0.5, 0)};
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const auto& fr = frames[f];
    if (usable(fr.head())) head = fr.head().position;
    for (int h = 0; h < 2; ++h)
      if (fr.hand(h).valid && all_finite(fr.hand(h).position)) hand[h] = fr.hand(h).position - head;
    auto p = m.frame(static_cast<int>(f));
    p.translations[0] = head;
    p.translations[1] = hand[0];
    p.translations[2] = hand[1];
  }
  return m;
}

}  // namespace legwork::accent
