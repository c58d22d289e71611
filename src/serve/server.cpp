// `legwork serve`: Boost.Beast HTTP + WebSocket on one port (see server.hpp).
#include <legwork/serve/server.hpp>

#include "http_api.hpp"
#include "vmc.hpp"

#include <legwork/accent/database.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/serve/avatar.hpp>
#include <legwork/serve/protocol.hpp>
#include <legwork/serve/rate_limit.hpp>
#include <legwork/wip/offline/learn.hpp>

#include <utility>  // before Asio: Boost 1.74 awaitable.hpp uses std::exchange without it

#include <boost/asio.hpp>
#include <boost/beast.hpp>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>

namespace legwork::serve {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;

// Every connection runs on a strand of the one network thread's io_context, named by its
// concrete type. Beast's default `tcp_stream` type-erases it (`any_io_executor`), and a
// strand does not fit the erased executor's inline buffer: each asynchronous step's
// work guard then allocated a copy (about 17 mallocs a frame, issue 11, session 43).
using Executor = net::strand<net::io_context::executor_type>;
using Socket = tcp::socket::rebind_executor<Executor>::other;
using Stream = beast::basic_stream<tcp, Executor>;

class WsSession;

namespace {
// The `rate` error's message for a dropped frame.
std::string rate_message(RateVerdict v, double max_rate_hz) {
  const auto hz = [](double r) { return std::to_string(static_cast<long long>(std::lround(r))); };
  if (v == RateVerdict::TooFastForTheClock)
    return "frames arriving above " + hz(max_rate_hz * RateLimiter::kCeilingFactor) +
           " Hz of the server's clock are dropped (the frames' times t advance faster than real time)";
  return "frames above " + hz(max_rate_hz) + " Hz are dropped (by the frames' own times t)";
}
}  // namespace

struct Server::Impl {
  ServeOptions opt;
  std::optional<accent::Database> db;
  Skeleton skeleton;
  std::optional<wip::LearnedMapping> wip_learned;
  ApiContext api;
  net::io_context ioc{1};
  tcp::acceptor acceptor{ioc};
  net::signal_set signals{ioc};
  net::thread_pool http_pool{1};
  Workers workers;
  std::unique_ptr<Vmc> vmc;
  std::mutex mu;
  std::map<std::string, std::weak_ptr<WsSession>> sessions;
  std::atomic<int> live{0};
  std::atomic<std::uint64_t> next_id{1}, opened{0}, closed{0}, frames{0}, errors{0}, refused{0}, rate_dropped{0};
  std::atomic<bool> stopping{false};

  explicit Impl(ServeOptions o);
  void accept();
  void shutdown();
  void wait_closed(SteadyClock::time_point deadline);
  std::string new_session_id() { return "s" + std::to_string(next_id++); }
};

// ---- WebSocket session -------------------------------------------------------

class WsSession : public std::enable_shared_from_this<WsSession> {
 public:
  WsSession(Socket&& s, Server::Impl& srv)
      : ws_(std::move(s)), srv_(srv), id_(srv.new_session_id()), rate_(srv.opt.max_rate_hz, SteadyClock::now()) {}

  void run(http::request<http::string_body> req) {
    // Beast's handshake and close timeouts (30 s). Its idle timeout re-arms a timer on every
    // read (a cancelled wait and a new one each frame); the session's own watch_idle() does
    // that job with one wake-up per quarter of --idle-timeout.
    auto to = websocket::stream_base::timeout::suggested(beast::role_type::server);
    to.idle_timeout = websocket::stream_base::none();
    to.keep_alive_pings = false;
    ws_.set_option(to);
    ws_.control_callback([this](websocket::frame_type, beast::string_view) { heard(); });
    ws_.set_option(websocket::stream_base::decorator(
        [](websocket::response_type& r) { r.set(http::field::server, "legwork-serve"); }));
    ws_.read_message_max(srv_.opt.max_message_bytes);
    ws_.async_accept(req, beast::bind_front_handler(&WsSession::on_accept, shared_from_this()));
  }

