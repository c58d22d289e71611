#include <legwork/walkcycle/offline/keys.hpp>

#include <legwork/io/bvh.hpp>
#include <legwork/io/text.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>

namespace legwork::walkcycle {

using nlohmann::json;

namespace {

const std::array<std::string_view, kKeyCount> kKeyNames{key_name(KeyName::Contact), key_name(KeyName::Down),
                                                         key_name(KeyName::Pass), key_name(KeyName::Up)};

// Context for error messages: "walk.json: keys.pass.rotations.LeftLeg: ...".
struct Where {
  std::string source;
  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw Error(source + ": " + field + ": " + what);
  }
};

double number(const json& v, const Where& w, const std::string& field) {
  if (!v.is_number()) w.fail(field, "expected a number, found " + std::string(v.type_name()));
  const double d = v.get<double>();
  if (!std::isfinite(d)) w.fail(field, "value is not finite");
  return d;
}

void check_fields(const json& obj, std::initializer_list<std::string_view> allowed, const Where& w,
                  const std::string& field) {
  if (!obj.is_object()) w.fail(field, "expected an object, found " + std::string(obj.type_name()));
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    if (std::find(allowed.begin(), allowed.end(), it.key()) != allowed.end()) continue;
    std::string list;
    for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    w.fail(field, "unknown field '" + it.key() + "' (expected " + list + ")");
  }
}

EulerOrder parse_order(const json& v, const Where& w) {
  if (!v.is_string()) w.fail("euler_order", "expected a string such as \"ZYX\"");
  std::string s = v.get<std::string>();
  EulerOrder o;
  if (s.size() != 3) w.fail("euler_order", "'" + s + "' is not a permutation of X, Y, Z");
  for (int i = 0; i < 3; ++i) {
    char c = static_cast<char>(std::toupper(static_cast<unsigned char>(s[static_cast<std::size_t>(i)])));
    if (c != 'X' && c != 'Y' && c != 'Z') w.fail("euler_order", "'" + s + "' is not a permutation of X, Y, Z");
    o.axes[static_cast<std::size_t>(i)] = c;
  }
  if (o.axes[0] == o.axes[1] || o.axes[1] == o.axes[2] || o.axes[0] == o.axes[2])
    w.fail("euler_order", "'" + s + "' repeats an axis");
  return o;
}

KeyPose parse_pose(const json& obj, const Skeleton& skel, const EulerOrder& order, const Where& w,
                   const std::string& field, bool allow_root) {
  if (allow_root) check_fields(obj, {"root", "rotations", "comment"}, w, field);
  else check_fields(obj, {"rotations", "comment"}, w, field);
  KeyPose pose;
  if (obj.contains("root")) {
    const auto& r = obj["root"];
    const std::string rf = field + ".root";
    check_fields(r, {"height", "forward", "side"}, w, rf);
    Vec3 off = Vec3::Zero();
    if (r.contains("side")) off.x() = number(r["side"], w, rf + ".side");
    if (r.contains("height")) {
      if (r["height"].is_string() && r["height"] == "floor") pose.height_on_floor = true;
      else if (r["height"].is_string()) w.fail(rf + ".height", "expected metres or \"floor\"");
      else off.y() = number(r["height"], w, rf + ".height");
    }
    if (r.contains("forward")) off.z() = number(r["forward"], w, rf + ".forward");
    if (off.norm() > 2.0) w.fail(rf, "root offset larger than 2 m; offsets are in metres");
    pose.root_offset = off;
  }
  if (obj.contains("rotations")) {
    const auto& rots = obj["rotations"];
    const std::string rf = field + ".rotations";
    if (!rots.is_object()) w.fail(rf, "expected an object {\"Joint\": [x, y, z], ...}");
    for (auto it = rots.begin(); it != rots.end(); ++it) {
      const std::string jf = rf + "." + it.key();
      const int j = find_joint_or_role(skel, it.key());
      if (j < 0) w.fail(jf, "unknown joint '" + it.key() + "' (not a joint of the skeleton nor a role name)");
      const auto& a = it.value();
      if (!a.is_array() || a.size() != 3) w.fail(jf, "expected [x, y, z] in degrees");
      Vec3 xyz(number(a[0], w, jf + "[0]"), number(a[1], w, jf + "[1]"), number(a[2], w, jf + "[2]"));
      if (xyz.cwiseAbs().maxCoeff() > 720.0) w.fail(jf, "angle beyond 720 degrees; angles are in degrees");
      if (pose.find(j)) w.fail(jf, "joint given twice (by name and by role?)");
      pose.set(j, euler_xyz_to_quat(xyz, order));
    }
  }
  return pose;
}

