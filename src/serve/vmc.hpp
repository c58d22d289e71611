#pragma once
// VMC protocol (OSC over UDP, liblo) for `legwork serve` (private header).
// Input (--vmc-in PORT): /VMC/Ext/Hmd/Pos, /VMC/Ext/Con/Pos, /VMC/Ext/Tra/Pos
// drive one avatar, sampled at --vmc-rate. Output (--vmc-out HOST:PORT): the
// VMC-driven avatar's body (or, without --vmc-in, the first WebSocket
// session's) as a Performer: /VMC/Ext/Root/Pos, /VMC/Ext/Bone/Pos per
// humanoid bone, /VMC/Ext/OK, /VMC/Ext/T, one bundle per pose.
#include <legwork/serve/avatar.hpp>
#include <legwork/serve/humanoid.hpp>
#include <legwork/serve/server.hpp>

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

namespace legwork::serve {

struct VmcInput;  // receiver state (vmc_input.hpp)

class Vmc {
 public:
  // Throws legwork::Error for a bad --vmc-out address or a --vmc-in port in use.
  Vmc(const ServeOptions& opt, const Resources& res, Workers& workers);
  ~Vmc();
  void start();
  void stop();
  // A new WebSocket avatar: takes the VMC output when nobody has it.
  void offer(const std::shared_ptr<Avatar>& a);
  void release(const Avatar* a);

 private:
  void send_pose(const Skeleton& skel, ConstPoseRef pose);
  void input_loop();

  ServeOptions opt_;
  Resources res_;
  Workers& workers_;
  void* out_address_ = nullptr;  // lo_address
  void* in_server_ = nullptr;    // lo_server
  std::unique_ptr<VmcInput> input_;  // receiver state (vmc_input.hpp)
  std::shared_ptr<Avatar> in_avatar_;
  std::mutex mu_;
  const Avatar* owner_ = nullptr;
  std::vector<HumanoidBone> bones_;
  const Skeleton* bones_for_ = nullptr;
  std::vector<Transform> model_;
  std::vector<BoneTransform> bone_out_;
  SteadyClock::time_point t0_ = SteadyClock::now();
  std::thread thread_;
  std::atomic<bool> running_{false};
};

}  // namespace legwork::serve