  void send(Outgoing o) {
    if (closed_) return;
    queue_for_client(out_, writing_ ? 1 : 0, std::move(o));  // a lagging client gets the newest poses
    if (!writing_) write_next();
  }

  // Ends the session: the avatar finishes (recording written), the close handshake starts.
  void close(websocket::close_code code) {
    const bool was_closed = closed_;
    finish();
    if (!was_closed) ws_.async_close(code, [self = shared_from_this()](beast::error_code) {});
  }

 private:
  void on_accept(beast::error_code ec) {
    if (ec) return;
    if (srv_.stopping || srv_.live.load() >= srv_.opt.max_sessions) {
      ++srv_.refused;
      error("busy", "server full (" + std::to_string(srv_.opt.max_sessions) + " sessions); try again later");
      closing_after_write_ = websocket::close_code::try_again_later;
      return;
    }
    ++srv_.live;
    ++srv_.opened;
    registered_ = true;
    {
      std::lock_guard lock(srv_.mu);
      srv_.sessions[id_] = weak_from_this();
    }
    heard();
    watch_idle();
    read();
  }

  void heard() {
    last_heard_ = SteadyClock::now();
    pinged_ = false;
  }

  // Idle connections (a client gone without closing its TCP connection): with nothing
  // received for half of --idle-timeout the session pings; for all of it, it is closed.
  void watch_idle() {
    const auto idle = std::chrono::duration<double>(srv_.opt.idle_timeout_seconds);
    idle_timer_.expires_after(std::chrono::duration_cast<SteadyClock::duration>(idle / 4));
    idle_timer_.async_wait([self = shared_from_this(), idle](beast::error_code ec) {
      if (ec || self->closed_) return;
      const auto quiet = SteadyClock::now() - self->last_heard_;
      if (quiet >= idle) {
        if (self->srv_.opt.verbose)
          std::fprintf(stderr, "legwork serve: %s closed: nothing received for %g s (--idle-timeout)\n", self->id_.c_str(),
                       self->srv_.opt.idle_timeout_seconds);
        beast::error_code ignored;
        beast::get_lowest_layer(self->ws_).socket().close(ignored);  // the pending read ends: finish()
        return;
      }
      if (quiet >= idle / 2 && !self->pinged_ && !self->ping_in_flight_) {  // Beast takes one ping at a time
        self->pinged_ = self->ping_in_flight_ = true;
        self->ws_.async_ping({}, [self](beast::error_code) { self->ping_in_flight_ = false; });
      }
      self->watch_idle();
    });
  }

