// serve_load: a load benchmark for `legwork serve` on loopback (not a timed
// test). N concurrent replay clients each stream a real CMU trial's head +
// hands at 90 Hz (binary frames) and time every pose's round trip. Bounded in
// clients and time; stops by itself.
//
//   serve_load --port P [--clients N] [--seconds S] [--method ik] [--ramp] [--json out.json]
//
// --ramp: N = 10, 20, 40, ... (up to --max-clients) until answers < 99 %,
// then halving steps between the last good N and the first bad one;
// "sustained" is the largest N found that kept p99 <= --p99-ms with every
// frame answered (the doubling steps below it kept it too). --server-pids adds the servers'
// CPU time per frame (from /proc) and the avatars per core it implies, --proxy-pids
// HAProxy's; the client's own CPU per frame is always printed.
#include <legwork/core/measure.hpp>
#include <legwork/core/tracker.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/serve/protocol.hpp>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <utility>  // before Asio (Boost 1.74 awaitable.hpp needs std::exchange)

#include <boost/asio.hpp>
#include <boost/beast.hpp>

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <unistd.h>
#include <vector>

namespace {

namespace beast = boost::beast;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using Clock = std::chrono::steady_clock;
using json = nlohmann::json;
using namespace legwork;

// The processes' threads' times in seconds, from Linux /proc/PID/task/TID/schedstat (exact
// nanoseconds, not the 10 ms ticks of /proc/PID/stat): on a CPU, and waiting on a run queue
// for one (CPU time other processes took from them).
struct SchedTimes {
  double cpu = 0, wait = 0;
};
SchedTimes sched_times(const std::vector<int>& pids) {
  SchedTimes total;
  for (int pid : pids) {
    const std::string dir = "/proc/" + std::to_string(pid) + "/task";
    std::error_code ec;
    for (const auto& t : std::filesystem::directory_iterator(dir, ec)) {
      std::ifstream in(t.path() / "schedstat");
      unsigned long long run = 0, wait = 0;
      if (in >> run >> wait) total.cpu += static_cast<double>(run) * 1e-9, total.wait += static_cast<double>(wait) * 1e-9;
    }
  }
  return total;
}

struct Run {
  int clients = 0;
  double server_cpu_us_per_frame = 0;  // with --server-pids
  double server_wait_us_per_frame = 0, client_wait_us_per_frame = 0;  // run-queue waits (CPU taken by others)
  double proxy_cpu_us_per_frame = 0;   // with --proxy-pids (HAProxy)
  double client_cpu_us_per_frame = 0;  // this load client's own
  std::uint64_t sent = 0, answered = 0, errors = 0, failed_clients = 0;
  std::vector<double> latency_ms;
  double p50 = 0, p90 = 0, p99 = 0, max = 0, answered_share = 0;
};

constexpr std::uint32_t kWarmupFrames = 45;  // the first half second of each client is not timed

constexpr long kPeriodUs = 11111;  // 90 Hz

class ReplayClient : public std::enable_shared_from_this<ReplayClient> {
 public:
  // phase: when in the 11.1 ms frame period this client sends (0..1);
  // delay: whole periods before its first frame (--start-spread).
  // hello: the session's hello message (JSON text).
  ReplayClient(net::io_context& ioc, const std::vector<std::string>& frames, Run& run, std::string hello, double seconds,
               int offset, double phase, long delay)
      : ws_(net::make_strand(ioc)), timer_(ioc), frames_(frames), run_(run), hello_(std::move(hello)), seconds_(seconds),
        index_(static_cast<std::size_t>(offset) % frames.size()), phase_(phase), delay_(delay) {}

  void start(const tcp::endpoint& ep) {
    beast::get_lowest_layer(ws_).expires_after(std::chrono::seconds(10));
    beast::get_lowest_layer(ws_).async_connect(ep, [self = shared_from_this(), ep](beast::error_code ec) {
      if (ec) return self->fail();
      beast::get_lowest_layer(self->ws_).expires_never();
      beast::get_lowest_layer(self->ws_).socket().set_option(tcp::no_delay(true), ec);
      self->ws_.async_handshake("127.0.0.1:" + std::to_string(ep.port()), "/ws", [self](beast::error_code e) {
        if (e) return self->fail();
        self->hello();
      });
    });
  }

