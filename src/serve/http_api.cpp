// Static files and the JSON API of `legwork serve` (see http_api.hpp).
#include "http_api.hpp"

#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/core/tracker.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/serve/protocol.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace legwork::serve {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr std::uintmax_t kMaxStaticBytes = 64u << 20;

HttpReply error_reply(unsigned status, std::string_view code, const std::string& message) {
  return {status, "application/json", format_error(code, message)};
}

std::string mime_type(const fs::path& p) {
  static const std::map<std::string, std::string> types{
      {".html", "text/html; charset=utf-8"}, {".js", "text/javascript; charset=utf-8"},
      {".mjs", "text/javascript; charset=utf-8"}, {".css", "text/css; charset=utf-8"},
      {".json", "application/json"}, {".png", "image/png"}, {".jpg", "image/jpeg"},
      {".svg", "image/svg+xml"}, {".glb", "model/gltf-binary"}, {".gltf", "model/gltf+json"},
      {".wasm", "application/wasm"}, {".map", "application/json"}, {".ico", "image/x-icon"},
      {".txt", "text/plain; charset=utf-8"}, {".bvh", "text/plain; charset=utf-8"}};
  const auto it = types.find(p.extension().string());
  return it == types.end() ? "application/octet-stream" : it->second;
}

int hex(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Percent-decoding; false on a malformed escape or a NUL.
bool url_decode(std::string_view in, std::string& out) {
  out.clear();
  for (std::size_t i = 0; i < in.size(); ++i) {
    if (in[i] == '%') {
      if (i + 2 >= in.size() || hex(in[i + 1]) < 0 || hex(in[i + 2]) < 0) return false;
      const char c = static_cast<char>(hex(in[i + 1]) * 16 + hex(in[i + 2]));
      if (c == '\0') return false;
      out += c;
      i += 2;
    } else {
      out += in[i] == '+' ? ' ' : in[i];
    }
  }
  return true;
}

// A relative path made only of plain segments (no "..", ".", empty or hidden ones).
bool safe_relative(const std::string& rel) {
  if (rel.empty() || rel.front() == '/' || rel.find('\\') != std::string::npos) return false;
  std::stringstream ss(rel);
  std::string seg;
  while (std::getline(ss, seg, '/'))
    if (seg.empty() || seg.front() == '.') return false;
  return true;
}

std::map<std::string, std::string> query_params(std::string_view q) {
  std::map<std::string, std::string> out;
  std::size_t at = 0;
  while (at <= q.size()) {
    const std::size_t amp = std::min(q.find('&', at), q.size());
    const std::string_view kv = q.substr(at, amp - at);
    const std::size_t eq = kv.find('=');
    std::string k, v;
    if (url_decode(kv.substr(0, eq), k) && (eq == std::string_view::npos || url_decode(kv.substr(eq + 1), v))) out[k] = v;
    at = amp + 1;
  }
  return out;
}

HttpReply static_file(const ApiContext& ctx, const std::string& path) {
  if (ctx.web_dir.empty()) return error_reply(404, "not_found", "no viewer: start the server with --web DIR (the built web/dist)");
  std::string rel = path.substr(1);
  if (rel.empty() || rel.back() == '/') rel += "index.html";
  if (!safe_relative(rel)) return error_reply(404, "not_found", "no such file");
  std::error_code ec;
  const fs::path root = fs::canonical(ctx.web_dir, ec);
  if (ec) return error_reply(404, "not_found", "viewer folder missing: " + ctx.web_dir);
  const fs::path file = fs::weakly_canonical(root / rel, ec);
  const auto [r, f] = std::mismatch(root.begin(), root.end(), file.begin(), file.end());
  if (ec || r != root.end() || !fs::is_regular_file(file, ec)) return error_reply(404, "not_found", "no such file: /" + rel);
  if (fs::file_size(file, ec) > kMaxStaticBytes) return error_reply(404, "not_found", "file too large: /" + rel);
  std::ifstream in(file, std::ios::binary);
  std::ostringstream body;
  body << in.rdbuf();
  return {200, mime_type(file), body.str()};
}

json vec_json(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

json trial_json(const ApiContext& ctx, const std::string& name, double rate) {
  io::BvhReadOptions ro;
  ro.drop_first_frame = true;
  const Motion m = io::load_bvh((fs::path(ctx.trials_dir) / (name + ".bvh")).string(), ro);
  const std::vector<TrackerFrame> frames = tracker_frames_from_motion(m, rate, 200'000);
  json jf = json::array();
  const char* keys[kDeviceCount] = {"head", "left", "right", "left_foot", "right_foot"};
  for (const TrackerFrame& f : frames) {
    json o = {{"t", f.time}};
    for (int d = 0; d < kDeviceCount; ++d) {
      const DevicePose& p = f.devices[static_cast<std::size_t>(d)];
      if (!p.valid) continue;
      o[keys[d]] = {{"p", vec_json(p.position)}, {"q", {p.rotation.w(), p.rotation.x(), p.rotation.y(), p.rotation.z()}}};
    }
    jf.push_back(std::move(o));
  }
  Pose pose(m.skeleton);
  std::vector<Vec3> world(static_cast<std::size_t>(m.joint_count()));
  json positions = json::array();
  for (const TrackerFrame& f : frames) {
    sample_motion(m, f.time, pose.ref());
    forward_positions(m.skeleton, pose.ref(), world);
    json row = json::array();
    for (const Vec3& p : world)
      for (int i = 0; i < 3; ++i) row.push_back(std::round(p[i] * 1e5) / 1e5);
    positions.push_back(std::move(row));
  }
  // The subject's standing height: replay clients pass it as user_height so
  // the avatars are the subject's size (an IK body taller than the headset
  // height would hang crouched with its feet off the floor).
  const double height = std::round(measure_body(m.skeleton).standing_height * 1e3) / 1e3;
  return {{"name", name}, {"fps", rate}, {"height", height}, {"frames", std::move(jf)},
          {"truth", {{"names", m.skeleton.names}, {"parents", m.skeleton.parents}, {"positions", std::move(positions)}}}};
}

HttpReply api(const ApiContext& ctx, const std::string& path, const std::map<std::string, std::string>& q) {
  if (path == "/api/info") {
    json j = {{"version", kProtocolVersion}, {"methods", available_methods(ctx.resources)}, {"classes", ctx.classes},
              {"database", ctx.resources.database_name}};
    return {200, "application/json", j.dump()};
  }
  if (path == "/api/trials") return {200, "application/json", json{{"trials", list_trials(ctx.trials_dir)}}.dump()};
  if (path == "/api/trial") {
    const auto n = q.find("name");
    if (n == q.end() || !safe_relative(n->second + ".bvh"))
      return error_reply(400, "bad_value", "/api/trial needs name=<trial> from /api/trials (e.g. walking/07_02)");
    const auto names = list_trials(ctx.trials_dir);
    if (!std::binary_search(names.begin(), names.end(), n->second))
      return error_reply(404, "not_found", "no trial '" + n->second + "' (see /api/trials)");
    double rate = 90;
    if (const auto r = q.find("rate"); r != q.end()) {
      char* end = nullptr;
      rate = std::strtod(r->second.c_str(), &end);
      if (end == r->second.c_str() || *end || !(rate >= 1 && rate <= 240))
        return error_reply(400, "bad_value", "rate must be a number of Hz in [1, 240] (got '" + r->second + "')");
    }
    return {200, "application/json", trial_json(ctx, n->second, rate).dump()};
  }
  return error_reply(404, "not_found", "no API endpoint " + path + " (have /api/info, /api/trials, /api/trial)");
}

}  // namespace

std::vector<std::string> list_trials(const std::string& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  if (dir.empty() || !fs::is_directory(dir, ec)) return out;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (!it->is_regular_file(ec) || it->path().extension() != ".bvh") continue;
    std::string rel = fs::relative(it->path(), dir, ec).replace_extension().generic_string();
    if (!ec && safe_relative(rel + ".bvh")) out.push_back(rel);
  }
  std::sort(out.begin(), out.end());
  return out;
}

HttpReply handle_http(const ApiContext& ctx, std::string_view method, std::string_view target) {
  if (method != "GET" && method != "HEAD") return error_reply(405, "bad_message", "only GET and HEAD are served");
  const std::size_t qm = target.find('?');
  std::string path;
  if (!url_decode(target.substr(0, qm), path) || path.empty() || path.front() != '/')
    return error_reply(400, "bad_message", "malformed request path");
  const auto q = qm == std::string_view::npos ? std::map<std::string, std::string>{} : query_params(target.substr(qm + 1));
  try {
    if (path.rfind("/api/", 0) == 0) return api(ctx, path, q);
    return static_file(ctx, path);
  } catch (const std::exception& e) {
    return error_reply(500, "server_error", e.what());
  }
}

}  // namespace legwork::serve