  void read() {
    ws_.async_read(buf_, [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
  }

  void on_read(beast::error_code ec) {
    if (ec) {
      finish();
      return;
    }
    heard();
    const auto data = buf_.cdata();
    const std::string_view bytes(static_cast<const char*>(data.data()), data.size());
    try {
      if (ws_.got_text())
        on_text(bytes);
      else
        on_frame(parse_binary_frame(std::as_bytes(std::span(bytes.data(), bytes.size()))));
    } catch (const ProtocolError& e) {
      error(e.code(), e.what());
    }
    buf_.consume(buf_.size());
    read();
  }

  void on_text(std::string_view text) {
    ClientMessage m = parse_text(text);
    switch (m.type) {
      case MessageType::Hello: return on_hello(m.hello);
      case MessageType::Frame: return on_frame(m.frame);
      case MessageType::Options:
        if (!avatar_) throw ProtocolError("bad_message", "send hello before options");
        if (avatar_->push_options(m.options)) srv_.workers.schedule(avatar_);
        return;
    }
  }

  void on_hello(const Hello& h) {
    if (avatar_) throw ProtocolError("bad_message", "hello already received for this session");
    std::unique_ptr<Method> method;
    std::vector<int> joints;
    try {
      method = make_method(srv_.api.resources, h.method);
    } catch (const ProtocolError&) {
      throw;
    } catch (const std::exception& e) {
      throw ProtocolError("bad_value", e.what());
    }
    joints = output_joints(method->skeleton(), h.joints);
    WelcomeInfo w{id_, h.method.method, srv_.opt.max_rate_hz, joints, false, {}};
    RecordSpec rec;
    if (!srv_.opt.record_dir.empty() && h.record.value_or(true)) rec = {srv_.opt.record_dir, srv_.opt.record_max_seconds};
    if (h.record.value_or(false) && srv_.opt.record_dir.empty())
      w.warnings.push_back("recording requested but the server has no --record DIR; not recording");
    w.recording = !rec.dir.empty();
    // dispatch: with --workers 0 the avatar runs inside this session's strand and the
    // pose is written at once (no handler allocation, no extra scheduler pass); from
    // a worker thread it is queued to the strand as a post would.
    Sink sink = [weak = weak_from_this(), ex = ws_.get_executor()](Outgoing o) {
      net::dispatch(ex, [weak, o = std::move(o)]() mutable {
        if (auto s = weak.lock()) s->send(std::move(o));
      });
    };
    avatar_ = std::make_shared<Avatar>(id_, srv_.api.resources, std::move(method), h, joints, std::move(sink), rec);
    if (srv_.vmc) srv_.vmc->offer(avatar_);
    send({format_welcome(avatar_->skeleton(), w), false, false});
    if (srv_.opt.verbose) std::fprintf(stderr, "legwork serve: %s hello method %s\n", id_.c_str(), h.method.method.c_str());
  }

  void on_frame(const TrackerFrame& f) {
    if (!avatar_) throw ProtocolError("bad_message", "send hello before frames");
    ++seq_;
    ++srv_.frames;
    // Rate limit by the frames' own times, with a wall-clock ceiling (rate_limit.hpp).
    const auto now = SteadyClock::now();
    const RateVerdict v = rate_.admit(f.time, now);
    if (v != RateVerdict::Accept) {
      ++srv_.rate_dropped;
      if (now - last_rate_error_ > std::chrono::seconds(1)) {
        last_rate_error_ = now;
        error("rate", rate_message(v, srv_.opt.max_rate_hz), seq_, f.time);
      }
      return;
    }
    if (avatar_->push(f, seq_, now)) srv_.workers.schedule(avatar_);
  }

  void error(std::string_view code, const std::string& message, std::optional<std::uint64_t> seq = {},
             std::optional<double> t = {}) {
    ++srv_.errors;
    send({format_error(code, message, seq, t), false, false});
  }

  void write_next() {
    if (out_.empty()) {
      writing_ = false;
      if (closing_after_write_) close(*closing_after_write_);
      return;
    }
    writing_ = true;
    ws_.text(!out_.front().binary);
    ws_.async_write(net::buffer(out_.front().data), [self = shared_from_this()](beast::error_code ec, std::size_t) {
      self->out_.pop_front();
      if (ec) {
        self->writing_ = false;
        self->out_.clear();
        return;
      }
      self->write_next();
    });
  }

  void finish() {
    closed_ = true;
    idle_timer_.cancel();  // its handler holds the session
    if (avatar_) {
      if (avatar_->close()) srv_.workers.schedule(avatar_);
      if (srv_.vmc) srv_.vmc->release(avatar_.get());
    }
    if (registered_) {
      registered_ = false;
      --srv_.live;
      ++srv_.closed;
      std::lock_guard lock(srv_.mu);
      srv_.sessions.erase(id_);
    }
  }

  websocket::stream<Stream> ws_;
  net::basic_waitable_timer<SteadyClock, net::wait_traits<SteadyClock>, Executor> idle_timer_{ws_.get_executor()};
  SteadyClock::time_point last_heard_{};
  bool pinged_ = false, ping_in_flight_ = false;  // pinged in this quiet spell; a ping not yet written
  beast::flat_buffer buf_;
  Server::Impl& srv_;
  std::string id_;
  std::shared_ptr<Avatar> avatar_;
  std::deque<Outgoing> out_;
  bool writing_ = false, closed_ = false, registered_ = false;
  std::optional<websocket::close_code> closing_after_write_;
  std::uint64_t seq_ = 0;
  RateLimiter rate_;
  SteadyClock::time_point last_rate_error_{};
};

// ---- HTTP session --------------------------------------------------------------

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(Socket&& s, Server::Impl& srv) : stream_(std::move(s)), srv_(srv) {}
  void run() { read(); }

 private:
  void read() {
    parser_.emplace();
    parser_->body_limit(srv_.opt.max_message_bytes);
    parser_->header_limit(16 * 1024);
    stream_.expires_after(std::chrono::seconds(30));
    http::async_read(stream_, buf_, *parser_, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      self->on_read(ec);
    });
  }

