// Counting and logging what DDS Security refuses in this process (issue 34 point 4): remote
// participants that do not authenticate, that access control refuses or that come without
// security, and remote writers refused, so that /diagnostics shows an attempt on a station.
//
// Cyclone 0.10.2 has no status, listener or count for any of these: proxy participants appear on
// DCPSParticipant before their handshake and stay there when it fails, and refused endpoints are
// simply not matched. What it does is log (src/core/ddsi/src/ddsi_handshake.c, HSEXCEPTION and
// HSERROR: "Begin handshake reply failed: <the plugin's reason>(code: N)", ...;
// ddsi_entity_match.c, handshake_end_cb: "handshake (lguid=G rguid=G) failed: (N) Failed" or
// "Timed out" after 100 s; ddsi_security_omg.c: "Non secure remote writer G is not allowed.",
// "Access control does not allow remote writer G", "Plugin does not allow remote participant G",
// ...; ddsi_proxy_participant.c: "Remote secure participant G not allowed"). count_security_
// refusals() installs the process's Cyclone log sink (the one of oversize_samples.h: a process
// has one) and reads those lines: by the source file and function Cyclone names, then a fixed
// marker before the GUID — nothing else of the text is interpreted; the reason is kept as text.
//
// Limits: with discovery protection on (hubrt's governance) Cyclone logs an access-control
// refusal of a remote writer or reader at trace level only (handle_not_allowed), which no sink
// sees unless tracing is on: a secured peer with permissions that do not allow a topic is refused
// all the same, but not counted here (its own side refuses the endpoint first, with
// DDS_RETCODE_NOT_ALLOWED_BY_SECURITY). Handshake failures mostly name no GUID: they are counted as
// events (each retry of a failing handshake is one, about one a second per peer); participants
// are counted once each where Cyclone names them.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace hubrt::dds {

// What one Cyclone log line says was refused.
enum class RefusedWhat : std::uint8_t {
  kNothing,         // not a refusal
  kAuthentication,  // a handshake step failed or timed out (the peer's or our certificate)
  kParticipant,     // a remote participant refused (access control, no security, no match)
  kWriter,          // a remote writer refused (no security, access control, attributes)
  kReader,          // a remote reader refused
};

struct RefusalLine {
  RefusedWhat what = RefusedWhat::kNothing;
  // The remote entity's GUID as Cyclone prints it ("1107a8e1:6c1f5a4e:e3d4a1cb:103") when the line
  // names one; its first three groups are its participant.
  std::array<std::uint32_t, 4> guid{};
  bool has_guid = false;
};

// Reads one Cyclone log line: `file` and `function` as Cyclone's log record names them, `message`
// without the header. Pure; never allocates.
[[nodiscard]] RefusalLine classify_security_log(std::string_view file, std::string_view function,
                                                std::string_view message) noexcept;

struct SecurityRefusalCounts {
  std::uint64_t participants = 0;    // distinct remote participants refused, as Cyclone names them
  std::uint64_t writers = 0;         // distinct remote writers refused
  std::uint64_t readers = 0;         // distinct remote readers refused
  std::uint64_t authentication = 0;  // failed handshake steps (events)
  [[nodiscard]] std::uint64_t total() const noexcept {
    return participants + writers + readers + authentication;
  }
};

// Installs the counting log sink (once per process; later calls do nothing) and counts from then
// on. Refusals are logged rate-limited where Cyclone's lines go (stderr, or what
// forward_cyclone_log set: hubd's bounded log queue): the first of each kind at once, then at most
// one line per kind every 10 s saying how many more there were; every other Cyclone message is
// written as Cyclone's default sink writes it. Call before the first participant. Thread-safe.
void count_security_refusals() noexcept;

// Whether count_security_refusals() was called in this process.
[[nodiscard]] bool security_refusals_counted() noexcept;

// The counts since count_security_refusals(). Thread-safe, lock-free.
[[nodiscard]] SecurityRefusalCounts security_refusals() noexcept;

// The last refusal's Cyclone message ("" when none yet), e.g. "Begin handshake reply failed:
// Certificate verification error: unable to get local issuer certificate(code: 0)", at most 300
// bytes, every byte that is not printable ASCII as '?' (the peer chose its certificate's subject);
// the log lines are written so too. Thread-safe; allocates the string returned.
[[nodiscard]] std::string last_security_refusal();

namespace detail {
// Called by the process's log sink (oversize_samples.cc) for every message. True when it is a
// refusal, counted and logged (or held back by the rate limit) here: the sink writes nothing more
// for it. False (the sink writes the message as Cyclone would) before count_security_refusals().
bool observe_security_log(std::string_view file, std::string_view function,
                          std::string_view message) noexcept;
// A refusal found elsewhere (peer_authentication_watch.h): logged rate-limited as the others and
// kept as the last reason; not counted here. Does nothing before count_security_refusals().
void report_refusal(RefusedWhat what, std::string_view reason) noexcept;
}  // namespace detail

}  // namespace hubrt::dds