json root_json(const Vec3& off, bool floor) {
  auto r4 = [](double v) { return std::round(v * 1e4) / 1e4 + 0.0; };
  json h = floor ? json("floor") : json(r4(off.y()));
  return {{"side", r4(off.x())}, {"height", h}, {"forward", r4(off.z())}};
}

json pose_json(const KeyPose& p, const Skeleton& skel, const EulerOrder& order) {
  json o = json::object();
  if (p.root_offset) o["root"] = root_json(*p.root_offset, p.height_on_floor);
  json rots = json::object();
  auto sorted = p.rotations;
  std::sort(sorted.begin(), sorted.end(), [](auto& a, auto& b) { return a.first < b.first; });
  for (const auto& [j, q] : sorted) {
    Vec3 e = quat_to_euler_xyz(q, order);
    auto r3 = [](double v) { return std::round(v * 1e3) / 1e3 + 0.0; };  // +0.0: no "-0"
    if (e.cwiseAbs().maxCoeff() < 5e-4) continue;
    rots[skel.names[static_cast<std::size_t>(j)]] = json::array({r3(e.x()), r3(e.y()), r3(e.z())});
  }
  o["rotations"] = rots;
  return o;
}

io::Channel axis_channel(char a) {
  return a == 'X' ? io::Channel::Xrotation : a == 'Y' ? io::Channel::Yrotation : io::Channel::Zrotation;
}

}  // namespace

Quat euler_xyz_to_quat(const Vec3& xyz, const EulerOrder& order) {
  io::Channel ch[3];
  double deg[3];
  for (int i = 0; i < 3; ++i) {
    const char a = order.axes[static_cast<std::size_t>(i)];
    ch[i] = axis_channel(a);
    deg[i] = xyz[a - 'X'];
  }
  return io::euler_to_quat(ch, deg, 3);
}

Vec3 quat_to_euler_xyz(const Quat& q, const EulerOrder& order) {
  io::Channel ch[3];
  for (int i = 0; i < 3; ++i) ch[i] = axis_channel(order.axes[static_cast<std::size_t>(i)]);
  double deg[3];
  io::quat_to_euler(q, ch, deg);
  Vec3 xyz;
  for (int i = 0; i < 3; ++i) xyz[order.axes[static_cast<std::size_t>(i)] - 'X'] = deg[i];
  return xyz;
}