 private:
  void fail() {
    if (!failed_) ++run_.failed_clients;
    failed_ = true;
  }

  void hello() {
    ws_.text(true);
    ws_.async_write(net::buffer(hello_), [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) return self->fail();
      self->read();
    });
  }

  void read() {
    ws_.async_read(buf_, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) return self->done_ ? void() : self->fail();
      self->on_message();
      self->buf_.consume(self->buf_.size());
      self->read();
    });
  }

  void on_message() {
    const auto now = Clock::now();
    if (ws_.got_text()) {
      const json j = json::parse(beast::buffers_to_string(buf_.data()), nullptr, false);
      if (j.value("type", "") == "welcome") {
        next_ = now + std::chrono::microseconds(static_cast<long>(phase_ * kPeriodUs) + delay_ * kPeriodUs);
        start_ = next_;
        timer_.expires_at(next_);
        timer_.async_wait([self = shared_from_this()](beast::error_code ec) {
          if (!ec && !self->failed_) self->tick();
        });
      } else {
        ++run_.errors;
      }
      return;
    }
    const auto d = buf_.cdata();
    const auto pose = serve::parse_binary_pose(std::span(static_cast<const std::byte*>(d.data()), d.size()));
    if (pose.seq >= 1 && pose.seq <= sent_at_.size()) {
      ++run_.answered;
      if (pose.seq <= kWarmupFrames) return;  // connection set-up and first allocations
      run_.latency_ms.push_back(std::chrono::duration<double, std::milli>(now - sent_at_[pose.seq - 1]).count());
    }
  }

  void tick() {
    if (std::chrono::duration<double>(Clock::now() - start_).count() >= seconds_) {
      timer_.expires_after(std::chrono::milliseconds(200));  // last answers
      timer_.async_wait([self = shared_from_this()](beast::error_code) {
        self->done_ = true;
        beast::get_lowest_layer(self->ws_).close();
      });
      return;
    }
    if (!writing_) {
      out_ = frames_[index_++ % frames_.size()];
      // Rewrite the time so it keeps increasing across trial loops.
      const double t = static_cast<double>(sent_at_.size()) / 90.0;
      std::memcpy(out_.data() + 4, &t, sizeof t);
      sent_at_.push_back(Clock::now());
      ++run_.sent;
      writing_ = true;
      ws_.binary(true);
      ws_.async_write(net::buffer(out_), [self = shared_from_this()](beast::error_code ec, std::size_t) {
        self->writing_ = false;
        if (ec) self->fail();
      });
    }
    next_ += std::chrono::microseconds(kPeriodUs);
    timer_.expires_at(next_);
    timer_.async_wait([self = shared_from_this()](beast::error_code ec) {
      if (!ec && !self->failed_) self->tick();
    });
  }

  websocket::stream<beast::tcp_stream> ws_;
  net::steady_timer timer_;
  const std::vector<std::string>& frames_;
  Run& run_;
  std::string hello_, out_;
  double seconds_;
  std::size_t index_;
  double phase_;
  long delay_;
  beast::flat_buffer buf_;
  std::vector<Clock::time_point> sent_at_;
  Clock::time_point start_, next_;
  bool writing_ = false, failed_ = false, done_ = false;
};

// Clients send at evenly spread phases of the frame period, as independent
// headsets do; `aligned` makes them all send at once (the worst case).
// `start_spread` seconds: client i starts its stream frac(i x 0.618...) of it
// later, in whole periods, as users who joined at different moments (0: all
// in the first period; their avatars then search the database on the same frames).
Run run_clients(const tcp::endpoint& ep, const std::vector<std::string>& frames, int clients, double seconds,
                const std::string& hello, bool aligned, double start_spread) {
  Run run;
  run.clients = clients;
  net::io_context ioc;
  for (int i = 0; i < clients; ++i) {
    const double u = std::fmod(0.6180339887498949 * i, 1.0);
    const long delay = aligned ? 0 : static_cast<long>(u * start_spread * 1e6 / kPeriodUs);
    std::make_shared<ReplayClient>(ioc, frames, run, hello, seconds, i * 7, aligned ? 0.0 : double(i) / clients, delay)->start(ep);
  }
  ioc.run_for(std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds + start_spread + 15)));
  auto& l = run.latency_ms;
  std::sort(l.begin(), l.end());
  if (!l.empty()) {
    run.p50 = l[l.size() / 2];
    run.p90 = l[std::min(l.size() - 1, static_cast<std::size_t>(0.90 * static_cast<double>(l.size())))];
    run.p99 = l[std::min(l.size() - 1, static_cast<std::size_t>(0.99 * static_cast<double>(l.size())))];
    run.max = l.back();
  }
  run.answered_share = run.sent ? static_cast<double>(run.answered) / static_cast<double>(run.sent) : 0;
  return run;
}