  void on_read(beast::error_code ec) {
    if (ec) {
      if (ec != http::error::end_of_stream) stream_.socket().shutdown(tcp::socket::shutdown_both, ec);
      return;
    }
    http::request<http::string_body> req = parser_->release();
    if (websocket::is_upgrade(req)) {
      if (req.target() != "/ws") return reply(req, {404, "application/json", format_error("not_found", "WebSocket endpoint is /ws")});
      stream_.expires_never();
      std::make_shared<WsSession>(stream_.release_socket(), srv_)->run(std::move(req));
      return;
    }
    // File reads and trial loading run off the network thread.
    net::post(srv_.http_pool, [self = shared_from_this(), req = std::move(req)]() mutable {
      HttpReply r = handle_http(self->srv_.api, std::string(req.method_string()), std::string(req.target()));
      net::post(self->stream_.get_executor(), [self, req = std::move(req), r = std::move(r)]() mutable { self->reply(req, std::move(r)); });
    });
  }

  void reply(const http::request<http::string_body>& req, HttpReply r) {
    auto res = std::make_shared<http::response<http::string_body>>(static_cast<http::status>(r.status), req.version());
    res->set(http::field::server, "legwork-serve");
    res->set(http::field::content_type, r.content_type);
    res->set(http::field::cache_control, "no-cache");
    res->keep_alive(req.keep_alive());
    if (req.method() != http::verb::head) res->body() = std::move(r.body);
    res->prepare_payload();
    if (req.method() == http::verb::head) res->content_length(r.body.size());
    http::async_write(stream_, *res, [self = shared_from_this(), res](beast::error_code ec, std::size_t) {
      if (ec || !res->keep_alive()) {
        self->stream_.socket().shutdown(tcp::socket::shutdown_send, ec);
        return;
      }
      self->read();
    });
  }

