// libFuzzer target for the VMC input of `legwork serve` (OSC over UDP):
// packets go through liblo's decoding (lo_server_dispatch_data: messages and
// bundles, as the server's socket hands them over) into legwork's handler
// (src/serve/vmc_input.cpp), which keeps the latest pose per device; after
// every packet the frame the avatar would get drives a full-body IK avatar.
// Input: OSC 1.0 stream framing, i.e. packets each preceded by its size as a
// big-endian int32 (a size beyond the input takes the rest).
// Never a crash, a sanitizer report or a non-finite pose; a valid device in a
// frame is finite, a zero quaternion or an absurd position is not usable().
#include "fuzz_body.hpp"
#include "vmc_input.hpp"

#include <lo/lo.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

namespace {

using namespace legwork;

void quiet(int, const char*, const char*) {}

struct Receiver {
  lo_server server = lo_server_new_with_proto(nullptr, LO_UDP, quiet);  // never read from: packets are dispatched
  serve::VmcInput input;
  fuzz::IkAvatar avatar;
  Receiver() {
    if (!server) std::abort();
    input.listen(server);
  }
};

void check_frame(const TrackerFrame& f) {
  for (const DevicePose& d : f.devices)
    if (d.valid && (!d.position.allFinite() || !d.rotation.coeffs().allFinite())) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static Receiver r;
  r.input = serve::VmcInput{};
  r.input.left_serial = "LHR-LEFT";
  r.input.right_serial = "LHR-RIGHT";
  r.avatar.restart();
  std::size_t at = 0;
  while (at + 4 <= size) {
    const std::uint32_t n = (std::uint32_t{data[at]} << 24) | (std::uint32_t{data[at + 1]} << 16) |
                            (std::uint32_t{data[at + 2]} << 8) | data[at + 3];
    at += 4;
    const std::size_t len = n < size - at ? n : size - at;
    std::vector<std::uint8_t> packet(data + at, data + at + len);  // liblo may swap bytes in place
    at += len;
    if (!packet.empty()) lo_server_dispatch_data(r.server, packet.data(), packet.size());
    TrackerFrame f;
    if (r.input.frame(f)) {
      check_frame(f);
      r.avatar.drive(f);
    }
  }
  return 0;
}