json to_json(const Run& r) {
  return {{"clients", r.clients},   {"frames_sent", r.sent},   {"poses", r.answered}, {"answered", r.answered_share},
          {"p50_ms", r.p50},        {"p90_ms", r.p90},         {"p99_ms", r.p99},         {"max_ms", r.max},     {"errors", r.errors},
          {"failed_clients", r.failed_clients}, {"server_cpu_us_per_frame", r.server_cpu_us_per_frame},
          {"server_runqueue_wait_us_per_frame", r.server_wait_us_per_frame},
          {"client_runqueue_wait_us_per_frame", r.client_wait_us_per_frame},
          {"proxy_cpu_us_per_frame", r.proxy_cpu_us_per_frame}, {"client_cpu_us_per_frame", r.client_cpu_us_per_frame},
          {"avatars_per_core_by_cpu", r.server_cpu_us_per_frame > 0 ? 1e6 / (90.0 * r.server_cpu_us_per_frame) : 0.0}};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"serve_load: N replay clients at 90 Hz against legwork serve on loopback"};
  int port = 0, clients = 10, max_clients = 1280;
  double seconds = 5, p99_limit = 5.0;
  bool ramp = false, still = false, aligned = false;
  std::string method = "ik", trial = std::string(LEGWORK_SOURCE_DIR) + "/data/cmu/bvh/walking/07_02.bvh", out, label = "one process";
  app.add_option("--port", port, "server (or haproxy) port on 127.0.0.1")->required();
  app.add_option("--clients", clients, "concurrent clients")->check(CLI::Range(1, 5000));
  app.add_option("--seconds", seconds, "streaming time per step")->check(CLI::Range(0.5, 60.0));
  app.add_option("--method", method, "session method");
  std::vector<std::string> classes;
  app.add_option("--classes", classes, "hello classes (accent; default: none given, the server recognises the activity)")->delimiter(',');
  double search_interval = -1, start_spread = 0;
  app.add_option("--start-spread", start_spread,
                 "seconds over which the clients' streams start (not with --aligned), as users joining at different "
                 "moments; 0 = all in the first frame period")
      ->check(CLI::Range(0.0, 10.0));
  app.add_option("--search-interval", search_interval,
                 "hello search_interval in seconds (accent: between two database searches; default: the server's)")
      ->check(CLI::Range(0.0, 1.0));
  double user_height = -1;
  app.add_option("--user-height", user_height,
                 "hello user_height in metres (default: the trial subject's standing height, as the viewer sends; 0: none)");
  app.add_option("--trial", trial, "BVH trial replayed (head + hands)");
  app.add_flag("--ramp", ramp, "double the clients until p99 or answers fail, then narrow the bracket");
  app.add_option("--max-clients", max_clients, "ramp ceiling")->check(CLI::Range(1, 5000));
  app.add_option("--p99-ms", p99_limit, "latency limit for 'sustained'");
  app.add_flag("--aligned", aligned, "all clients send at the same instant (worst case; default: spread over the 11.1 ms period)");
  app.add_option("--label", label, "name of this configuration in the JSON");
  app.add_option("--json", out, "write the figures here");
  std::vector<int> server_pids;
  app.add_option("--server-pids", server_pids, "server process ids: report their CPU time per frame")->delimiter(',');
  std::vector<int> proxy_pids;
  app.add_option("--proxy-pids", proxy_pids, "proxy (HAProxy) process ids: report their CPU time per frame")->delimiter(',');
  app.add_flag("--still", still, "replay only the trial's first frame (a user standing still; for output checks)");
  CLI11_PARSE(app, argc, argv);

  io::BvhReadOptions ro;
  ro.drop_first_frame = true;
  const Motion motion = io::load_bvh(trial, ro);
  if (user_height < 0) user_height = measure_body(motion.skeleton).standing_height;
  json hello = {{"type", "hello"}, {"version", 1}, {"method", method}, {"format", "binary"}, {"record", false}};
  if (user_height > 0 && method != "walker") hello["user_height"] = user_height;
  if (!classes.empty()) hello["classes"] = classes;
  if (search_interval >= 0) hello["search_interval"] = search_interval;
  std::vector<std::string> frames;
  for (auto f : tracker_frames_from_motion(motion, 90.0)) {
    f.foot(kLeft).valid = f.foot(kRight).valid = false;
    frames.push_back(serve::binary_frame(f));
    if (still) break;
  }
  const tcp::endpoint ep(net::ip::make_address("127.0.0.1"), static_cast<unsigned short>(port));
  json steps = json::array();
  // One step: n clients for `seconds`; prints and records it; true when ok.
  auto step = [&](int n, bool& answered) {
    const std::vector<int> self{static_cast<int>(getpid())};
    const SchedTimes server0 = sched_times(server_pids), self0 = sched_times(self), proxy0 = sched_times(proxy_pids);
    Run r = run_clients(ep, frames, n, seconds, hello.dump(), aligned, start_spread);
    if (r.answered > 0) {
      const auto per_frame = [&](double s) { return 1e6 * s / static_cast<double>(r.answered); };
      const SchedTimes server1 = sched_times(server_pids), self1 = sched_times(self), proxy1 = sched_times(proxy_pids);
      r.client_wait_us_per_frame = per_frame(self1.wait - self0.wait);
      r.client_cpu_us_per_frame = per_frame(self1.cpu - self0.cpu);
      r.proxy_cpu_us_per_frame = per_frame(proxy1.cpu - proxy0.cpu);
      r.server_cpu_us_per_frame = per_frame(server1.cpu - server0.cpu);
      r.server_wait_us_per_frame = per_frame(server1.wait - server0.wait);
    }
    answered = r.answered_share >= 0.99 && r.failed_clients == 0;
    const bool ok = answered && r.p99 <= p99_limit;
    char proxy[48] = "";
    if (!proxy_pids.empty()) std::snprintf(proxy, sizeof proxy, ", proxy %.1f", r.proxy_cpu_us_per_frame);
    std::printf("%-13s clients %5d  sent %8llu  answered %6.2f %%  p50 %6.2f ms  p90 %6.2f ms  p99 %7.2f ms  max %7.2f ms  server CPU %6.1f us/frame  "
                "run-queue wait: server %6.1f, client %6.1f us/frame  CPU: client %5.1f%s us/frame  %s\n",
                label.c_str(), n, static_cast<unsigned long long>(r.sent), 100 * r.answered_share, r.p50, r.p90, r.p99, r.max,
                r.server_cpu_us_per_frame, r.server_wait_us_per_frame, r.client_wait_us_per_frame, r.client_cpu_us_per_frame,
                proxy, ok ? "ok" : "over");
    std::fflush(stdout);
    steps.push_back(to_json(r));
    steps.back()["ok"] = ok;
    return ok;
  };
  int sustained = 0, first_over = 0;
  for (int n = ramp ? 10 : clients; n <= (ramp ? max_clients : clients); n *= 2) {
    bool answered = false;
    const bool ok = step(n, answered);
    if (ok && first_over == 0) sustained = n;  // sustained: every smaller step ok too
    if (!ok && first_over == 0) first_over = n;
    if (!answered) break;  // p99 over the limit alone: keep going for the CPU figures
  }
  // Narrow the doubling's bracket (sustained, first_over) to an eighth of it.
  while (ramp && sustained > 0 && first_over > sustained && first_over - sustained > std::max(4, sustained / 8)) {
    const int mid = (sustained + first_over) / 2;
    bool answered = false;
    (step(mid, answered) ? sustained : first_over) = mid;
  }
  std::printf("%s: %d avatars sustained at 90 Hz with p99 <= %.1f ms (method %s)\n", label.c_str(), sustained, p99_limit, method.c_str());
  if (!out.empty()) {
    std::ofstream(out) << json{{"label", label}, {"method", method}, {"hello", hello}, {"rate_hz", 90}, {"p99_limit_ms", p99_limit}, {"aligned", aligned}, {"start_spread_seconds", start_spread},
                               {"sustained_avatars", sustained}, {"steps", steps}}
                              .dump(2)
                       << "\n";
  }
  return 0;
}
