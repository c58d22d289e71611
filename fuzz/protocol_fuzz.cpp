// libFuzzer target for the messages of `legwork serve`'s WebSocket protocol
// (src/serve/protocol.cpp; the parser, not a socket): a text message (hello,
// frame, options) or a binary "LWF1" frame. A parsed frame goes on into a
// full-body IK avatar and the pose answer is formatted both ways, as the
// server does; the frame's JSON and binary forms must parse back.
// Any input ends in a ClientMessage or a ProtocolError with a code: never
// another exception, a crash, a sanitizer report, invalid JSON out, or a
// non-finite pose.
#include "fuzz_body.hpp"

#include <legwork/core/fk.hpp>
#include <legwork/serve/protocol.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace {

using namespace legwork;
using namespace legwork::serve;

void check_devices(const TrackerFrame& f) {
  if (!std::isfinite(f.time)) std::abort();
  for (const DevicePose& d : f.devices)
    if (d.valid && (!d.position.allFinite() || !(std::abs(d.rotation.squaredNorm() - 1) < 1e-6))) std::abort();
}

// The frame's own forms parse back (a client library writes them).
void round_trip(const TrackerFrame& f) {
  try {
    const ClientMessage back = parse_text(json_frame(f));
    const std::string bin = binary_frame(f);
    const TrackerFrame b = parse_binary_frame(std::as_bytes(std::span(bin.data(), bin.size())));
    for (std::size_t d = 0; d < f.devices.size(); ++d)
      if (back.frame.devices[d].valid != f.devices[d].valid || b.devices[d].valid != f.devices[d].valid) std::abort();
  } catch (const ProtocolError&) {
    std::abort();
  }
}

// What the server does with a frame: update, then the pose answer in both formats.
void answer(fuzz::IkAvatar& avatar, const TrackerFrame& f) {
  const UpdateStatus s = avatar.drive(f);
  std::vector<Vec3> world(avatar.pose().rotations.size());
  forward_positions(avatar.skeleton(), avatar.pose().ref(), world);
  std::vector<int> joints(world.size());
  for (std::size_t j = 0; j < joints.size(); ++j) joints[j] = static_cast<int>(j);
  PoseMessage m;
  m.t = f.time;
  m.status = s;
  m.pose = avatar.pose().ref();
  m.world = world;
  m.joints = joints;
  std::string out;
  format_pose_json(out, m);
  if (!nlohmann::json::accept(out)) std::abort();
  format_pose_binary(out, m);
  const BinaryPose p = parse_binary_pose(std::as_bytes(std::span(out.data(), out.size())));
  if (p.rotations.size() != joints.size()) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static fuzz::IkAvatar avatar;
  avatar.restart();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    TrackerFrame f;
    if (text.substr(0, 4) == "LWF1") {
      f = parse_binary_frame(std::as_bytes(std::span(data, size)));
    } else {
      const ClientMessage m = parse_text(text);
      if (m.type == MessageType::Hello) {
        if (!std::isfinite(m.hello.method.exaggeration) || !std::isfinite(m.hello.method.user_height)) std::abort();
        (void)output_joints(avatar.skeleton(), m.hello.joints);
        return 0;
      }
      if (m.type == MessageType::Options) {
        if (m.options.exaggeration && !std::isfinite(*m.options.exaggeration)) std::abort();
        return 0;
      }
      f = m.frame;
    }
    check_devices(f);
    round_trip(f);
    answer(avatar, f);
  } catch (const ProtocolError& e) {
    if (e.code().empty() || std::strlen(e.what()) == 0) std::abort();
  }
  return 0;
}
