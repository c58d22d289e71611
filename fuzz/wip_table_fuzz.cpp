// libFuzzer target for learned walking-in-place tables (the text written by
// `legwork wip learn`, read by `--table`, `serve --wip-table` and the C API's
// lw_model_create_wip_learned) and what consumes them: a walking-in-place
// model with the learned depth mapping, driven over a real walk's ankles and
// head (the repo's 05_01, which turns round, so the turning gain is reached).
// Any input ends in a legwork::Error or in a model whose every output is
// finite: never a crash, a sanitizer report or a hang.
#include "fuzz_body.hpp"

#include <legwork/wip/offline/learn.hpp>
#include <legwork/wip/wip.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

namespace {

using namespace legwork;

// The walk's trackers at 30 Hz, the first 3 s (through its first steps).
const std::vector<TrackerFrame>& walk_frames() {
  static const std::vector<TrackerFrame> f = fuzz::sample_frames("cmu/bvh/walking/05_01.bvh", 30.0, 90);
  return f;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  wip::LearnedMapping table;
  try {
    table = wip::parse_learned_mapping(text, "fuzz.txt");
  } catch (const Error&) {
    return 0;
  }
  // The lookup at the grid's corners, beyond them and at NaN stays finite.
  for (double c : {-1.0, 0.0, 0.99, 2.0, 5.0})
    for (double rate : {-1.0, 0.0, 1.0, 1e9, std::nan("")})
      if (!std::isfinite(table.depth(c, 2 - c, 1, c, 0.1, 1.0, rate)) || !std::isfinite(table.depth(c, c, -1, 1e9, NAN, NAN, rate)))
        std::abort();
  static const Skeleton& skel = fuzz::sample_skeleton();
  wip::Settings settings;
  settings.mapping.depth = wip::DepthMapping::Learned;
  std::optional<wip::Model> built;
  try {
    built.emplace(wip::make_model(skel, settings, {}, &table));
  } catch (const Error&) {
    return 0;
  }
  const wip::Model& model = *built;
  wip::State state(model);
  Pose pose(model.skeleton());
  wip::Info info;
  for (const TrackerFrame& f : walk_frames()) {
    wip::update(model, f, state, pose.ref(), &info);
    if (!std::isfinite(info.z[0]) || !std::isfinite(info.z[1]) || !std::isfinite(info.turn_rate)) std::abort();
    for (std::size_t j = 0; j < pose.rotations.size(); ++j)
      if (!pose.rotations[j].coeffs().allFinite() || !pose.translations[j].allFinite()) std::abort();
  }
  return 0;
}
