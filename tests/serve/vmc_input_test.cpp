// VMC input decoding (src/serve/vmc_input.cpp) without a socket: OSC packets
// as liblo hands them over, checked value by value (Unity's frame mirrored).
#include "../../src/serve/vmc_input.hpp"

#include <gtest/gtest.h>

#include <lo/lo.h>

#include <cmath>
#include <cstdlib>
#include <vector>

namespace legwork::serve {
namespace {

// A device message as a VMC sender writes it: serial, position xyz, quaternion xyzw (Unity).
std::vector<char> device_message(const char* path, const char* serial, const std::vector<float>& v) {
  lo_message m = lo_message_new();
  lo_message_add_string(m, serial);
  for (float x : v) lo_message_add_float(m, x);
  std::size_t size = 0;
  void* data = lo_message_serialise(m, path, nullptr, &size);
  std::vector<char> out(static_cast<const char*>(data), static_cast<const char*>(data) + size);
  std::free(data);
  lo_message_free(m);
  return out;
}

void quiet(int, const char*, const char*) {}

// The serial "HMD" puts every argument at 4 (mod 8) bytes in the packet; the
// handler read them as lo_arg members, which need 8-byte alignment (UBSan:
// misaligned member access; caught by the sanitizer run of this test).
TEST(VmcInput, DeviceMessagesBecomeAFrameInLegworksAxes) {
  lo_server server = lo_server_new_with_proto(nullptr, LO_UDP, quiet);
  ASSERT_NE(server, nullptr);
  VmcInput input;
  input.listen(server);
  auto hmd = device_message("/VMC/Ext/Hmd/Pos", "HMD", {0.25f, 1.6f, 0.5f, 0, 0, 0, 1});
  auto left = device_message("/VMC/Ext/Con/Pos", "LHR-1", {-0.3f, 1.0f, 0.7f, 0, 0, 0, 1});
  ASSERT_EQ(lo_server_dispatch_data(server, hmd.data(), hmd.size()), static_cast<int>(hmd.size()));
  ASSERT_EQ(lo_server_dispatch_data(server, left.data(), left.size()), static_cast<int>(left.size()));
  TrackerFrame f;
  ASSERT_TRUE(input.frame(f));
  ASSERT_TRUE(f.head().valid);
  // Unity is left-handed (x to the right): legwork's x is mirrored.
  EXPECT_FLOAT_EQ(static_cast<float>(f.head().position.x()), -0.25f);
  EXPECT_FLOAT_EQ(static_cast<float>(f.head().position.y()), 1.6f);
  EXPECT_FLOAT_EQ(static_cast<float>(f.head().position.z()), 0.5f);
  EXPECT_TRUE(usable(f.head()));
  // The controller at Unity x = -0.3 (the user's left) is the left hand.
  ASSERT_TRUE(f.hand(kLeft).valid);
  EXPECT_FLOAT_EQ(static_cast<float>(f.hand(kLeft).position.x()), 0.3f);
  EXPECT_FALSE(f.hand(kRight).valid);
  // A non-finite sample is ignored, the last good pose stays.
  auto bad = device_message("/VMC/Ext/Hmd/Pos", "HMD", {NAN, 1.6f, 0.5f, 0, 0, 0, 1});
  lo_server_dispatch_data(server, bad.data(), bad.size());
  EXPECT_FALSE(input.frame(f));  // nothing new arrived
  lo_server_free(server);
}

}  // namespace
}  // namespace legwork::serve
