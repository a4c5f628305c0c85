#include "screen_format.h"

#include <cmath>

#include <fmt/format.h>

#include "hubrt/base/utf8.h"

#include "render.h"
#include "sample_decoder.h"

namespace hubrt::hubctl::screen {
namespace {

constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD

// `text` with every ill-formed byte replaced by U+FFFD; `emit` gets each well-formed sequence.
template <typename Emit>
void for_each_valid(std::string_view text, std::string& out, Emit emit) {
  while (!text.empty()) {
    const std::size_t n = utf8_sequence_length(text);
    if (n == 0) {
      out += kReplacement;
      text.remove_prefix(1);
      continue;
    }
    emit(text.substr(0, n), out);
    text.remove_prefix(n);
  }
}

std::string valid_utf8(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for_each_valid(text, out, [](std::string_view seq, std::string& o) { o += seq; });
  return out;
}

// Every string in `value` made valid UTF-8 (a value decoded by SampleDecoder already is; this
// keeps the page safe whatever a caller passes).
nlohmann::ordered_json repaired(const nlohmann::ordered_json& value) {
  if (value.is_string()) return valid_utf8(value.get_ref<const std::string&>());
  if (value.is_array()) {
    auto out = nlohmann::ordered_json::array();
    for (const auto& item : value) out.push_back(repaired(item));
    return out;
  }
  if (value.is_object()) {
    auto out = nlohmann::ordered_json::object();
    for (const auto& [key, item] : value.items()) out[valid_utf8(key)] = repaired(item);
    return out;
  }
  return value;
}

std::string text_of(const nlohmann::ordered_json& state, const char* key) {
  const auto it = state.find(key);
  return it != state.end() && it->is_string() ? it->get<std::string>() : std::string();
}

// The panel's fields: the State itself (node-type layout) or its first field that is an object
// with operator_verified (hub layout).
const nlohmann::ordered_json* panel_fields(const nlohmann::ordered_json& state) {
  if (!state.is_object()) return nullptr;
  if (state.contains("operator_verified")) return &state;
  for (const auto& [key, value] : state.items())
    if (value.is_object() && value.contains("operator_verified")) return &value;
  return nullptr;
}

}  // namespace

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size() + text.size() / 8);
  for_each_valid(text, out, [](std::string_view seq, std::string& o) {
    if (seq.size() > 1) {
      o += seq;
      return;
    }
    const char c = seq[0];
    switch (c) {
      case '&':
        o += "&amp;";
        break;
      case '<':
        o += "&lt;";
        break;
      case '>':
        o += "&gt;";
        break;
      case '"':
        o += "&quot;";
        break;
      case '\'':
        o += "&#39;";
        break;
      case '\t':
      case '\n':
        o += c;
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F)
          o += kReplacement;
        else
          o += c;
    }
  });
  return out;
}

std::string safe_json(const nlohmann::ordered_json& value) {
  const std::string dumped = safe_dump(repaired(value));
  std::string out;
  out.reserve(dumped.size());
  for (const char c : dumped) {
    switch (c) {
      case '<':
        out += "\\u003c";
        break;
      case '>':
        out += "\\u003e";
        break;
      case '&':
        out += "\\u0026";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string sse_event(std::string_view name, std::string_view data) {
  std::string out = "event: ";
  for (const char c : name)
    if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-')
      out += c;
  out += '\n';
  std::size_t begin = 0;
  while (true) {
    const std::size_t end = data.find_first_of("\r\n", begin);
    out += "data: ";
    out += data.substr(begin, end == std::string_view::npos ? std::string_view::npos : end - begin);
    out += '\n';
    if (end == std::string_view::npos) break;
    begin = end + 1;
    if (data[end] == '\r' && begin < data.size() && data[begin] == '\n') ++begin;
  }
  out += '\n';
  return out;
}

OperatorView find_operator(const std::map<std::string, WatchedState>& states, const std::string& topic,
                           std::chrono::steady_clock::time_point now) {
  OperatorView view;
  for (const auto& [name, w] : states) {
    if (!topic.empty() && name != topic) continue;
    const nlohmann::ordered_json* panel = panel_fields(w.last);
    if (panel == nullptr) continue;
    view.topic = name;
    view.fresh = !w.silent(now);
    const auto& p = *panel;
    view.verified = p.value("operator_verified", false);
    view.name = text_of(p, "operator_name");
    view.verified_for = number_or_nan(p, "verified_for");
    view.last_badge = text_of(p, "last_badge");
    view.last_badge_reason = text_of(p, "last_badge_reason");
    view.confirm_seq = p.value("confirm_seq", std::uint64_t{0});
    break;
  }
  return view;
}

nlohmann::ordered_json snapshot(const OperatorView& op, const std::optional<Instruction>& instruction,
                                const std::map<std::string, WatchedState>& states,
                                std::chrono::steady_clock::time_point now) {
  nlohmann::ordered_json out;
  out["operator"] = {{"topic", op.topic},
                     {"fresh", op.fresh},
                     {"verified", op.verified && op.fresh},
                     {"name", op.name},
                     {"verified_for", std::isfinite(op.verified_for) ? nlohmann::ordered_json(op.verified_for)
                                                                     : nlohmann::ordered_json(nullptr)},
                     {"last_badge", op.last_badge},
                     {"last_badge_reason", op.last_badge_reason},
                     {"confirm_seq", op.confirm_seq}};
  if (instruction)
    out["instruction"] = {
        {"step", instruction->step}, {"text", instruction->text}, {"seq", instruction->seq}};
  else
    out["instruction"] = nullptr;
  auto station = nlohmann::ordered_json::array();
  for (const auto& [topic, w] : states) {
    nlohmann::ordered_json row;
    row["topic"] = topic;
    if (w.received == 0) {
      row["fresh"] = "waiting";
    } else if (w.silent(now)) {
      row["fresh"] = "silent";
    } else {
      row["fresh"] = w.last.value("fresh_msg", false) ? "yes" : "no";
    }
    row["lifecycle"] = w.received == 0 ? std::string("-") : lifecycle(w.last);
    // A t_plus that is NaN (a peer may send anything) is null: JSON has no NaN; the page shows "-".
    const double t_plus = number_or_nan(w.last, "t_plus");
    row["t_plus"] = std::isfinite(t_plus) ? nlohmann::ordered_json(t_plus) : nlohmann::ordered_json(nullptr);
    std::string action;
    if (w.last.is_object() && w.last.contains("echo") && w.last["echo"].is_object())
      action = text_of(w.last["echo"], "action");
    row["action"] = action;
    auto errors = nlohmann::ordered_json::array();
    if (w.last.is_object() && w.last.contains("error_list") && w.last["error_list"].is_array())
      for (const auto& e : w.last["error_list"])
        if (e.is_string()) errors.push_back(e);
    row["errors"] = std::move(errors);
    station.push_back(std::move(row));
  }
  out["station"] = std::move(station);
  return repaired(out);
}

std::string initial_html(const OperatorView& op, const std::optional<Instruction>& instruction) {
  const bool verified = op.verified && op.fresh;
  std::string who = verified ? op.name : std::string("nobody verified");
  std::string text = instruction ? instruction->text : std::string("no instruction yet");
  const std::string step = instruction ? instruction->step : std::string();
  return fmt::format(
      "<p id=\"who\" class=\"{}\">{}</p>\n<h2 id=\"instruction-step\">{}</h2>\n<p id=\"instruction\">{}</p>",
      verified ? "verified" : "unverified", html_escape(who), html_escape(step), html_escape(text));
}

}  // namespace hubrt::hubctl::screen
