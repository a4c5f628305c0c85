#include "screen_server.h"

#include <httplib.h>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <random>
#include <thread>

#include <fmt/format.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/json.h"

#include "confirm_gate.h"
#include "listen_address.h"
#include "screen_format.h"
#include "station_tap.h"
#include "station_watch.h"
#include "tap_decoder.h"
#include "web_assets.h"

namespace hubrt::hubctl {
namespace {

using Clock = std::chrono::steady_clock;

constexpr std::size_t kMaxBody = 1024;                 // POST /confirm has no body worth more
constexpr int kHttpThreads = 8;                        // each event stream holds one
constexpr int kMaxEventStreams = 4;                    // the rest stay free for pages and presses
constexpr auto kKeepAlive = std::chrono::seconds(15);  // a comment line: proxies keep the stream
constexpr auto kRepublish = std::chrono::seconds(1);   // "silent" needs time, not a sample, to show

// What the DDS thread publishes to the HTTP threads. Guarded by `mutex`.
struct Shared {
  std::mutex mutex;
  std::condition_variable changed;
  std::string json = "{}";
  std::uint64_t version = 0;
  screen::OperatorView op;
  std::optional<screen::Instruction> instruction;
  bool stopping = false;
};

// The DDS side: discovery, the instruction, the confirm writer.
class DdsSide {
 public:
  static Expected<std::unique_ptr<DdsSide>> open(const ServeOptions& options) {
    auto participant = join_domain(options.domain, "hubctl-serve");
    if (!participant) return participant.error();
    auto side = std::unique_ptr<DdsSide>(new DdsSide(std::move(*participant), options));
    TapOptions tap_options;
    tap_options.filter = &is_state_topic;
    auto tap = StationTap::start(side->participant_, std::move(tap_options));
    if (!tap) return tap.error();
    side->tap_ = std::move(*tap);
    side->states_ = side->tap_->subscribe(10'000);
    const auto& types = msgs::all_types();
    side->instruction_type_ = types.find_by_ros_name("hub_msgs/msg/OperatorInstruction");
    side->confirm_type_ = types.find_by_ros_name("hub_msgs/msg/OperatorConfirm");
    if (side->instruction_type_ == nullptr || side->confirm_type_ == nullptr)
      return make_error(ErrorCode::kInternal, "hubctl serve: message types missing from the registry");
    auto it = dds::UntypedTopic::create(side->participant_, *side->instruction_type_->descriptor,
                                        options.instruction_topic);
    if (!it) return it.error();
    side->instruction_topic_.emplace(std::move(*it));
    auto ir = dds::UntypedReader::create(side->participant_, *side->instruction_topic_);
    if (!ir) return ir.error();
    side->instruction_reader_.emplace(std::move(*ir));
    side->instruction_sample_.emplace(*side->instruction_type_->descriptor);
    auto ct = dds::UntypedTopic::create(side->participant_, *side->confirm_type_->descriptor,
                                        options.confirm_topic);
    if (!ct) return ct.error();
    side->confirm_topic_.emplace(std::move(*ct));
    auto cw = dds::UntypedWriter::create(side->participant_, *side->confirm_topic_);
    if (!cw) return cw.error();
    side->confirm_writer_.emplace(std::move(*cw));
    return side;
  }

  // One pass: new States and instructions; true when the snapshot should be sent again.
  bool poll(Clock::time_point /*now*/) {
    bool changed = watch_.drain(*states_, state_decoder_);
    while (true) {
      const Result<bool> taken = instruction_reader_->take_next(instruction_sample_->data());
      if (!taken.is_ok() || !taken.value()) break;
      auto value = decoder_.decode(*instruction_type_, instruction_sample_->data());
      if (!value) continue;
      instruction_ = screen::Instruction{value->value("step", ""), value->value("text", ""),
                                         value->value("seq", std::uint64_t{0})};
      changed = true;
    }
    return changed;
  }

  void publish(Shared& shared, Clock::time_point now) {
    const auto op = screen::find_operator(watch_.states(), operator_state_, now);
    std::string json = screen::safe_json(screen::snapshot(op, instruction_, watch_.states(), now));
    const std::lock_guard<std::mutex> lock(shared.mutex);
    shared.op = op;
    shared.instruction = instruction_;
    if (json != shared.json) {
      shared.json = std::move(json);
      ++shared.version;
      shared.changed.notify_all();
    }
  }

  // Thread-safe (Cyclone's dds_write is); the caller holds Shared::mutex so presses go out in order.
  Status send_press(std::uint32_t press_id) {
    dds::UntypedSample sample(*confirm_type_->descriptor);
    const nlohmann::ordered_json value = {{"source", "screen"}, {"press_id", press_id}};
    if (auto ok = msgs::from_json(*confirm_type_, value, sample.data()); !ok) return Status(ok.error().code);
    return confirm_writer_->write(sample.data());
  }

 private:
  DdsSide(dds::Participant participant, const ServeOptions& options)
      : participant_(std::move(participant)),
        operator_state_(options.operator_state),
        state_decoder_("hubctl serve", participant_),
        decoder_("hubctl serve", options.instruction_topic) {}

  dds::Participant participant_;
  std::string operator_state_;
  std::unique_ptr<StationTap> tap_;  // every State, as they come; before the decoder, after the participant
  std::unique_ptr<TapSubscription> states_;
  TapDecoder state_decoder_;
  StationWatch watch_;
  SampleDecoder decoder_;
  const msgs::TypeInfo* instruction_type_ = nullptr;
  const msgs::TypeInfo* confirm_type_ = nullptr;
  std::optional<dds::UntypedTopic> instruction_topic_;
  std::optional<dds::UntypedReader> instruction_reader_;
  std::optional<dds::UntypedSample> instruction_sample_;
  std::optional<dds::UntypedTopic> confirm_topic_;
  std::optional<dds::UntypedWriter> confirm_writer_;
  std::optional<screen::Instruction> instruction_;
};

void add_page_headers(httplib::Response& res) {
  // Everything the page needs is its own: no other origin, no inline script, not framed.
  res.set_header("Content-Security-Policy",
                 "default-src 'none'; script-src 'self'; style-src 'self'; connect-src 'self'; "
                 "img-src 'self'; frame-ancestors 'none'; base-uri 'none'; form-action 'none'");
  res.set_header("X-Content-Type-Options", "nosniff");
  res.set_header("X-Frame-Options", "DENY");
  res.set_header("Referrer-Policy", "no-referrer");
  res.set_header("Cache-Control", "no-store");
}

std::string render_index(const Shared& shared) {
  std::string page(web::kIndexHtml);
  const std::string marker = "<!--FIRST-VIEW-->";
  const auto at = page.find(marker);
  if (at != std::string::npos)
    page.replace(at, marker.size(), screen::initial_html(shared.op, shared.instruction));
  return page;
}

void add_routes(httplib::Server& server, Shared& shared, DdsSide& dds, screen::ConfirmGate& gate,
                std::atomic<int>& streams) {
  server.Get("/", [&shared](const httplib::Request&, httplib::Response& res) {
    const std::lock_guard<std::mutex> lock(shared.mutex);
    res.set_content(render_index(shared), "text/html; charset=utf-8");
  });
  server.Get("/screen.js", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(std::string(web::kScreenJs), "text/javascript; charset=utf-8");
  });
  server.Get("/screen.css", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(std::string(web::kScreenCss), "text/css; charset=utf-8");
  });
  server.Get("/state", [&shared](const httplib::Request&, httplib::Response& res) {
    const std::lock_guard<std::mutex> lock(shared.mutex);
    res.set_content(shared.json, "application/json");
  });
  server.Get("/events", [&shared, &streams](const httplib::Request&, httplib::Response& res) {
    if (streams.fetch_add(1) >= kMaxEventStreams) {
      streams.fetch_sub(1);
      res.status = 503;
      res.set_content("too many event streams\n", "text/plain; charset=utf-8");
      return;
    }
    // cpp-httplib calls the provider again and again on this connection's thread while it returns
    // true; false (a write to a gone client failed) ends the response; the releaser runs once
    // either way (httplib.h: set_chunked_content_provider, write_content_chunked).
    auto last = std::make_shared<std::uint64_t>(0);
    res.set_chunked_content_provider(
        "text/event-stream",
        [&shared, last](std::size_t, httplib::DataSink& sink) {
          std::string out;
          {
            std::unique_lock<std::mutex> lock(shared.mutex);
            const bool woke = shared.changed.wait_for(
                lock, kKeepAlive, [&] { return shared.stopping || shared.version != *last; });
            if (shared.stopping) {
              sink.done();
              return true;
            }
            if (woke) {
              *last = shared.version;
              out = screen::sse_event("state", shared.json);
            } else {
              out = ": keep-alive\n\n";
            }
          }
          return sink.write(out.data(), out.size());
        },
        [&streams](bool) { streams.fetch_sub(1); });
  });
  server.Post("/confirm", [&shared, &dds, &gate](const httplib::Request& req, httplib::Response& res) {
    const std::string marker = req.get_header_value(std::string(screen::kConfirmHeader));
    const std::string origin = req.get_header_value("Origin");
    const std::string host = req.get_header_value("Host");
    const std::lock_guard<std::mutex> lock(shared.mutex);
    auto decision = gate.decide({marker, origin, host}, shared.op, Clock::now());
    if (decision.http_status == 200) {
      if (auto sent = dds.send_press(decision.press_id); !sent.is_ok()) {
        decision.http_status = 503;
        decision.message = fmt::format("the press could not be sent: {}", to_string(sent.code()));
      }
    }
    res.status = decision.http_status;
    const nlohmann::ordered_json body = {
        {"ok", decision.http_status == 200}, {"message", decision.message}, {"press_id", decision.press_id}};
    res.set_content(screen::safe_json(body), "application/json");
  });
}

}  // namespace

