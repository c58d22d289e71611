// VMC protocol in and out over liblo (see vmc.hpp).
#include "vmc.hpp"

#include <legwork/core/engine.hpp>
#include <legwork/core/fk.hpp>

#include <lo/lo.h>

#include <cmath>
#include <cstdio>
#include <map>

namespace legwork::serve {

namespace {
constexpr double kStaleSeconds = 0.5;  // a device not heard from for this long counts as lost

void quiet_error(int num, const char* msg, const char* where) {
  std::fprintf(stderr, "legwork serve: vmc: liblo error %d: %s%s%s\n", num, msg ? msg : "", where ? " at " : "", where ? where : "");
}

double arg_number(char type, lo_arg* a) { return type == 'f' ? a->f : type == 'd' ? a->d : NAN; }
}  // namespace

struct Vmc::Input {
  struct Track {
    DevicePose pose;
    double heard = -1;  // seconds (t0-relative) of the last message
  };
  std::string left_serial, right_serial;
  Track head;
  std::map<std::string, Track> controllers, trackers;
  std::map<std::string, int> side;  // serial -> kLeft / kRight (controllers and trackers)
  bool fresh = false;
  SteadyClock::time_point t0;

  double now() const { return std::chrono::duration<double>(SteadyClock::now() - t0).count(); }

  // The side of a device at `p`, by where it is relative to the headset's heading.
  int side_of(const Vec3& p) const {
    const Vec3 fwd = head.pose.rotation * Vec3::UnitZ();
    const double yaw = std::atan2(fwd.x(), fwd.z());
    const Vec3 d = p - head.pose.position;
    const double local_x = std::cos(yaw) * d.x() - std::sin(yaw) * d.z();  // +x = the user's left
    return local_x >= 0 ? kLeft : kRight;
  }

  int assign(const std::string& serial, const Vec3& p, bool controller) {
    if (controller && serial == left_serial) return kLeft;
    if (controller && serial == right_serial) return kRight;
    const auto it = side.find(serial);
    if (it != side.end()) return it->second;
    if (head.heard < 0) return -1;  // decided once the headset is tracking
    const int s = side_of(p);
    side[serial] = s;
    return s;
  }

  void on(const char* path, const std::string& serial, const Vec3& p, const Quat& q) {
    const std::string_view pth(path);
    Track t{DevicePose{from_engine(Engine::Unity, p), from_engine(Engine::Unity, q).normalized(), true}, now()};
    if (pth == "/VMC/Ext/Hmd/Pos") head = t;
    else if (pth == "/VMC/Ext/Con/Pos") controllers[serial] = t;
    else trackers[serial] = t;
    fresh = true;
  }

