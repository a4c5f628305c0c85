#include "hubrt/dds/security_refusals.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>

#include <fmt/format.h>

#include "log_sink.h"

namespace hubrt::dds {
namespace {

// Where Cyclone 0.10.2 logs a refusal: the file (its name, as __FILE__ ends), a fixed text the
// remote GUID follows (or "" for a line that names none), and what is refused. `unsecured`: the
// line says the remote has no security, so its participant is refused as well.
struct Marker {
  std::string_view file;
  std::string_view text;
  RefusedWhat what;
  bool unsecured = false;
};
constexpr Marker kMarkers[] = {
    // ddsi_entity_match.c, handshake_end_cb: "handshake (lguid=G rguid=G) failed: (N) Failed".
    {"ddsi_entity_match.c", "rguid=", RefusedWhat::kAuthentication},
    {"ddsi_security_omg.c", "Non secure remote writer ", RefusedWhat::kWriter, true},
    {"ddsi_security_omg.c", "Non secure remote reader ", RefusedWhat::kReader, true},
    {"ddsi_security_omg.c", "Access control does not allow remote writer ", RefusedWhat::kWriter},
    {"ddsi_security_omg.c", "Access control does not allow remote reader ", RefusedWhat::kReader},
    {"ddsi_security_omg.c", "match_remote_writer ", RefusedWhat::kWriter},
    {"ddsi_security_omg.c", "match_remote_reader ", RefusedWhat::kReader},
    {"ddsi_security_omg.c", "Plugin does not allow remote participant ", RefusedWhat::kParticipant},
    {"ddsi_security_omg.c", "Could not get remote participant ", RefusedWhat::kParticipant},
    {"ddsi_security_omg.c", "and remote participant ", RefusedWhat::kParticipant},
    {"ddsi_proxy_participant.c", "Remote secure participant ", RefusedWhat::kParticipant},
};

bool ends_with_file(std::string_view path, std::string_view name) noexcept {
  return path.ends_with(name) && (path.size() == name.size() || path[path.size() - name.size() - 1] == '/');
}

int hex_digit(char c) noexcept {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// PGUIDFMT ("%x:%x:%x:%x") at the start of `text`.
bool parse_guid(std::string_view text, std::array<std::uint32_t, 4>& guid) noexcept {
  std::size_t at = 0;
  for (std::size_t group = 0; group < 4; ++group) {
    if (group > 0) {
      if (at >= text.size() || text[at] != ':') return false;
      ++at;
    }
    std::uint32_t value = 0;
    std::size_t digits = 0;
    for (; at < text.size() && digits < 9 && hex_digit(text[at]) >= 0; ++at, ++digits)
      value = value * 16 + static_cast<std::uint32_t>(hex_digit(text[at]));
    if (digits == 0 || digits > 8) return false;
    guid[group] = value;
  }
  return true;
}

// Distinct GUIDs (or participants: the first three groups) seen, up to a bound: past it every
// new one counts, unremembered (a count that errs high rather than low). Not thread-safe.
template <std::size_t N, std::size_t Groups>
class DistinctGuids {
 public:
  bool insert(const std::array<std::uint32_t, 4>& guid) noexcept {
    for (std::size_t i = 0; i < size_; ++i) {
      if (std::equal(guid.begin(), guid.begin() + Groups, seen_[i].begin())) return false;
    }
    if (size_ < N) seen_[size_++] = guid;
    return true;
  }

 private:
  std::array<std::array<std::uint32_t, 4>, N> seen_{};
  std::size_t size_ = 0;
};

// A kind of refusal's log lines: the first at once, then one per kLogEvery with how many more.
struct RateLimit {
  std::chrono::steady_clock::time_point last{};
  bool logged = false;
  std::uint64_t suppressed = 0;
};
constexpr auto kLogEvery = std::chrono::seconds(10);
constexpr std::size_t kMaxReason = 300;

struct State {
  std::mutex mutex;  // the tables, the rate limits and the last reason (Cyclone logs from many threads)
  DistinctGuids<256, 3> participants;
  DistinctGuids<256, 4> writers;
  DistinctGuids<256, 4> readers;
  std::array<RateLimit, 5> limits{};
  std::array<char, kMaxReason> last_reason{};
  std::size_t last_reason_size = 0;
};

State& state() noexcept {
  static State s;
  return s;
}

std::atomic<bool> g_refusals_counted{false};
std::atomic<std::uint64_t> g_participants{0};
std::atomic<std::uint64_t> g_writers{0};
std::atomic<std::uint64_t> g_readers{0};
std::atomic<std::uint64_t> g_authentication{0};

std::string_view name_of(RefusedWhat what) noexcept {
  switch (what) {
    case RefusedWhat::kAuthentication:
      return "a remote participant's authentication";
    case RefusedWhat::kParticipant:
      return "a remote participant";
    case RefusedWhat::kWriter:
      return "a remote writer";
    case RefusedWhat::kReader:
      return "a remote reader";
    case RefusedWhat::kNothing:
      break;
  }
  return "nothing";
}

// Copies `text` into `out` (at most its size) with every byte that is not printable ASCII as '?':
// a plugin's reason carries the peer's certificate subject, which the peer chose. Returns the size.
std::size_t copy_printable(std::string_view text, char* out, std::size_t capacity) noexcept {
  const std::size_t n = std::min(text.size(), capacity);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    out[i] = c >= 0x20 && c < 0x7f ? static_cast<char>(c) : '?';
  }
  return n;
}

// Writes "DDS Security refused <what>: <reason>" where Cyclone's lines go (stderr, or hubd's log
// queue: detail::write_log_line): the first of a kind at once, then at
// most one per kLogEvery saying how many were held back. `s.mutex` must be held. No allocation
// (Cyclone's threads, the hub's cycle).
void write_limited(State& s, RefusedWhat what, std::string_view reason) noexcept {
  RateLimit& limit = s.limits[static_cast<std::size_t>(what)];
  const auto now = std::chrono::steady_clock::now();
  if (limit.logged && now - limit.last < kLogEvery) {
    ++limit.suppressed;
    return;
  }
  std::array<char, 64> more{};
  std::size_t more_size = 0;
  if (limit.suppressed > 0) {
    more_size =
        fmt::format_to_n(more.data(), more.size(), " ({} more since the last such line)", limit.suppressed)
            .size;
    more_size = std::min(more_size, more.size());
  }
  std::array<char, 512> text{};
  const std::size_t size =
      std::min(fmt::format_to_n(text.data(), text.size() - 1, "DDS Security refused {}: {}{}", name_of(what),
                                reason, std::string_view(more.data(), more_size))
                   .size,
               text.size() - 1);
  text[size] = '\n';
  detail::write_log_line({text.data(), size + 1});
  limit.logged = true;
  limit.last = now;
  limit.suppressed = 0;
}

}  // namespace

RefusalLine classify_security_log(std::string_view file, std::string_view function,
                                  std::string_view message) noexcept {
  RefusalLine line;
  for (const Marker& m : kMarkers) {
    if (!ends_with_file(file, m.file)) continue;
    const auto at = message.find(m.text);
    if (at == std::string_view::npos) continue;
    if (m.what == RefusedWhat::kAuthentication &&
        (function != "handshake_end_cb" || message.find(") failed: ") == std::string_view::npos)) {
      continue;
    }
    if ((m.text == "match_remote_writer " || m.text == "match_remote_reader ") &&
        message.find("security_attributes mismatch") == std::string_view::npos) {
      continue;
    }
    line.what = m.what;
    line.has_guid = parse_guid(message.substr(at + m.text.size()), line.guid);
    return line;
  }
  // Every warning and error of the handshake's state machine is a failed step; they name no GUID.
  if (ends_with_file(file, "ddsi_handshake.c")) line.what = RefusedWhat::kAuthentication;
  return line;
}

namespace detail {

bool observe_security_log(std::string_view file, std::string_view function,
                          std::string_view message) noexcept {
  if (!g_refusals_counted.load(std::memory_order_acquire)) return false;
  const RefusalLine line = classify_security_log(file, function, message);
  if (line.what == RefusedWhat::kNothing) return false;
  const bool unsecured = message.starts_with("Non secure remote ");
  State& s = state();
  const std::lock_guard lock(s.mutex);
  switch (line.what) {
    case RefusedWhat::kAuthentication:
      g_authentication.fetch_add(1, std::memory_order_relaxed);
      if (line.has_guid && s.participants.insert(line.guid))
        g_participants.fetch_add(1, std::memory_order_relaxed);
      break;
    case RefusedWhat::kParticipant:
      if (!line.has_guid || s.participants.insert(line.guid))
        g_participants.fetch_add(1, std::memory_order_relaxed);
      break;
    case RefusedWhat::kWriter:
    case RefusedWhat::kReader: {
      auto& table = line.what == RefusedWhat::kWriter ? s.writers : s.readers;
      auto& count = line.what == RefusedWhat::kWriter ? g_writers : g_readers;
      if (!line.has_guid || table.insert(line.guid)) count.fetch_add(1, std::memory_order_relaxed);
      if (unsecured && line.has_guid && s.participants.insert(line.guid))
        g_participants.fetch_add(1, std::memory_order_relaxed);
      break;
    }
    case RefusedWhat::kNothing:
      break;
  }
  s.last_reason_size = copy_printable(message, s.last_reason.data(), s.last_reason.size());
  write_limited(s, line.what, {s.last_reason.data(), s.last_reason_size});
  return true;
}

void report_refusal(RefusedWhat what, std::string_view reason) noexcept {
  if (!g_refusals_counted.load(std::memory_order_acquire) || what == RefusedWhat::kNothing) return;
  State& s = state();
  const std::lock_guard lock(s.mutex);
  s.last_reason_size = copy_printable(reason, s.last_reason.data(), s.last_reason.size());
  write_limited(s, what, {s.last_reason.data(), s.last_reason_size});
}

}  // namespace detail

void count_security_refusals() noexcept {
  if (g_refusals_counted.exchange(true, std::memory_order_acq_rel)) return;
  detail::install_process_log_sink();
}

bool security_refusals_counted() noexcept {
  return g_refusals_counted.load(std::memory_order_acquire);
}

SecurityRefusalCounts security_refusals() noexcept {
  return {g_participants.load(std::memory_order_relaxed), g_writers.load(std::memory_order_relaxed),
          g_readers.load(std::memory_order_relaxed), g_authentication.load(std::memory_order_relaxed)};
}

std::string last_security_refusal() {
  State& s = state();
  const std::lock_guard lock(s.mutex);
  return {s.last_reason.data(), s.last_reason_size};
}

}  // namespace hubrt::dds