int run_serve(const ServeOptions& options) {
  install_stop_handler();
  auto endpoint = parse_listen(options.listen);
  if (!endpoint) {
    fmt::print(stderr, "hubctl serve: {}\n", endpoint.error().message);
    return kExitUsage;
  }
  auto dds = DdsSide::open(options);
  if (!dds) {
    fmt::print(stderr, "hubctl serve: {}\n", dds.error().message);
    return kExitUsage;
  }
  Shared shared;
  (*dds)->publish(shared, Clock::now());
  std::random_device random;
  screen::ConfirmGate gate(random(),
                           std::chrono::milliseconds(static_cast<int>(options.min_press_interval_s * 1000)));
  std::atomic<int> streams{0};

  httplib::Server server;
  server.new_task_queue = [] { return new httplib::ThreadPool(kHttpThreads); };
  // cpp-httplib 0.11.4 (yhirose/cpp-httplib, httplib.h, Server::read_content): a body over this
  // is answered 413 before any handler runs (hubrt_hubctl_serve_test checks it).
  server.set_payload_max_length(kMaxBody);
  server.set_read_timeout(5, 0);
  server.set_write_timeout(5, 0);
  server.set_keep_alive_max_count(20);
  int port = 0;
  server.set_pre_routing_handler([&](const httplib::Request& req, httplib::Response& res) {
    add_page_headers(res);
    if (!screen::host_allowed(req.get_header_value("Host"), endpoint->address,
                              static_cast<std::uint16_t>(port))) {
      res.status = 403;
      res.set_content("unknown Host\n", "text/plain; charset=utf-8");
      return httplib::Server::HandlerResponse::Handled;
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });
  add_routes(server, shared, **dds, gate, streams);

  port = endpoint->port == 0 ? server.bind_to_any_port(endpoint->address)
                             : (server.bind_to_port(endpoint->address, endpoint->port) ? endpoint->port : -1);
  if (port <= 0) {
    fmt::print(stderr, "hubctl serve: cannot listen on {}\n", options.listen);
    return kExitFailed;
  }
  const bool v6 = endpoint->address.find(':') != std::string::npos;
  fmt::print("serving http://{}{}{}:{}/\n", v6 ? "[" : "", endpoint->address, v6 ? "]" : "", port);
  std::fflush(stdout);
  std::thread http([&server] { server.listen_after_bind(); });

  const auto start = Clock::now();
  auto next_publish = start;
  while (!stop_requested()) {
    const auto now = Clock::now();
    if (options.duration_s > 0 && now - start >= seconds(options.duration_s)) break;
    if ((*dds)->poll(now) || now >= next_publish) {
      next_publish = now + kRepublish;
      (*dds)->publish(shared, now);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  {
    const std::lock_guard<std::mutex> lock(shared.mutex);
    shared.stopping = true;
    shared.changed.notify_all();
  }
  server.stop();
  http.join();
  return kExitOk;
}

}  // namespace hubrt::hubctl
