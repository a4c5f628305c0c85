// DDS Security's cost on a hub: command -> echo latency, and the hub's CPU and RSS, with the
// station's governance (discovery and liveliness encrypted, payload encrypted, access control) vs
// without, side by side in one run.
//
// Two hubd (Dock ECU, fake backend, same rate) in two private domains on loopback: one plain, one
// secured with a PKI made here (firmware/security, as `hubctl security init/add` makes it). This
// process is the planner for both on the Cyclone C API; its secured domain is created with the
// planner's credentials (Cyclone keeps one configuration per domain per process). Blocks of both
// sides alternate, so machine noise hits both alike. CPU: the hub's user+system time over the
// measured blocks (same traffic on both sides); RSS: the hub's resident set at the end.
#include <unistd.h>

#include <filesystem>
#include <tuple>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "hubrt/dds/domain.h"
#include "hubrt/security/participant_security.h"
#include "hubrt/security/pki.h"

#include "bench_common.h"
#include "echo_peer.h"
#include "proc_stats.h"
#include "raw_dds.h"
#include "role_permissions.h"

namespace hubrt::bench {
namespace {

Expected<std::string> make_pki(const std::string& dir) {
  const auto now = static_cast<std::int64_t>(::time(nullptr));
  const security::Validity validity{now - 3600, now + 24 * 3600};
  if (auto ok = security::init_station(dir, validity); !ok) return std::move(ok).error();
  // The identities `hubctl security add` makes: the simulated Dock ECU (its sim bridge's topics
  // too) and a planner, with the permissions of their roles.
  for (const auto& [identity, role, hubs] :
       {std::tuple{"dock_ecu", "hub", std::vector<std::string>{"dock_ecu"}},
        std::tuple{"planner", "planner", std::vector<std::string>{}}}) {
    auto topics = hubctl::role_permissions(role, hubs, /*simulation=*/true);
    if (!topics) return std::move(topics).error();
    if (auto ok = security::add_identity(dir, identity, validity, topics->publish, topics->subscribe); !ok) {
      return std::move(ok).error();
    }
  }
  return security::security_xml_for({dir, "planner"}, now);
}

struct Side {
  Peer peer;
  test_support::ChildProcess* hub = nullptr;
  ProcSample before;
  ProcSample after;
};

nlohmann::ordered_json side_json(const Side& side, double elapsed_s) {
  nlohmann::ordered_json json;
  json["echo_ms"] = summary_json(side.peer.latencies_ms);
  json["lost"] = side.peer.lost;
  json["hub_cpu_percent"] = cpu_percent(side.before, side.after, elapsed_s);
  json["hub_rss_mb"] = side.after.rss_mb;
  json["hub_hwm_mb"] = side.after.hwm_mb;
  json["hub_threads"] = side.after.threads;
  return json;
}

int run(const std::string& out, std::size_t rounds, std::size_t per_block, double hub_rate, double gap_ms) {
  auto plain_domain = join_private_domain();
  if (!plain_domain) return fmt::print(stderr, "{}\n", plain_domain.error().message), 1;
  auto secure_domain = test_support::TestDomain::acquire();
  if (!secure_domain) return fmt::print(stderr, "{}\n", secure_domain.error().message), 1;
  std::string dir = (std::filesystem::temp_directory_path() / "hubrt-bench-security-XXXXXX").string();
  if (::mkdtemp(dir.data()) == nullptr) return fmt::print(stderr, "mkdtemp failed\n"), 1;
  auto planner_xml = make_pki(dir);
  if (!planner_xml) return fmt::print(stderr, "{}\n", planner_xml.error().message), 1;

  const std::string rate = fmt::format("{}", hub_rate);
  auto plain_hub = start_hubd({"--hub", "dock_ecu", "--rate", rate});
  if (!plain_hub) return fmt::print(stderr, "{}\n", plain_hub.error().message), 1;
  auto secure_hub =
      start_hubd({"--hub", "dock_ecu", "--rate", rate, "--domain", std::to_string(secure_domain->domain_id()),
                  "--security", dir, "--identity", "dock_ecu"});
  if (!secure_hub) return fmt::print(stderr, "{}\n", secure_hub.error().message), 1;

  auto plain_participant = raw_participant(plain_domain->domain_id());
  if (!plain_participant) return fmt::print(stderr, "{}\n", plain_participant.error().message), 1;
  const std::string secure_config = dds::loopback_config_xml() + "," + *planner_xml;
  const dds_entity_t domain_handle = dds_create_domain(secure_domain->domain_id(), secure_config.c_str());
  if (domain_handle < 0) return fmt::print(stderr, "secured domain: {}\n", dds_strretcode(domain_handle)), 1;
  auto secure_participant = raw_participant(secure_domain->domain_id());
  if (!secure_participant) return fmt::print(stderr, "{}\n", secure_participant.error().message), 1;

  auto plain_peer = open_peer(*plain_participant, "hub", "rt/dock/command", "rt/dock_ecu/dock/state");
  if (!plain_peer)
    return fmt::print(stderr, "{}\n{}\n", plain_peer.error().message, plain_hub->stderr_text()), 1;
  auto secure_peer =
      open_peer(*secure_participant, "secured hub", "rt/dock/command", "rt/dock_ecu/dock/state");
  if (!secure_peer) {
    return fmt::print(stderr, "{}\n{}\n", secure_peer.error().message, secure_hub->stderr_text()), 1;
  }
  Side plain{std::move(*plain_peer), &*plain_hub, {}, {}};
  Side secure{std::move(*secure_peer), &*secure_hub, {}, {}};

  progress(fmt::format("security: {} rounds of {} round trips per side (hubs at {} Hz)", rounds, per_block,
                       hub_rate));
  run_block(plain.peer, 50, false);  // warm-up: discovery and the security handshake settle
  run_block(secure.peer, 50, false);
  for (Side* side : {&plain, &secure}) {
    auto sample = read_proc(side->hub->pid());
    if (!sample) return fmt::print(stderr, "{}\n", sample.error().message), 1;
    side->before = *sample;
  }
  const double start = mono_now();
  for (std::size_t round = 0; round < rounds; ++round) {
    run_block(plain.peer, per_block, true, gap_ms / 1e3);
    run_block(secure.peer, per_block, true, gap_ms / 1e3);
  }
  const double elapsed = mono_now() - start;
  for (Side* side : {&plain, &secure}) {
    auto sample = read_proc(side->hub->pid());
    if (!sample) return fmt::print(stderr, "{}\n", sample.error().message), 1;
    side->after = *sample;
  }
  dds_delete(*plain_participant);
  dds_delete(domain_handle);
  stop(*plain_hub);
  stop(*secure_hub);
  std::error_code ignored;
  std::filesystem::remove_all(dir, ignored);

  nlohmann::ordered_json result;
  result["payload"] = "DockCommand out, DockState back (as the echo latency benchmark)";
  result["security"] =
      "governance of hubctl security init: discovery, liveliness and payload encrypted, "
      "access control on; ECDSA P-256 identities";
  result["hub_rate_hz"] = hub_rate;
  result["gap_ms"] = gap_ms;
  result["seconds"] = elapsed;
  result["off"] = side_json(plain, elapsed);
  result["on"] = side_json(secure, elapsed);
  const auto off = summary_of(plain.peer.latencies_ms);
  const auto on = summary_of(secure.peer.latencies_ms);
  result["ratio_p50"] = off.p50 > 0 ? on.p50 / off.p50 : 0.0;
  progress(fmt::format("security: echo p50 off {:.3f} ms on {:.3f} ms; p99 off {:.3f} ms on {:.3f} ms",
                       off.p50, on.p50, off.p99, on.p99));
  if (auto ok = write_json(out, result); !ok) return fmt::print(stderr, "{}\n", ok.error().message), 1;
  return 0;
}

}  // namespace
}  // namespace hubrt::bench

int main(int argc, char** argv) {
  CLI::App app{"DDS Security on vs off: echo latency, hub CPU and RSS"};
  std::string out = "security.json";
  std::size_t rounds = 10;
  std::size_t per_block = 200;
  double hub_rate = 100;
  app.add_option("--out", out, "Result file (JSON)");
  app.add_option("--rounds", rounds, "Alternating blocks per side");
  app.add_option("--per-block", per_block, "Round trips per block");
  app.add_option("--hub-rate", hub_rate, "The hubs' cycle rate in Hz");
  // Longer than the hubs' immediate-State budget (10 ms), so every echo is an immediate State.
  double gap_ms = 12;
  app.add_option("--gap-ms", gap_ms, "Pause after each round trip, in ms");
  CLI11_PARSE(app, argc, argv);
  return hubrt::bench::run(out, rounds, per_block, hub_rate, gap_ms);
}
