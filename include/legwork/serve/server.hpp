#pragma once
// `legwork serve`: HTTP + WebSocket on one port (Boost.Beast), one avatar per
// WebSocket connection over one shared read-only accent database, synthesis
// on worker threads, optional VMC (OSC/UDP) input and output.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace legwork::serve {

// Bounds of ServeOptions::idle_timeout_seconds (--idle-timeout): a tenth of a second to a week.
inline constexpr double kMinIdleTimeoutSeconds = 0.1, kMaxIdleTimeoutSeconds = 604800;

struct ServeOptions {
  std::string db_path;        // accent database (.lwdb); empty: ik only (needs skeleton_path)
  std::string skeleton_path;  // BVH whose skeleton drives ik when there is no database
  std::string wip_table;      // learned walking-in-place mapping ("" = sessions cannot ask for mapping "learned")
  std::string walks_dir;      // walk files for the walker method ("" = no walker)
  std::string host = "127.0.0.1";
  int port = 8080;            // 0: any free port (see Server::port())
  std::string web_dir;        // static files ("" = none)
  std::string trials_dir;     // BVH trials for /api/trials ("" = none)
  int vmc_in_port = 0;        // 0: no VMC input
  std::string vmc_out;        // HOST:PORT, "" = no VMC output
  std::string vmc_method = "ik";    // method of the VMC-driven avatar
  std::string vmc_left_serial, vmc_right_serial;  // controller serials; empty: by side at start
  double vmc_rate_hz = 90;    // VMC input sampling and output rate
  int max_sessions = 64;
  double max_rate_hz = 120;   // per-session frame rate limit by the frames' own times (rate_limit.hpp)
  std::size_t max_message_bytes = 64 * 1024;
  std::string record_dir;     // record sessions here ("" = off)
  double record_max_seconds = 300;
  double idle_timeout_seconds = 300;  // a WebSocket with nothing received this long is closed (pinged at half)
  int workers = 1;            // synthesis threads
  bool verbose = false;
};

struct ServerStats {
  std::uint64_t sessions_opened = 0, sessions_closed = 0, frames = 0, poses = 0, errors = 0, refused = 0;
  std::uint64_t rate_dropped = 0;  // frames dropped by the rate limit (rate_limit.hpp)
  int live_sessions = 0;
};

class Server {
 public:
  // Loads the database, binds the port. Throws legwork::Error with a clear
  // message (missing database, port in use, bad --vmc-out...).
  explicit Server(ServeOptions opt);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  unsigned short port() const;  // the bound port
  // Runs until stop() (or SIGINT/SIGTERM when handle_signals). Blocks.
  void run(bool handle_signals = false);
  // Thread-safe: closes every session (recordings are written) and returns run().
  void stop();
  ServerStats stats() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace legwork::serve