  Stream stream_;
  beast::flat_buffer buf_;
  Server::Impl& srv_;
  std::optional<http::request_parser<http::string_body>> parser_;
};

// ---- Server ------------------------------------------------------------------

Server::Impl::Impl(ServeOptions o) : opt(std::move(o)), workers(opt.workers) {
  if (!opt.db_path.empty()) {
    db = accent::load_database(opt.db_path);
    api.classes = db->classes();
    api.resources.db = &*db;
    api.resources.database_name = std::filesystem::path(opt.db_path).filename().string();
  }
  if (!opt.skeleton_path.empty()) {
    skeleton = io::load_bvh(opt.skeleton_path).skeleton;
    api.resources.skeleton = &skeleton;
  }
  if (!opt.wip_table.empty()) {
    wip_learned = wip::read_learned_mapping(opt.wip_table);
    api.resources.wip_learned = &*wip_learned;
  }
  if (!opt.walks_dir.empty() && !std::filesystem::is_directory(opt.walks_dir))
    throw Error("--walks '" + opt.walks_dir + "' is not a folder (walk files for the walker method, e.g. data/walks)");
  api.resources.walks_dir = opt.walks_dir;
  if (!api.resources.db && !api.resources.skeleton)
    throw Error("legwork serve needs an avatar: --db FILE.lwdb (all methods) or --skeleton FILE.bvh (ik only)");
  api.web_dir = opt.web_dir;
  api.trials_dir = opt.trials_dir;
  if (!(opt.max_rate_hz > 0)) throw Error("--max-rate must be positive");
  if (opt.max_sessions < 1) throw Error("--max-sessions must be at least 1");
  if (!(opt.idle_timeout_seconds >= kMinIdleTimeoutSeconds && opt.idle_timeout_seconds <= kMaxIdleTimeoutSeconds))
    throw Error("--idle-timeout must be between 0.1 and 604800 seconds (a week)");
  beast::error_code ec;
  const auto addr = net::ip::make_address(opt.host, ec);
  if (ec) throw Error("--host '" + opt.host + "' is not an IP address");
  const tcp::endpoint ep(addr, static_cast<unsigned short>(opt.port));
  acceptor.open(ep.protocol(), ec);
  if (!ec) acceptor.set_option(net::socket_base::reuse_address(true), ec);
  if (!ec) acceptor.bind(ep, ec);
  if (!ec) acceptor.listen(net::socket_base::max_listen_connections, ec);
  if (ec) throw Error("cannot listen on " + opt.host + ":" + std::to_string(opt.port) + ": " + ec.message());
  if (opt.vmc_in_port > 0 || !opt.vmc_out.empty()) vmc = std::make_unique<Vmc>(opt, api.resources, workers);
}

void Server::Impl::accept() {
  acceptor.async_accept(net::make_strand(ioc), [this](beast::error_code ec, Socket s) {
    if (!acceptor.is_open()) return;
    if (!ec) {
      beast::error_code ignored;
      s.set_option(tcp::no_delay(true), ignored);  // small pose messages go out at once (no Nagle wait)
      std::make_shared<HttpSession>(std::move(s), *this)->run();
    }
    accept();
  });
}

void Server::Impl::shutdown() {
  if (stopping.exchange(true)) return;
  beast::error_code ec;
  acceptor.close(ec);
  signals.cancel(ec);
  std::vector<std::shared_ptr<WsSession>> live_sessions;
  {
    std::lock_guard lock(mu);
    for (auto& [id, w] : sessions)
      if (auto s = w.lock()) live_sessions.push_back(s);
  }
  for (auto& s : live_sessions)
    net::post(ioc, [s] { s->close(websocket::close_code::going_away); });
  // Give clients up to half a second to complete the close handshake, then stop.
  wait_closed(SteadyClock::now() + std::chrono::milliseconds(500));
}

void Server::Impl::wait_closed(SteadyClock::time_point deadline) {
  if (live.load() == 0 || SteadyClock::now() >= deadline) {
    ioc.stop();
    return;
  }
  auto timer = std::make_shared<net::steady_timer>(ioc, std::chrono::milliseconds(5));
  timer->async_wait([this, timer, deadline](beast::error_code) { wait_closed(deadline); });
}

Server::Server(ServeOptions opt) : impl_(std::make_unique<Impl>(std::move(opt))) {}

Server::~Server() {
  stop();
  impl_->workers.stop();
  impl_->http_pool.join();
}

unsigned short Server::port() const { return impl_->acceptor.local_endpoint().port(); }

void Server::run(bool handle_signals) {
  Impl& s = *impl_;
  if (handle_signals) {
    s.signals.add(SIGINT);
    s.signals.add(SIGTERM);
    s.signals.async_wait([&s](beast::error_code ec, int) {
      if (!ec) s.shutdown();
    });
  }
  if (s.vmc) s.vmc->start();
  s.accept();
  s.ioc.run();
  if (s.vmc) s.vmc->stop();
  // The avatars closed in shutdown() finish their recordings; drain the workers.
  s.workers.stop();
}

void Server::stop() {
  net::post(impl_->ioc, [s = impl_.get()] { s->shutdown(); });
}

ServerStats Server::stats() const {
  const Impl& s = *impl_;
  ServerStats st;
  st.sessions_opened = s.opened;
  st.sessions_closed = s.closed;
  st.frames = s.frames;
  st.errors = s.errors;
  st.refused = s.refused;
  st.rate_dropped = s.rate_dropped;
  st.live_sessions = s.live;
  return st;
}

}  // namespace legwork::serve
