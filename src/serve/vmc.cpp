// VMC protocol in and out over liblo (see vmc.hpp).
#include "vmc.hpp"

#include "vmc_input.hpp"

#include <legwork/core/engine.hpp>
#include <legwork/core/fk.hpp>

#include <lo/lo.h>

#include <cstdio>

namespace legwork::serve {

namespace {
void quiet_error(int num, const char* msg, const char* where) {
  std::fprintf(stderr, "legwork serve: vmc: liblo error %d: %s%s%s\n", num, msg ? msg : "", where ? " at " : "", where ? where : "");
}

std::pair<std::string, std::string> split_host_port(const std::string& s) {
  const auto c = s.rfind(':');
  if (c == std::string::npos || c == 0 || c + 1 == s.size())
    throw Error("--vmc-out '" + s + "': expected HOST:PORT (the VMC receiver's default port is 39539)");
  return {s.substr(0, c), s.substr(c + 1)};
}
}  // namespace

Vmc::Vmc(const ServeOptions& opt, const Resources& res, Workers& workers)
    : opt_(opt), res_(res), workers_(workers), input_(std::make_unique<VmcInput>()) {
  if (!opt.vmc_out.empty()) {
    const auto [host, port] = split_host_port(opt.vmc_out);
    out_address_ = lo_address_new(host.c_str(), port.c_str());
    if (!out_address_) throw Error("--vmc-out '" + opt.vmc_out + "': not a usable UDP address");
  }
  if (opt.vmc_in_port > 0) {
    const std::string port = std::to_string(opt.vmc_in_port);
    in_server_ = lo_server_new_with_proto(port.c_str(), LO_UDP, quiet_error);
    if (!in_server_) throw Error("--vmc-in " + port + ": cannot listen on that UDP port (in use?)");
    input_->listen(in_server_);
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
