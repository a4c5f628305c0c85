// The operator screen's text: what `hubctl serve` sends to the browser, kept apart from the HTTP
// server so that it is tested on its own with hostile strings. States come from anyone on the
// DDS domain, so every string is made valid UTF-8 and escaped for where it goes (HTML, JSON in
// server-sent events).
#pragma once

#include <chrono>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "station_watch.h"

namespace hubrt::hubctl::screen {

// `text` as HTML text or attribute value: & < > " ' as character references, every byte that is
// not part of a well-formed UTF-8 sequence (RFC 3629) and every C0 control but tab and newline
// (and DEL) as U+FFFD.
std::string html_escape(std::string_view text);

// `value` as one line of JSON that is safe anywhere in a page: valid UTF-8 (bad bytes become
// U+FFFD), and < > & written as \u003c \u003e \u0026 so that no "</script>" or "<!--" appears.
std::string safe_json(const nlohmann::ordered_json& value);

// One server-sent event (WHATWG HTML, "Server-sent events", the event stream format): the name
// (letters, digits, '_' and '-' only; anything else is dropped) and the data, one "data:" line per
// line of `data` (CR, LF and CRLF all end a line), then the blank line that dispatches it.
std::string sse_event(std::string_view name, std::string_view data);

// What the screen knows about the operator panel.
struct OperatorView {
  std::string topic;   // "" when no operator panel State was found
  bool fresh = false;  // its State is not silent
  bool verified = false;
  std::string name;
  double verified_for = 0;
  std::string last_badge;
  std::string last_badge_reason;
  std::uint64_t confirm_seq = 0;
};

// The operator panel among `states`: the one on `topic` when given, else the first whose State
// (node-type layout) or one of whose fields (hub layout, e.g. "panel") has operator_verified.
OperatorView find_operator(const std::map<std::string, WatchedState>& states, const std::string& topic,
                           std::chrono::steady_clock::time_point now);

// The current instruction, as the planner published it.
struct Instruction {
  std::string step;
  std::string text;
  std::uint64_t seq = 0;
};

// Everything the page shows, as JSON: {"operator": {...}, "instruction": {...} or null,
// "station": [{"topic", "fresh": "yes"|"no"|"silent"|"waiting", "lifecycle", "t_plus", "action",
// "errors": [...]}...]}.
nlohmann::ordered_json snapshot(const OperatorView& op, const std::optional<Instruction>& instruction,
                                const std::map<std::string, WatchedState>& states,
                                std::chrono::steady_clock::time_point now);

// The page's first view without script: who is verified and the instruction, HTML-escaped.
std::string initial_html(const OperatorView& op, const std::optional<Instruction>& instruction);

}  // namespace hubrt::hubctl::screen
