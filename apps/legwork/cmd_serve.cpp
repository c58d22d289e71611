// legwork serve: live avatars over WebSocket (browser viewer) and VMC (OSC).
#include "command.hpp"

#include <legwork/serve/server.hpp>

#include <filesystem>
#include <iostream>

namespace legwork::cli {
namespace {

// A default folder: relative to the working directory, else to the source tree.
std::string default_path(const std::string& rel) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(rel, ec)) return rel;
#ifdef LEGWORK_SOURCE_DIR
  const fs::path p = fs::path(LEGWORK_SOURCE_DIR) / rel;
  if (fs::exists(p, ec)) return p.string();
#endif
  return "";
}

void register_serve(CLI::App& app) {
  auto o = std::make_shared<serve::ServeOptions>();
  auto* cmd = app.add_subcommand("serve",
                                 "Live avatars: HTTP + WebSocket (viewer, docs/protocol.md) and VMC (OSC/UDP) in and out.\n"
                                 "Example: legwork serve --db all.lwdb --port 8080   then open http://127.0.0.1:8080/");
  cmd->add_option("--db", o->db_path, "accent database (.lwdb, from 'legwork accent build'); without it the ik and wip methods on --skeleton");
  cmd->add_option("--wip-table", o->wip_table,
                  "learned walking-in-place mapping for sessions asking \"mapping\": \"learned\" (default: "
                  "data/wip/learned_mapping.txt when present; `legwork wip learn` makes one)");
  cmd->add_option("--walks", o->walks_dir,
                  "walk files (legwork-walk/1) for sessions of method \"walker\" (default: data/walks when present)");
  cmd->add_option("--skeleton", o->skeleton_path, "BVH whose skeleton the ik/wip/combined avatars use when there is no --db (default: data/cmu/bvh/walking/07_01.bvh)");
  cmd->add_option("--host", o->host, "address to bind (127.0.0.1 = this machine only; 0.0.0.0 = every interface)")->capture_default_str();
  cmd->add_option("--port", o->port, "HTTP + WebSocket port (0 = any free port, printed)")->capture_default_str()->check(CLI::Range(0, 65535));
  cmd->add_option("--web", o->web_dir, "viewer folder served at / (default: web/dist if present)");
  cmd->add_option("--trials", o->trials_dir, "BVH trials for /api/trials and replay (default: data/cmu/bvh)");
  cmd->add_option("--vmc-in", o->vmc_in_port, "receive VMC trackers (/VMC/Ext/Hmd|Con|Tra/Pos) on this UDP port")->check(CLI::Range(1, 65535));
  cmd->add_option("--vmc-out", o->vmc_out, "send the body as a VMC Performer to HOST:PORT (Marionette default port 39539)");
  cmd->add_option("--vmc-method", o->vmc_method, "method of the VMC-driven avatar (accent, ik, wip, combined, walker)")->capture_default_str();
  cmd->add_option("--vmc-left", o->vmc_left_serial, "serial of the left controller (default: by side of the headset when tracking starts)");
  cmd->add_option("--vmc-right", o->vmc_right_serial, "serial of the right controller");
  cmd->add_option("--vmc-rate", o->vmc_rate_hz, "VMC input sampling rate, Hz")->capture_default_str()->check(CLI::Range(1.0, 240.0));
  cmd->add_option("--max-sessions", o->max_sessions, "most WebSocket sessions at once")->capture_default_str()->check(CLI::Range(1, 100000));
  cmd->add_option("--max-rate", o->max_rate_hz, "most frames per second of a session's own time stamps (above: dropped; wall-clock ceiling twice this)")->capture_default_str()->check(positive_number());
  cmd->add_option("--record", o->record_dir, "record each session here when it ends: input as tracker CSV, output as BVH");
  cmd->add_option("--record-max-seconds", o->record_max_seconds, "longest recording per session")->capture_default_str()->check(positive_number());
  cmd->add_option("--idle-timeout", o->idle_timeout_seconds, "seconds a WebSocket may send nothing before it is closed (pinged at half of it)")->capture_default_str()->check(CLI::Range(serve::kMinIdleTimeoutSeconds, serve::kMaxIdleTimeoutSeconds));
  cmd->add_option("--workers", o->workers, "synthesis threads (0: synthesize on the network thread, fastest for one process per core)")->capture_default_str()->check(CLI::Range(0, 256));
  cmd->add_flag("--verbose", o->verbose, "log sessions to stderr");
  cmd->callback([o] {
    if (o->web_dir.empty()) o->web_dir = default_path("web/dist");
    if (o->trials_dir.empty()) o->trials_dir = default_path("data/cmu/bvh");
    if (o->wip_table.empty()) o->wip_table = default_path("data/wip/learned_mapping.txt");
    if (o->walks_dir.empty()) o->walks_dir = default_path("data/walks");
    if (o->db_path.empty() && o->skeleton_path.empty() && !o->trials_dir.empty()) {
      const auto p = std::filesystem::path(o->trials_dir) / "walking" / "07_01.bvh";
      if (std::filesystem::exists(p)) o->skeleton_path = p.string();
    }
    serve::Server server(*o);
    std::cout << "legwork serve: listening on http://" << o->host << ":" << server.port() << "/ (WebSocket ws://" << o->host
              << ":" << server.port() << "/ws)" << std::endl;
    if (!o->vmc_out.empty()) std::cout << "legwork serve: VMC out to " << o->vmc_out << std::endl;
    if (o->vmc_in_port > 0) std::cout << "legwork serve: VMC in on UDP port " << o->vmc_in_port << std::endl;
    server.run(true);
    const serve::ServerStats s = server.stats();
    std::cout << "legwork serve: stopped (" << s.sessions_opened << " sessions, " << s.frames << " frames, " << s.errors
              << " errors)" << std::endl;
  });
}

}  // namespace

LEGWORK_COMMAND(register_serve, 80);

}  // namespace legwork::cli