WalkKeys parse_walk_keys(std::string_view text, const Skeleton& skel, std::string_view source) {
  const Where w{std::string(source)};
  json doc;
  try {
    doc = json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {
    throw Error(std::string(source) + ": not valid JSON: " + e.what());
  }
  check_fields(doc, {"format", "name", "description", "skeleton", "frames_per_cycle", "fps", "euler_order", "timing",
                     "keys", "inbetweens", "shift", "stand", "floor_clamp", "comment"},
               w, "(top level)");
  WalkKeys k;
  if (doc.contains("format") && doc["format"] != "legwork-walk/1")
    w.fail("format", "expected \"legwork-walk/1\"");
  if (doc.contains("name")) {
    if (!doc["name"].is_string()) w.fail("name", "expected a string");
    k.name = doc["name"].get<std::string>();
  }
  if (doc.contains("description") && doc["description"].is_string()) k.description = doc["description"].get<std::string>();
  if (doc.contains("skeleton")) {
    if (!doc["skeleton"].is_string()) w.fail("skeleton", "expected a path string");
    k.skeleton_path = doc["skeleton"].get<std::string>();
  }
  if (doc.contains("frames_per_cycle")) {
    const double n = number(doc["frames_per_cycle"], w, "frames_per_cycle");
    if (n != std::floor(n) || n < 8 || n > 1000 || static_cast<int>(n) % 2)
      w.fail("frames_per_cycle", "expected an even whole number of frames from 8 to 1000");
    k.frames_per_cycle = static_cast<int>(n);
  }
  if (doc.contains("fps")) {
    k.fps = number(doc["fps"], w, "fps");
    if (k.fps <= 0 || k.fps > 1000) w.fail("fps", "expected a rate in (0, 1000] Hz");
  }
  if (doc.contains("euler_order")) k.euler = parse_order(doc["euler_order"], w);
  const double half = k.frames_per_cycle / 2.0;
  k.key_frames = {0, half / 4, half / 2, 3 * half / 4};
  if (doc.contains("timing")) {
    const auto& t = doc["timing"];
    check_fields(t, {"down", "pass", "up"}, w, "timing");
    for (int i = 1; i < kKeyCount; ++i) {
      const std::string nm(kKeyNames[static_cast<std::size_t>(i)]);
      if (t.contains(nm)) k.key_frames[static_cast<std::size_t>(i)] = number(t[nm], w, "timing." + nm);
    }
    for (int i = 1; i < kKeyCount; ++i)
      if (!(k.key_frames[static_cast<std::size_t>(i)] > k.key_frames[static_cast<std::size_t>(i - 1)]))
        w.fail("timing", "key frames must increase: contact (0) < down < pass < up");
    if (!(k.key_frames[3] < half)) w.fail("timing.up", "must come before the next contact at frame " + std::to_string(half));
  }
  if (!doc.contains("keys")) w.fail("keys", "missing: a walk needs the contact, down, pass and up key poses");
  const auto& keys = doc["keys"];
  if (!keys.is_object()) w.fail("keys", "expected an object with contact, down, pass, up");
  for (auto it = keys.begin(); it != keys.end(); ++it)
    if (std::find(kKeyNames.begin(), kKeyNames.end(), it.key()) == kKeyNames.end())
      w.fail("keys." + it.key(), "unknown key pose '" + it.key() + "' (expected contact, down, pass, up; the next contact is the mirror of contact)");
  for (int i = 0; i < kKeyCount; ++i) {
    const std::string nm(kKeyNames[static_cast<std::size_t>(i)]);
    if (!keys.contains(nm)) w.fail("keys", "missing key pose '" + nm + "'");
    k.keys[static_cast<std::size_t>(i)] = parse_pose(keys[nm], skel, k.euler, w, "keys." + nm, true);
    if (!k.keys[static_cast<std::size_t>(i)].root_offset) k.keys[static_cast<std::size_t>(i)].root_offset = Vec3::Zero();
  }
  if (doc.contains("inbetweens")) {
    const auto& ibs = doc["inbetweens"];
    if (!ibs.is_array()) w.fail("inbetweens", "expected an array of {\"frame\": F, ...}");
    for (std::size_t i = 0; i < ibs.size(); ++i) {
      const std::string f = "inbetweens[" + std::to_string(i) + "]";
      check_fields(ibs[i], {"frame", "root", "rotations", "comment"}, w, f);
      if (!ibs[i].contains("frame")) w.fail(f, "missing 'frame'");
      Inbetween ib;
      ib.frame = number(ibs[i]["frame"], w, f + ".frame");
      if (!(ib.frame > 0 && ib.frame < half))
        w.fail(f + ".frame", "must lie inside the first step, 0 < frame < " + std::to_string(half));
      for (double kf : k.key_frames)
        if (std::abs(kf - ib.frame) < 1e-9) w.fail(f + ".frame", "falls on a key pose; edit the key instead");
      json pose = ibs[i];
      pose.erase("frame");
      ib.pose = parse_pose(pose, skel, k.euler, w, f, true);
      k.inbetweens.push_back(std::move(ib));
    }
  }
  if (doc.contains("shift")) {
    const auto& s = doc["shift"];
    if (!s.is_object()) w.fail("shift", "expected an object {\"Joint\": frames, ...}");
    for (auto it = s.begin(); it != s.end(); ++it) {
      const int j = find_joint_or_role(skel, it.key());
      if (j < 0) w.fail("shift." + it.key(), "unknown joint '" + it.key() + "'");
      const double d = number(it.value(), w, "shift." + it.key());
      if (std::abs(d) >= half) w.fail("shift." + it.key(), "offset must be shorter than a step (" + std::to_string(half) + " frames)");
      k.shift.emplace_back(j, d);
    }
  }
  if (doc.contains("stand")) k.stand = parse_pose(doc["stand"], skel, k.euler, w, "stand", false);
  if (doc.contains("floor_clamp")) {
    if (!doc["floor_clamp"].is_boolean()) w.fail("floor_clamp", "expected true or false");
    k.floor_clamp = doc["floor_clamp"].get<bool>();
  }
  return k;
}

WalkKeys read_walk_keys(const std::string& path, const Skeleton& skel) {
  return parse_walk_keys(io::read_text_file(path), skel, path);
}

std::string walk_skeleton_path(const std::string& walk_path) {
  json doc;
  try {
    doc = json::parse(io::read_text_file(walk_path));
  } catch (const json::exception& e) {
    throw Error(walk_path + ": not valid JSON: " + e.what());
  }
  if (!doc.is_object() || !doc.contains("skeleton") || !doc["skeleton"].is_string()) return "";
  std::filesystem::path p(doc["skeleton"].get<std::string>());
  if (p.is_relative()) p = std::filesystem::path(walk_path).parent_path() / p;
  return p.lexically_normal().string();
}

WalkFile load_walk(const std::string& walk_path, const std::string& skeleton_bvh) {
  WalkFile w;
  if (skeleton_bvh.empty()) {
    const std::string sp = walk_skeleton_path(walk_path);
    if (sp.empty()) throw Error(walk_path + ": the walk names no \"skeleton\"; pass --skeleton FILE.bvh");
    io::BvhReadOptions o;
    o.drop_first_frame = true;
    w.skeleton = io::read_bvh(sp, o).motion.skeleton;
  } else {
    w.skeleton = io::read_bvh(skeleton_bvh).motion.skeleton;
  }
  w.keys = read_walk_keys(walk_path, w.skeleton);
  return w;
}

std::string format_walk_keys(const WalkKeys& k, const Skeleton& skel) {
  json doc = json::object();
  doc["format"] = "legwork-walk/1";
  doc["name"] = k.name;
  doc["description"] = k.description;
  if (!k.skeleton_path.empty()) doc["skeleton"] = k.skeleton_path;
  doc["frames_per_cycle"] = k.frames_per_cycle;
  doc["fps"] = std::round(k.fps * 1e3) / 1e3;
  doc["euler_order"] = k.euler.str();
  auto r2 = [](double v) { return std::round(v * 100) / 100 + 0.0; };
  doc["timing"] = {{"down", r2(k.key_frames[1])}, {"pass", r2(k.key_frames[2])}, {"up", r2(k.key_frames[3])}};
  json keys = json::object();
  for (int i = 0; i < kKeyCount; ++i)
    keys[std::string(kKeyNames[static_cast<std::size_t>(i)])] = pose_json(k.keys[static_cast<std::size_t>(i)], skel, k.euler);
  doc["keys"] = keys;
  if (!k.inbetweens.empty()) {
    json ibs = json::array();
    for (const auto& ib : k.inbetweens) {
      json p = pose_json(ib.pose, skel, k.euler);
      p["frame"] = ib.frame;
      ibs.push_back(p);
    }
    doc["inbetweens"] = ibs;
  }
  if (!k.shift.empty()) {
    json s = json::object();
    for (auto [j, d] : k.shift) s[skel.names[static_cast<std::size_t>(j)]] = d;
    doc["shift"] = s;
  }
  if (!k.floor_clamp) doc["floor_clamp"] = false;
  if (k.stand) {
    json st = pose_json(*k.stand, skel, k.euler);
    st.erase("root");
    doc["stand"] = st;
  }
  return doc.dump(2) + "\n";
}

void write_walk_keys(const std::string& path, const WalkKeys& keys, const Skeleton& skel) {
  io::write_text_file(path, format_walk_keys(keys, skel));
}

std::vector<std::pair<int, double>> parse_shift_spec(std::string_view spec, const Skeleton& skel) {
  std::vector<std::pair<int, double>> out;
  std::size_t pos = 0;
  while (pos <= spec.size()) {
    auto comma = spec.find(',', pos);
    if (comma == std::string_view::npos) comma = spec.size();
    std::string_view item = spec.substr(pos, comma - pos);
    pos = comma + 1;
    if (item.empty()) continue;
    auto eq = item.find('=');
    if (eq == std::string_view::npos)
      throw Error("--shift '" + std::string(item) + "': expected JOINT=FRAMES, e.g. LeftShoulder=0,LeftArm=1,LeftForeArm=2");
    std::string name(item.substr(0, eq));
    std::string val(item.substr(eq + 1));
    const int j = find_joint_or_role(skel, name);
    if (j < 0) throw Error("--shift: unknown joint '" + name + "'");
    char* end = nullptr;
    const double d = std::strtod(val.c_str(), &end);
    if (val.empty() || end != val.c_str() + val.size() || !std::isfinite(d))
      throw Error("--shift: '" + val + "' for " + name + " is not a number of frames");
    out.emplace_back(j, d);
  }
  return out;
}

}  // namespace legwork::walkcycle
