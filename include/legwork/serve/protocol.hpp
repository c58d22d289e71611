#pragma once
// legwork live protocol v1 (docs/protocol.md): parsing client messages and
// formatting server messages, JSON and binary. Pure functions, no sockets.
#include <legwork/core/motion.hpp>
#include <legwork/core/tracker.hpp>
#include <legwork/serve/methods.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace legwork::serve {

inline constexpr int kProtocolVersion = 1;
inline constexpr std::size_t kMaxMessageBytes = 64 * 1024;
inline constexpr std::size_t kBinaryFrameBytes = 156;
inline constexpr std::size_t kBinaryPoseHeaderBytes = 24;

enum class Format : std::uint8_t { Json, Binary };

// A client's protocol mistake: `code` is one of the protocol's error codes
// (bad_json, bad_version, bad_message, bad_value, ...), what() the message.
class ProtocolError : public Error {
 public:
  ProtocolError(std::string code, const std::string& message) : Error(message), code_(std::move(code)) {}
  const std::string& code() const { return code_; }

 private:
  std::string code_;
};

struct Hello {
  MethodOptions method;
  std::vector<std::string> joints;  // output joint names; empty = all
  Format format = Format::Json;
  std::optional<bool> record;       // unset: the server's default
};

struct OptionsUpdate {
  std::optional<double> exaggeration;
  std::optional<std::vector<std::string>> classes;
  std::optional<bool> recognize_class;
};

enum class MessageType : std::uint8_t { Hello, Frame, Options };
struct ClientMessage {
  MessageType type = MessageType::Frame;
  Hello hello;
  TrackerFrame frame;
  OptionsUpdate options;
};

// Parses one text message. Throws ProtocolError: bad_json (not JSON / not an
// object), bad_version (hello without version 1), bad_message (unknown type,
// missing or mistyped field), bad_value (a non-finite or out-of-range number).
ClientMessage parse_text(std::string_view text);
// Parses one binary client frame ("LWF1", 156 bytes). Throws ProtocolError.
TrackerFrame parse_binary_frame(std::span<const std::byte> bytes);
// The binary form of a frame (for clients, tests and the benchmark).
std::string binary_frame(const TrackerFrame& f);
// The JSON form of a frame.
std::string json_frame(const TrackerFrame& f);

// Output joint indices for a hello's joint names (empty = all joints); throws
// ProtocolError bad_value naming an unknown joint.
std::vector<int> output_joints(const Skeleton& skel, const std::vector<std::string>& names);

struct WelcomeInfo {
  std::string session;
  std::string method;
  double max_rate_hz = 120;
  std::vector<int> joints;            // output joints
  bool recording = false;
  std::vector<std::string> warnings;
};
std::string format_welcome(const Skeleton& skel, const WelcomeInfo& w);
std::string format_error(std::string_view code, std::string_view message, std::optional<std::uint64_t> seq = {},
                         std::optional<double> t = {});

// One pose answer. `world` = model-space joint positions (all joints).
struct PoseMessage {
  std::uint64_t seq = 0;
  double t = 0;
  UpdateStatus status = UpdateStatus::Ok;
  ConstPoseRef pose;
  std::span<const Vec3> world;
  std::span<const int> joints;
  const InfoFields* info = nullptr;
  double server_us = 0;
};
const char* status_text(UpdateStatus s);  // ok | degraded | rejected | restarted
// Appends the JSON (text) or binary form to `out` (cleared first).
void format_pose_json(std::string& out, const PoseMessage& m);
void format_pose_binary(std::string& out, const PoseMessage& m);

// Decoded binary pose (tests, benchmark, viewer reference).
struct BinaryPose {
  double t = 0;
  std::uint32_t seq = 0;
  std::uint8_t status = 0;
  std::vector<Quat> rotations;
  std::vector<Vec3> positions;
};
BinaryPose parse_binary_pose(std::span<const std::byte> bytes);

}  // namespace legwork::serve
