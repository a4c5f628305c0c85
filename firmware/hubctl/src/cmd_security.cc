// hubctl security init DIR / add DIR IDENTITY --role ...: the station's DDS Security files
// (firmware/security, docs/deploy.md "Securing a station").
#include <chrono>
#include <ctime>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "hubrt/security/pki.h"

#include "commands.h"
#include "domain_set.h"
#include "role_permissions.h"
#include "session.h"

namespace hubrt::hubctl {
namespace {

struct ValidityOptions {
  std::string valid_from;  // YYYY-MM-DD (UTC); empty: now
  int valid_days = 0;
};

struct SecurityOptions {
  std::string dir;
  std::string identity;
  std::string role;
  std::vector<std::string> hubs;
  bool simulation = false;
  std::string domains;  // --domains, e.g. "13" or "10-41"; empty: every domain
  ValidityOptions ca_validity{{}, 3650};
  ValidityOptions identity_validity{{}, 365};
};

Expected<security::Validity> validity(const ValidityOptions& options) {
  std::int64_t start =
      std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch())
          .count();
  if (!options.valid_from.empty()) {
    std::tm tm{};
    const char* end = strptime(options.valid_from.c_str(), "%Y-%m-%d", &tm);
    if (end == nullptr || *end != '\0') {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("--valid-from '{}' is not a date YYYY-MM-DD", options.valid_from));
    }
    start = timegm(&tm);
  }
  constexpr std::int64_t kDay = 24 * 3600;
  return security::Validity{start, start + options.valid_days * kDay};
}

int report(const Expected<void>& done, const std::string& what) {
  if (!done) {
    fmt::print(stderr, "hubctl security: {}\n", done.error().message);
    return done.error().code == ErrorCode::kInternal || done.error().code == ErrorCode::kIo ? kExitFailed
                                                                                            : kExitUsage;
  }
  fmt::print("{}\n", what);
  return kExitOk;
}

int run_init(const SecurityOptions& options) {
  auto dates = validity(options.ca_validity);
  if (!dates) return report(std::move(dates).error(), "");
  return report(
      security::init_station(options.dir, *dates),
      fmt::format("station CAs and governance made in {} (CA keys in {}/private: keep them off the boards)",
                  options.dir, options.dir));
}

int run_add(const SecurityOptions& options) {
  auto dates = validity(options.identity_validity);
  if (!dates) return report(std::move(dates).error(), "");
  auto topics = role_permissions(options.role, options.hubs, options.simulation);
  if (!topics) return report(std::move(topics).error(), "");
  std::vector<std::uint32_t> domains;
  if (!options.domains.empty()) {
    auto parsed = parse_domain_set(options.domains);
    if (!parsed) return report(make_error(parsed.error().code, "--domains: " + parsed.error().message), "");
    domains = std::move(*parsed);
  }
  return report(
      security::add_identity(options.dir, options.identity, *dates, topics->publish, topics->subscribe,
                             domains),
      fmt::format("identity '{}' ({}) issued in {}: publishes {}; subscribes {}; in domains {}",
                  options.identity, options.role, options.dir,
                  topics->publish.empty() ? "nothing" : fmt::format("{}", fmt::join(topics->publish, " ")),
                  fmt::join(topics->subscribe, " "),
                  domains.empty()
                      ? fmt::format("{}-{} (all)", security::kFirstDomainId, security::kLastDomainId)
                      : format_domain_set(domains)));
}

void add_validity_options(CLI::App& app, ValidityOptions& options) {
  app.add_option("--valid-from", options.valid_from,
                 "First day of validity, YYYY-MM-DD in UTC (default: now)");
  app.add_option("--valid-days", options.valid_days, "Days of validity")
      ->default_val(options.valid_days)
      ->check(CLI::Range(1, 36500));
}

}  // namespace

void add_security_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<SecurityOptions>();
  auto* security = app.add_subcommand("security", "Make the station's DDS Security files (CAs, identities)");
  security->require_subcommand(1);
  auto* init = security->add_subcommand(
      "init", "Make the station's identity CA and permissions CA and its signed governance in DIR");
  init->add_option("dir", options->dir, "Station security folder (made if missing)")->required();
  add_validity_options(*init, options->ca_validity);
  init->callback([options, &exit_code] { exit_code = run_init(*options); });

  auto* add = security->add_subcommand(
      "add", "Issue an identity (certificate, key, signed permissions) in DIR; again to renew it");
  add->add_option("dir", options->dir, "Station security folder (hubctl security init)")->required();
  add->add_option("identity", options->identity, "Identity name: the hub instance, planner, an observer")
      ->required();
  add->add_option("--role", options->role, "What it may do: hub, planner, observer or simulator (hubsim)")
      ->required()
      ->check(CLI::IsMember({"hub", "planner", "observer", "simulator"}));
  add->add_option("--hub", options->hubs,
                  "Hub file or type whose topics the identity publishes and reads (--role hub; repeatable)");
  add->add_flag("--sim", options->simulation, "Also the simulated station's /sim topics (planner, hub)");
  add->add_option("--domains", options->domains,
                  "DDS domains it may join: an id, a range 10-41 or a list 3,5,7-9 (default: all; a plant's "
                  "station: its own, docs/plant.md)");
  add_validity_options(*add, options->identity_validity);
  add->callback([options, &exit_code] { exit_code = run_add(*options); });
}

}  // namespace hubrt::hubctl
