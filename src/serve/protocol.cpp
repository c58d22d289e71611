// legwork live protocol v1: message parsing and formatting (see protocol.hpp).
#include <legwork/serve/protocol.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>

namespace legwork::serve {
namespace {

using json = nlohmann::json;

constexpr std::array<const char*, kDeviceCount> kDeviceKeys{"head", "left", "right", "left_foot", "right_foot"};

[[noreturn]] void fail(const char* code, const std::string& msg) { throw ProtocolError(code, msg); }

double number(const json& v, const std::string& where) {
  if (!v.is_number()) fail("bad_value", where + " is not a number (got " + std::string(v.type_name()) + ")");
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail("bad_value", where + " is not finite");
  return d;
}

DevicePose parse_device(const json& d, const std::string& name) {
  DevicePose out;
  if (d.is_null()) return out;
  if (!d.is_object()) fail("bad_message", "frame." + name + " must be an object {\"p\":[x,y,z],\"q\":[w,x,y,z]} or null");
  const auto p = d.find("p");
  if (p == d.end() || !p->is_array() || p->size() != 3)
    fail("bad_message", "frame." + name + ".p must be an array of 3 numbers [x,y,z] (metres)");
  for (int i = 0; i < 3; ++i) out.position[i] = number((*p)[static_cast<std::size_t>(i)], "frame." + name + ".p[" + std::to_string(i) + "]");
  const auto q = d.find("q");
  if (q != d.end() && !q->is_null()) {
    if (!q->is_array() || q->size() != 4) fail("bad_message", "frame." + name + ".q must be an array of 4 numbers [w,x,y,z]");
    std::array<double, 4> c{};
    for (std::size_t i = 0; i < 4; ++i) c[i] = number((*q)[i], "frame." + name + ".q[" + std::to_string(i) + "]");
    // Scaled by the largest component first: the norm of [1e300, 0, 0, 0] overflows to Inf
    // and would normalize to a zero quaternion.
    const double big = std::max({std::abs(c[0]), std::abs(c[1]), std::abs(c[2]), std::abs(c[3])});
    const Quat r = big > 0 ? Quat(c[0] / big, c[1] / big, c[2] / big, c[3] / big) : Quat(0, 0, 0, 0);
    if (!(big * r.norm() > 1e-6)) fail("bad_value", "frame." + name + ".q is not a rotation (zero length)");
    out.rotation = r.normalized();
  }
  out.valid = true;
  return out;
}

TrackerFrame parse_frame(const json& j) {
  TrackerFrame f;
  const auto t = j.find("t");
  if (t == j.end()) fail("bad_message", "frame without \"t\" (seconds)");
  f.time = number(*t, "frame.t");
  for (int i = 0; i < kDeviceCount; ++i) {
    const auto d = j.find(kDeviceKeys[static_cast<std::size_t>(i)]);
    if (d != j.end()) f.devices[static_cast<std::size_t>(i)] = parse_device(*d, kDeviceKeys[static_cast<std::size_t>(i)]);
  }
  return f;
}

bool boolean(const json& v, const std::string& where) {
  if (!v.is_boolean()) fail("bad_message", where + " must be true or false");
  return v.get<bool>();
}

std::vector<std::string> string_list(const json& v, const char* field) {
  if (!v.is_array()) fail("bad_message", std::string(field) + " must be an array of strings");
  std::vector<std::string> out;
  for (const auto& s : v) {
    if (!s.is_string()) fail("bad_message", std::string(field) + " must be an array of strings");
    out.push_back(s.get<std::string>());
  }
  return out;
}

Hello parse_hello(const json& j) {
  const auto v = j.find("version");
  if (v == j.end() || !v->is_number_integer() || v->get<long long>() != kProtocolVersion)
    fail("bad_version", "unsupported protocol version " + (v == j.end() ? std::string("(missing)") : v->dump()) +
                            ": this server speaks version " + std::to_string(kProtocolVersion));
  Hello h;
  if (auto m = j.find("method"); m != j.end()) {
    if (!m->is_string()) fail("bad_message", "hello.method must be a string");
    h.method.method = m->get<std::string>();
  }
  if (auto c = j.find("classes"); c != j.end() && !c->is_null()) h.method.classes = string_list(*c, "hello.classes");
  if (auto e = j.find("exaggeration"); e != j.end()) h.method.exaggeration = number(*e, "hello.exaggeration");
  if (auto rc = j.find("recognize_class"); rc != j.end()) h.method.recognize_class = boolean(*rc, "hello.recognize_class");
  if (auto fl = j.find("foot_lift_height"); fl != j.end()) h.method.foot_lift_height = number(*fl, "hello.foot_lift_height");
  if (auto fs = j.find("foot_lock_slack"); fs != j.end()) h.method.foot_lock_slack = number(*fs, "hello.foot_lock_slack");
  if (auto fh = j.find("foot_lock_hold_seconds"); fh != j.end()) h.method.foot_lock_hold_seconds = number(*fh, "hello.foot_lock_hold_seconds");
  if (auto tw = j.find("travel_weight"); tw != j.end()) h.method.travel_weight = number(*tw, "hello.travel_weight");
  if (auto hd = j.find("max_head_height_diff"); hd != j.end())
    h.method.max_head_height_diff = number(*hd, "hello.max_head_height_diff");
  if (auto sf = j.find("smooth_feedforward"); sf != j.end()) h.method.smooth_feedforward = number(*sf, "hello.smooth_feedforward");
  if (auto lr = j.find("lying_root_smoothing"); lr != j.end()) h.method.lying_root_smoothing = number(*lr, "hello.lying_root_smoothing");
  if (auto lc = j.find("lying_crown"); lc != j.end()) h.method.lying_crown = number(*lc, "hello.lying_crown");
  if (auto oc = j.find("other_class_cost"); oc != j.end()) h.method.other_class_cost = number(*oc, "hello.other_class_cost");
  if (auto si = j.find("search_interval"); si != j.end()) h.method.search_interval = number(*si, "hello.search_interval");
  if (auto fl = j.find("floor"); fl != j.end()) h.method.floor = boolean(*fl, "hello.floor");
  if (auto fh = j.find("floor_height"); fh != j.end()) h.method.floor_height = number(*fh, "hello.floor_height");
  if (auto fw = j.find("foot_swing_speed"); fw != j.end()) h.method.foot_swing_speed = number(*fw, "hello.foot_swing_speed");
  if (auto u = j.find("user_height"); u != j.end() && !u->is_null()) h.method.user_height = number(*u, "hello.user_height");
  if (auto mp = j.find("mapping"); mp != j.end() && !mp->is_null()) {
    if (!mp->is_string()) fail("bad_message", "hello.mapping must be a string (\"document\" or \"learned\")");
    h.method.mapping = mp->get<std::string>();
  }
  for (const char* key : {"walk", "root"})
    if (auto w = j.find(key); w != j.end() && !w->is_null()) {
      if (!w->is_string()) fail("bad_message", std::string("hello.") + key + " must be a string");
      (std::string(key) == "walk" ? h.method.walk : h.method.root) = w->get<std::string>();
    }
  if (auto g = j.find("ground"); g != j.end() && !g->is_null()) {
    if (!g->is_object()) fail("bad_message", "hello.ground must be an object (a path file's \"ground\": slope or heightfield)");
    h.method.ground = g->dump();
  }
  if (auto x = j.find("max_turn_per_step"); x != j.end()) h.method.max_turn_per_step = number(*x, "hello.max_turn_per_step");
  if (auto x = j.find("soft_reach"); x != j.end()) h.method.soft_reach = number(*x, "hello.soft_reach");
  if (auto x = j.find("stairs_cadence"); x != j.end()) h.method.stairs_cadence = number(*x, "hello.stairs_cadence");
  if (auto d = j.find("detector"); d != j.end() && !d->is_null()) {
    if (!d->is_string()) fail("bad_message", "hello.detector must be a string (\"document\" or \"adaptive\")");
    h.method.detector = d->get<std::string>();
  }
  if (auto js = j.find("joints"); js != j.end() && !(js->is_string() && js->get<std::string>() == "all"))
    h.joints = string_list(*js, "hello.joints (\"all\" or joint names)");
  if (auto f = j.find("format"); f != j.end()) {
    if (*f == "json") h.format = Format::Json;
    else if (*f == "binary") h.format = Format::Binary;
    else fail("bad_value", "hello.format must be \"json\" or \"binary\"");
  }
  if (auto r = j.find("record"); r != j.end()) {
    if (!r->is_boolean()) fail("bad_message", "hello.record must be true or false");
    h.record = r->get<bool>();
  }
  return h;
}

template <typename T>
void put(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.append(b, sizeof(T));
}
// A double as a float of the binary forms: out-of-range values saturate
// (a plain cast of them is undefined behaviour); they stay absurd, so a
// device carrying one is still not usable().
float to_float(double v) {
  constexpr double kMax = std::numeric_limits<float>::max();
  return static_cast<float>(std::isnan(v) ? v : std::clamp(v, -kMax, kMax));
}

template <typename T>
T get(std::span<const std::byte> bytes, std::size_t at) {
  T v;
  std::memcpy(&v, bytes.data() + at, sizeof(T));
  return v;
}

void num(std::string& out, double v, int precision) {
  if (!std::isfinite(v)) {
    out += "null";
    return;
  }
  char b[48];
  auto r = std::to_chars(b, b + sizeof b, v, std::chars_format::fixed, precision);
  if (r.ec != std::errc()) {  // too long in fixed notation (|v| >= ~1e40): shortest exponent form
    r = std::to_chars(b, b + sizeof b, v);
    out.append(b, static_cast<std::size_t>(r.ptr - b));
    return;
  }
  // Trim trailing zeros ("0.500000" -> "0.5", "1.000" -> "1").
  char* e = r.ptr;
  char* dot = static_cast<char*>(std::memchr(b, '.', static_cast<std::size_t>(e - b)));
  if (dot) {
    while (e > dot + 1 && e[-1] == '0') --e;
    if (e == dot + 1) --e;
  }
  if (e - b == 2 && b[0] == '-' && b[1] == '0') {
    out += '0';
    return;
  }
  out.append(b, static_cast<std::size_t>(e - b));
}

void vec(std::string& out, const Vec3& v) {
  out += '[';
  num(out, v.x(), 5);
  out += ',';
  num(out, v.y(), 5);
  out += ',';
  num(out, v.z(), 5);
  out += ']';
}

void quat(std::string& out, const Quat& q) {
  out += '[';
  num(out, q.w(), 6);
  out += ',';
  num(out, q.x(), 6);
  out += ',';
  num(out, q.y(), 6);
  out += ',';
  num(out, q.z(), 6);
  out += ']';
}

}  // namespace

ClientMessage parse_text(std::string_view text) {
  json j = json::parse(text.begin(), text.end(), nullptr, false);
  if (j.is_discarded()) fail("bad_json", "message is not valid JSON (" + std::to_string(text.size()) + " bytes)");
  if (!j.is_object()) fail("bad_json", "message must be a JSON object with a \"type\"");
  const auto type = j.find("type");
  if (type == j.end() || !type->is_string()) fail("bad_message", "message without a \"type\" string");
  ClientMessage m;
  const std::string t = type->get<std::string>();
  if (t == "frame") {
    m.type = MessageType::Frame;
    m.frame = parse_frame(j);
  } else if (t == "hello") {
    m.type = MessageType::Hello;
    m.hello = parse_hello(j);
  } else if (t == "options") {
    m.type = MessageType::Options;
    if (auto e = j.find("exaggeration"); e != j.end()) m.options.exaggeration = number(*e, "options.exaggeration");
    if (auto rc = j.find("recognize_class"); rc != j.end()) m.options.recognize_class = boolean(*rc, "options.recognize_class");
    if (auto c = j.find("classes"); c != j.end()) m.options.classes = c->is_null() ? std::vector<std::string>{} : string_list(*c, "options.classes");
  } else {
    fail("bad_message", "unknown message type '" + t + "' (expected hello, frame or options)");
  }
  return m;
}

TrackerFrame parse_binary_frame(std::span<const std::byte> bytes) {
  if (bytes.size() != kBinaryFrameBytes)
    fail("bad_message", "binary frame has " + std::to_string(bytes.size()) + " bytes, expected " + std::to_string(kBinaryFrameBytes));
  if (std::memcmp(bytes.data(), "LWF1", 4) != 0) fail("bad_message", "binary frame does not start with \"LWF1\"");
  TrackerFrame f;
  f.time = get<double>(bytes, 4);
  if (!std::isfinite(f.time)) fail("bad_value", "frame.t is not finite");
  const auto mask = get<std::uint8_t>(bytes, 12);
  for (int d = 0; d < kDeviceCount; ++d) {
    if (!(mask & (1u << d))) continue;
    std::array<float, 7> v{};
    for (std::size_t i = 0; i < 7; ++i) {
      v[i] = get<float>(bytes, 16 + static_cast<std::size_t>(d) * 28 + i * 4);
      if (!std::isfinite(v[i])) fail("bad_value", std::string("frame.") + kDeviceKeys[static_cast<std::size_t>(d)] + " has a non-finite value");
    }
    DevicePose& p = f.devices[static_cast<std::size_t>(d)];
    p.position = Vec3(v[0], v[1], v[2]);
    Quat q(v[3], v[4], v[5], v[6]);
    if (!(q.norm() > 1e-6)) fail("bad_value", std::string("frame.") + kDeviceKeys[static_cast<std::size_t>(d)] + ".q is not a rotation (zero length)");
    p.rotation = q.normalized();
    p.valid = true;
  }
  return f;
}

std::string binary_frame(const TrackerFrame& f) {
  std::string out = "LWF1";
  put(out, f.time);
  std::uint8_t mask = 0;
  for (int d = 0; d < kDeviceCount; ++d)
    if (f.devices[static_cast<std::size_t>(d)].valid) mask = static_cast<std::uint8_t>(mask | (1u << d));
  put(out, mask);
  out.append(3, '\0');
  for (const DevicePose& p : f.devices) {
    const Quat q = p.valid ? p.rotation : Quat::Identity();
    const Vec3 x = p.valid ? p.position : Vec3::Zero();
    for (double v : {x.x(), x.y(), x.z(), q.w(), q.x(), q.y(), q.z()}) put(out, to_float(v));
  }
  return out;
}

std::string json_frame(const TrackerFrame& f) {
  std::string out = "{\"type\":\"frame\",\"t\":";
  num(out, f.time, 6);
  for (int d = 0; d < kDeviceCount; ++d) {
    const DevicePose& p = f.devices[static_cast<std::size_t>(d)];
    if (!p.valid) continue;
    out += std::string(",\"") + kDeviceKeys[static_cast<std::size_t>(d)] + "\":{\"p\":";
    vec(out, p.position);
    out += ",\"q\":";
    quat(out, p.rotation);
    out += '}';
  }
  out += '}';
  return out;
}

std::vector<int> output_joints(const Skeleton& skel, const std::vector<std::string>& names) {
  std::vector<int> out;
  if (names.empty()) {
    for (int j = 0; j < skel.joint_count(); ++j) out.push_back(j);
    return out;
  }
  for (const auto& n : names) {
    const int j = skel.find(n);
    if (j < 0) fail("bad_value", "hello.joints: no joint '" + n + "' in the avatar skeleton (see welcome.skeleton.names)");
    out.push_back(j);
  }
  return out;
}

std::string format_welcome(const Skeleton& skel, const WelcomeInfo& w) {
  json names = skel.names, parents = skel.parents, offsets = json::array(), joints = json::array();
  for (const Vec3& o : skel.rest_offsets) offsets.push_back({o.x(), o.y(), o.z()});
  for (int j : w.joints) joints.push_back(skel.names[static_cast<std::size_t>(j)]);
  json m = {{"type", "welcome"},   {"version", kProtocolVersion},
            {"session", w.session}, {"method", w.method},
            {"skeleton", {{"names", names}, {"parents", parents}, {"offsets", offsets}}},
            {"joints", joints},     {"max_rate_hz", w.max_rate_hz},
            {"recording", w.recording}};
  if (!w.warnings.empty()) m["warnings"] = w.warnings;
  return m.dump();
}

std::string format_error(std::string_view code, std::string_view message, std::optional<std::uint64_t> seq,
                         std::optional<double> t) {
  json m = {{"type", "error"}, {"code", code}, {"message", message}};
  if (seq) m["seq"] = *seq;
  if (t && std::isfinite(*t)) m["t"] = *t;
  return m.dump(-1, ' ', false, json::error_handler_t::replace);
}

const char* status_text(UpdateStatus s) {
  switch (s) {
    case UpdateStatus::Ok: return "ok";
    case UpdateStatus::Degraded: return "degraded";
    case UpdateStatus::Rejected: return "rejected";
    case UpdateStatus::Restarted: return "restarted";
  }
  return "ok";
}

void format_pose_json(std::string& out, const PoseMessage& m) {
  out.clear();
  out += "{\"type\":\"pose\",\"seq\":";
  out += std::to_string(m.seq);
  out += ",\"t\":";
  num(out, m.t, 6);
  out += ",\"status\":\"";
  out += status_text(m.status);
  out += "\",\"root\":";
  vec(out, m.pose.translations[0]);
  out += ",\"rotations\":[";
  for (std::size_t i = 0; i < m.joints.size(); ++i) {
    if (i) out += ',';
    quat(out, m.pose.rotations[static_cast<std::size_t>(m.joints[i])]);
  }
  out += "],\"positions\":[";
  for (std::size_t i = 0; i < m.joints.size(); ++i) {
    if (i) out += ',';
    vec(out, m.world[static_cast<std::size_t>(m.joints[i])]);
  }
  out += "],\"info\":{";
  if (m.info)
    for (int i = 0; i < m.info->count; ++i) {
      const auto& it = m.info->items[static_cast<std::size_t>(i)];
      if (i) out += ',';
      out += '"';
      out += it.key;
      out += "\":";
      if (it.text) {
        out += '"';
        out += it.text;
        out += '"';
      } else {
        num(out, it.number, 6);
      }
    }
  out += "},\"server_us\":";
  num(out, m.server_us, 1);
  out += '}';
}

void format_pose_binary(std::string& out, const PoseMessage& m) {
  // Sized once and written in place (a per-value append cost 7,000 instructions a pose).
  out.resize(kBinaryPoseHeaderBytes + 28 * m.joints.size());
  char* at = out.data();
  const auto write = [&at](auto v) {
    std::memcpy(at, &v, sizeof v);
    at += sizeof v;
  };
  std::memcpy(at, "LWP1", 4);
  at += 4;
  write(m.t);
  write(static_cast<std::uint32_t>(m.seq));
  write(static_cast<std::uint8_t>(m.status));
  std::memset(at, 0, 3);
  at += 3;
  write(static_cast<std::uint32_t>(m.joints.size()));
  for (int j : m.joints) {
    const Quat& q = m.pose.rotations[static_cast<std::size_t>(j)];
    for (double v : {q.w(), q.x(), q.y(), q.z()}) write(to_float(v));
  }
  for (int j : m.joints) {
    const Vec3& p = m.world[static_cast<std::size_t>(j)];
    for (double v : {p.x(), p.y(), p.z()}) write(to_float(v));
  }
}

BinaryPose parse_binary_pose(std::span<const std::byte> bytes) {
  if (bytes.size() < kBinaryPoseHeaderBytes || std::memcmp(bytes.data(), "LWP1", 4) != 0)
    throw Error("binary pose: not an \"LWP1\" message");
  BinaryPose p;
  p.t = get<double>(bytes, 4);
  p.seq = get<std::uint32_t>(bytes, 12);
  p.status = get<std::uint8_t>(bytes, 16);
  const auto n = get<std::uint32_t>(bytes, 20);
  if (bytes.size() != kBinaryPoseHeaderBytes + std::size_t{n} * 28)
    throw Error("binary pose: " + std::to_string(bytes.size()) + " bytes for " + std::to_string(n) + " joints");
  std::size_t at = kBinaryPoseHeaderBytes;
  for (std::uint32_t i = 0; i < n; ++i, at += 16)
    p.rotations.emplace_back(get<float>(bytes, at), get<float>(bytes, at + 4), get<float>(bytes, at + 8), get<float>(bytes, at + 12));
  for (std::uint32_t i = 0; i < n; ++i, at += 12)
    p.positions.emplace_back(get<float>(bytes, at), get<float>(bytes, at + 4), get<float>(bytes, at + 8));
  return p;
}

}  // namespace legwork::serve