  bool frame(TrackerFrame& f) {
    const double t = now();
    if (!fresh || head.heard < 0) return false;
    fresh = false;
    f = TrackerFrame{};
    f.time = t;
    const auto live = [&](const Track& tr) { return tr.heard >= 0 && t - tr.heard < kStaleSeconds; };
    if (live(head)) f.head() = head.pose;
    for (auto& [serial, tr] : controllers) {
      const int s = assign(serial, tr.pose.position, true);
      if (s >= 0 && live(tr)) f.hand(s) = tr.pose;
    }
    for (auto& [serial, tr] : trackers) {
      const int s = assign(serial, tr.pose.position, false);
      if (s >= 0 && live(tr)) f.foot(s) = tr.pose;
    }
    return true;
  }
};

namespace {
int on_device(const char* path, const char* types, lo_arg** argv, int argc, lo_message, void* user) {
  if (argc < 8 || types[0] != 's') return 0;
  double v[7];
  for (int i = 0; i < 7; ++i) {
    v[i] = arg_number(types[i + 1], argv[i + 1]);
    if (!std::isfinite(v[i])) return 0;  // a malformed sample is ignored
  }
  static_cast<Vmc::Input*>(user)->on(path, &argv[0]->s, Vec3(v[0], v[1], v[2]), Quat(v[6], v[3], v[4], v[5]));
  return 0;
}

std::pair<std::string, std::string> split_host_port(const std::string& s) {
  const auto c = s.rfind(':');
  if (c == std::string::npos || c == 0 || c + 1 == s.size())
    throw Error("--vmc-out '" + s + "': expected HOST:PORT (the VMC receiver's default port is 39539)");
  return {s.substr(0, c), s.substr(c + 1)};
}
}  // namespace

Vmc::Vmc(const ServeOptions& opt, const Resources& res, Workers& workers)
    : opt_(opt), res_(res), workers_(workers), input_(std::make_unique<Input>()) {
  if (!opt.vmc_out.empty()) {
    const auto [host, port] = split_host_port(opt.vmc_out);
    out_address_ = lo_address_new(host.c_str(), port.c_str());
    if (!out_address_) throw Error("--vmc-out '" + opt.vmc_out + "': not a usable UDP address");
  }
  if (opt.vmc_in_port > 0) {
    const std::string port = std::to_string(opt.vmc_in_port);
    in_server_ = lo_server_new_with_proto(port.c_str(), LO_UDP, quiet_error);
    if (!in_server_) throw Error("--vmc-in " + port + ": cannot listen on that UDP port (in use?)");
    for (const char* p : {"/VMC/Ext/Hmd/Pos", "/VMC/Ext/Con/Pos", "/VMC/Ext/Tra/Pos"})
      lo_server_add_method(static_cast<lo_server>(in_server_), p, nullptr, on_device, input_.get());
    input_->left_serial = opt.vmc_left_serial;
    input_->right_serial = opt.vmc_right_serial;
    Hello hello;
    hello.method.method = opt.vmc_method;
    std::unique_ptr<Method> m = make_method(res_, hello.method);
    RecordSpec rec;
    if (!opt.record_dir.empty()) rec = {opt.record_dir, opt.record_max_seconds};
    Sink sink = [verbose = opt.verbose](Outgoing o) {
      if (verbose && !o.droppable) std::fprintf(stderr, "legwork serve: vmc avatar: %s\n", o.data.c_str());
    };
    const std::vector<int> joints = output_joints(m->skeleton(), {});
    in_avatar_ = std::make_shared<Avatar>("vmc", res_, std::move(m), hello, joints, std::move(sink), rec);
    offer(in_avatar_);
  }
}

Vmc::~Vmc() {
  stop();
  if (in_server_) lo_server_free(static_cast<lo_server>(in_server_));
  if (out_address_) lo_address_free(static_cast<lo_address>(out_address_));
}

void Vmc::start() {
  if (!in_server_ || running_.exchange(true)) return;
  t0_ = SteadyClock::now();
  input_->t0 = t0_;
  thread_ = std::thread([this] { input_loop(); });
}

void Vmc::stop() {
  running_ = false;
  if (thread_.joinable()) thread_.join();
  if (in_avatar_ && in_avatar_->close()) workers_.schedule(in_avatar_);
}

void Vmc::input_loop() {
  const auto period = std::chrono::duration_cast<SteadyClock::duration>(std::chrono::duration<double>(1.0 / opt_.vmc_rate_hz));
  auto next = SteadyClock::now() + period;
  std::uint64_t seq = 0;
  while (running_) {
    lo_server_recv_noblock(static_cast<lo_server>(in_server_), 1);
    if (SteadyClock::now() < next) continue;
    next += period;
    TrackerFrame f;
    if (input_->frame(f) && in_avatar_->push(f, ++seq, SteadyClock::now())) workers_.schedule(in_avatar_);
  }
}

void Vmc::offer(const std::shared_ptr<Avatar>& a) {
  if (!out_address_) return;
  {
    std::lock_guard lock(mu_);
    if (owner_) return;
    owner_ = a.get();
  }
  a->set_listener([this](const Skeleton& skel, ConstPoseRef pose, std::span<const Vec3>) { send_pose(skel, pose); });
}

void Vmc::release(const Avatar* a) {
  std::lock_guard lock(mu_);
  if (owner_ == a) owner_ = nullptr;
}

void Vmc::send_pose(const Skeleton& skel, ConstPoseRef pose) {
  std::lock_guard lock(mu_);
  if (bones_for_ != &skel) {
    bones_ = humanoid_bones(skel);
    bones_for_ = &skel;
    model_.resize(static_cast<std::size_t>(skel.joint_count()));
    bone_out_.resize(bones_.size());
  }
  forward_kinematics(skel, pose, model_);
  humanoid_pose(bones_, model_, bone_out_);
  lo_bundle b = lo_bundle_new(LO_TT_IMMEDIATE);
  const auto add = [&](const char* path, const char* name, const Vec3& p, const Quat& q) {
    lo_message m = lo_message_new();
    lo_message_add_string(m, name);
    for (double v : {p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w()}) lo_message_add_float(m, static_cast<float>(v));
    lo_bundle_add_message(b, path, m);
  };
  add("/VMC/Ext/Root/Pos", "root", Vec3::Zero(), Quat::Identity());
  for (std::size_t i = 0; i < bones_.size(); ++i)
    add("/VMC/Ext/Bone/Pos", std::string(bones_[i].name).c_str(), bone_out_[i].position, bone_out_[i].rotation);
  lo_message ok = lo_message_new();
  lo_message_add_int32(ok, 1);
  lo_bundle_add_message(b, "/VMC/Ext/OK", ok);
  lo_message t = lo_message_new();
  lo_message_add_float(t, static_cast<float>(std::chrono::duration<double>(SteadyClock::now() - t0_).count()));
  lo_bundle_add_message(b, "/VMC/Ext/T", t);
  lo_send_bundle(static_cast<lo_address>(out_address_), b);
  lo_bundle_free_recursive(b);
}

}  // namespace legwork::serve
