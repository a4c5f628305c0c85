#include "scenario.h"

#include <algorithm>
#include <filesystem>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace hubrt::hubctl {
namespace {

using config::YamlMap;

constexpr std::string_view kStepKinds[] = {"command",      "wait",  "hold",        "station",
                                           "sim",          "badge", "instruction", "fault",
                                           "stop_sending", "sleep", "repeat",      "include"};
constexpr int kMaxRepeat = 10'000;
constexpr double kMaxSeconds = 24 * 3600.0;

// ${i} of the innermost repeat; 0 outside any.
std::string substitute(std::string text, int iteration) {
  if (iteration == 0) return text;
  const std::string marker = "${i}";
  const std::string value = std::to_string(iteration);
  for (auto at = text.find(marker); at != std::string::npos; at = text.find(marker, at + value.size())) {
    text.replace(at, marker.size(), value);
  }
  return text;
}

std::string where(const YamlMap& map) {
  return fmt::format("{}:{}", map.file(), map.node().Mark().line + 1);
}

Expected<std::string> text(const YamlMap& map, std::string_view key, int iteration) {
  auto value = map.string(key);
  if (!value) return value;
  return substitute(std::move(*value), iteration);
}

// hub + node, or station: true.
Expected<StepTarget> target(const YamlMap& body, int iteration, bool node_required) {
  StepTarget out;
  if (body.has("station")) {
    auto station = body.boolean("station");
    if (!station) return std::move(station).error();
    if (!*station) return body.error_at("station", "write station: true, or name a hub and node instead");
    if (body.has("hub") || body.has("node"))
      return body.error("either station: true or hub and node, not both");
    out.station = true;
    return out;
  }
  auto hub = text(body, "hub", iteration);
  if (!hub) return std::move(hub).error();
  out.hub = *hub;
  if (node_required || body.has("node")) {
    auto node = text(body, "node", iteration);
    if (!node) return std::move(node).error();
    out.node = *node;
  }
  return out;
}

Expected<std::vector<Predicate>> conditions(const YamlMap& body, std::string_view key, int iteration) {
  std::vector<std::string> texts;
  if (body.has(key) && body.node()[std::string(key)].IsSequence()) {
    auto list = body.list_of_strings(key);
    if (!list) return std::move(list).error();
    texts = std::move(*list);
    if (texts.empty()) return body.error_at(key, "give at least one condition");
  } else {
    auto one = body.string(key);
    if (!one) return std::move(one).error();
    texts.push_back(std::move(*one));
  }
  std::vector<Predicate> out;
  for (const auto& condition : texts) {
    auto parsed = parse_predicate(substitute(condition, iteration));
    if (!parsed) return body.error_at(key, parsed.error().message);
    out.push_back(std::move(*parsed));
  }
  return out;
}

// Every key of `body` but `taken`, as field = text.
Expected<std::vector<FieldText>> other_fields(const YamlMap& body,
                                              std::initializer_list<std::string_view> taken, int iteration) {
  std::vector<FieldText> out;
  for (const std::string& key : body.keys()) {
    if (std::find(taken.begin(), taken.end(), key) != taken.end()) continue;
    auto value = text(body, key, iteration);
    if (!value) return std::move(value).error();
    out.push_back(FieldText{key, std::move(*value)});
  }
  return out;
}

Expected<Duration> duration(const YamlMap& map, std::string_view key, Duration fallback, bool required) {
  if (!required && !map.has(key)) return fallback;
  auto value = map.number(key, 0.0, kMaxSeconds);
  if (!value) return std::move(value).error();
  // Not session.h's seconds(): the scenario fuzz harness compiles this file without session.cc.
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(*value));
}

struct Context {
  const Scenario& scenario;
  int depth = 0;
};

Expected<void> parse_steps(const YamlMap& parent, std::string_view key, const Context& context, int iteration,
                           std::vector<Step>& out);

Expected<void> parse_body(std::string_view kind, const YamlMap& body, const Context& context, int iteration,
                          Step& step) {
  if (kind == "command") {
    step.kind = StepKind::kCommand;
    auto t = target(body, iteration, true);
    if (!t) return std::move(t).error();
    if (t->station) return body.error("a command goes to a hub's node; the world takes 'station:' steps");
    step.target = std::move(*t);
    auto action = text(body, "action", iteration);
    if (!action) return std::move(action).error();
    step.action = *action;
    auto fields = other_fields(body, {"hub", "node", "action"}, iteration);
    if (!fields) return std::move(fields).error();
    step.fields = std::move(*fields);
  } else if (kind == "wait" || kind == "hold") {
    const bool wait = kind == "wait";
    step.kind = wait ? StepKind::kWait : StepKind::kHold;
    if (auto ok =
            body.only_keys({"hub", "node", "station", wait ? "until" : "while", wait ? "timeout" : "for"});
        !ok)
      return ok;
    auto t = target(body, iteration, true);
    if (!t) return std::move(t).error();
    step.target = std::move(*t);
    auto parsed = conditions(body, wait ? "until" : "while", iteration);
    if (!parsed) return std::move(parsed).error();
    step.conditions = std::move(*parsed);
    auto time = wait ? duration(body, "timeout", context.scenario.default_timeout, false)
                     : duration(body, "for", Duration{}, true);
    if (!time) return std::move(time).error();
    (wait ? step.timeout : step.duration) = *time;
  } else if (kind == "station") {
    step.kind = StepKind::kStation;
    step.target.station = true;
    auto action = text(body, "action", iteration);
    if (!action) return std::move(action).error();
    step.action = *action;
    auto fields = other_fields(body, {"action"}, iteration);
    if (!fields) return std::move(fields).error();
    step.fields = std::move(*fields);
  } else if (kind == "sim") {
    step.kind = StepKind::kSimInput;
    if (auto ok = body.only_keys({"hub", "signal", "active"}); !ok) return ok;
    auto hub = text(body, "hub", iteration);
    if (!hub) return std::move(hub).error();
    auto signal = text(body, "signal", iteration);
    if (!signal) return std::move(signal).error();
    auto active = body.boolean("active");
    if (!active) return std::move(active).error();
    step.target.hub = *hub;
    step.signal = *signal;
    step.active = *active;
  } else if (kind == "badge") {
    step.kind = StepKind::kBadge;
    if (auto ok = body.only_keys({"hub", "reader", "text"}); !ok) return ok;
    auto hub = text(body, "hub", iteration);
    if (!hub) return std::move(hub).error();
    auto reader = text(body, "reader", iteration);
    if (!reader) return std::move(reader).error();
    auto badge = text(body, "text", iteration);
    if (!badge) return std::move(badge).error();
    step.target.hub = *hub;
    step.signal = *reader;
    step.text = *badge;
  } else if (kind == "instruction") {
    step.kind = StepKind::kInstruction;
    if (auto ok = body.only_keys({"step", "text"}); !ok) return ok;
    auto name = text(body, "step", iteration);
    if (!name) return std::move(name).error();
    auto what = text(body, "text", iteration);
    if (!what) return std::move(what).error();
    step.signal = *name;
    step.text = *what;
  } else if (kind == "fault") {
    step.kind = StepKind::kFault;
    if (auto ok = body.only_keys({"hub", "device", "fault", "value"}); !ok) return ok;
    auto hub = text(body, "hub", iteration);
    if (!hub) return std::move(hub).error();
    auto device = text(body, "device", iteration);
    if (!device) return std::move(device).error();
    auto fault = text(body, "fault", iteration);
    if (!fault) return std::move(fault).error();
    auto value = body.integer_or("value", 0, 0, 0xFFFF'FFFF);
    if (!value) return std::move(value).error();
    step.target.hub = *hub;
    step.device = *device;
    step.fault = *fault;
    step.value = static_cast<std::uint32_t>(*value);
  } else if (kind == "stop_sending") {
    step.kind = StepKind::kStopSending;
    if (auto ok = body.only_keys({"hub", "node"}); !ok) return ok;
    auto t = target(body, iteration, false);
    if (!t) return std::move(t).error();
    step.target = std::move(*t);
  }
  return {};
}

Expected<void> parse_step(const YamlMap& map, const Context& context, int iteration, std::vector<Step>& out) {
  std::vector<std::string> kinds;
  for (const std::string& key : map.keys()) {
    if (key == "name") continue;
    if (std::find(std::begin(kStepKinds), std::end(kStepKinds), key) == std::end(kStepKinds)) {
      return map.error_at(key,
                          fmt::format("unknown step '{}' (steps: {})", key, fmt::join(kStepKinds, ", ")));
    }
    kinds.push_back(key);
  }
  if (kinds.size() != 1) {
    return map.error(
        fmt::format("a step is exactly one of: {}; this one has {}", fmt::join(kStepKinds, ", "),
                    kinds.empty() ? std::string("none") : fmt::format("{}", fmt::join(kinds, ", "))));
  }
  const std::string& kind = kinds.front();
  std::string name;
  if (map.has("name")) {
    auto n = text(map, "name", iteration);
    if (!n) return std::move(n).error();
    name = *n;
  }
  if (kind == "repeat") {
    auto body = map.map("repeat");
    if (!body) return std::move(body).error();
    if (auto ok = body->only_keys({"times", "steps"}); !ok) return ok;
    auto times = body->integer("times", 1, kMaxRepeat);
    if (!times) return std::move(times).error();
    if (context.depth >= 4) return map.error("includes and repeats nest at most 4 deep");
    const Context inner{context.scenario, context.depth + 1};
    for (int i = 1; i <= *times; ++i) {
      if (auto ok = parse_steps(*body, "steps", inner, i, out); !ok) return ok;
    }
    return {};
  }
  if (kind == "include") {
    auto file = text(map, "include", iteration);
    if (!file) return std::move(file).error();
    if (context.depth >= 4) return map.error("includes and repeats nest at most 4 deep");
    const std::filesystem::path base = std::filesystem::path(map.file()).parent_path();
    auto included = YamlMap::load_file((base / *file).lexically_normal().string());
    if (!included) return map.error_at("include", included.error().message);
    if (auto ok = included->only_keys({"description", "steps"}); !ok) return ok;
    const Context inner{context.scenario, context.depth + 1};
    return parse_steps(*included, "steps", inner, iteration, out);
  }
  Step step;
  step.where = where(map);
  step.name = std::move(name);
  if (kind == "sleep") {
    auto s = duration(map, "sleep", Duration{}, true);
    if (!s) return std::move(s).error();
    step.kind = StepKind::kSleep;
    step.duration = *s;
  } else {
    auto body = map.map(kind);
    if (!body) return std::move(body).error();
    if (auto ok = parse_body(kind, *body, context, iteration, step); !ok) return ok;
  }
  out.push_back(std::move(step));
  return {};
}

Expected<void> parse_steps(const YamlMap& parent, std::string_view key, const Context& context, int iteration,
                           std::vector<Step>& out) {
  auto steps = parent.list_of_maps(key);
  if (!steps) return std::move(steps).error();
  if (steps->empty()) return parent.error_at(key, "no steps");
  for (const YamlMap& map : *steps) {
    if (auto ok = parse_step(map, context, iteration, out); !ok) return ok;
  }
  return {};
}

std::string target_text(const StepTarget& target) {
  if (target.station) return "station";
  return target.node.empty() ? target.hub : fmt::format("{}/{}", target.hub, target.node);
}

std::string conditions_text(const std::vector<Predicate>& conditions) {
  std::vector<std::string_view> texts;
  texts.reserve(conditions.size());
  for (const auto& c : conditions) texts.emplace_back(c.text);
  return fmt::format("{}", fmt::join(texts, ", "));
}

std::string fields_text(const std::vector<FieldText>& fields) {
  std::string out;
  for (const auto& f : fields) out += fmt::format(" {}={}", f.path, f.text);
  return out;
}

}  // namespace

std::string Step::describe() const {
  if (!name.empty()) return name;
  switch (kind) {
    case StepKind::kCommand:
      return fmt::format("command {}: {}{}", target_text(target), action, fields_text(fields));
    case StepKind::kWait:
      return fmt::format("wait {}: {}", target_text(target), conditions_text(conditions));
    case StepKind::kHold:
      return fmt::format("hold {} for {:.1f} s: {}", target_text(target), to_seconds(duration),
                         conditions_text(conditions));
    case StepKind::kStation:
      return fmt::format("station: {}{}", action, fields_text(fields));
    case StepKind::kSimInput:
      return fmt::format("sim {}: {} -> {}", target.hub, signal, active);
    case StepKind::kBadge:
      // The badge itself stays out of reports and logs, as the operator hub keeps it out of its State.
      return fmt::format("badge {}: a badge at {}", target.hub, signal);
    case StepKind::kInstruction:
      return fmt::format("instruction {}: {}", signal, text);
    case StepKind::kFault:
      return fmt::format("fault {}: {} {}{}", target.hub, device, fault,
                         value != 0 ? fmt::format(" ({})", value) : std::string());
    case StepKind::kStopSending:
      return fmt::format("stop sending to {}", target_text(target));
    case StepKind::kSleep:
      return fmt::format("sleep {:.2f} s", to_seconds(duration));
  }
  return "?";
}

Expected<Scenario> parse_scenario(const YamlMap& root) {
  if (auto ok = root.only_keys({"description", "rate_hz", "timeout", "steps"}); !ok)
    return std::move(ok).error();
  Scenario out;
  out.file = root.file();
  auto description = root.string_or("description", "");
  if (!description) return std::move(description).error();
  out.description = *description;
  auto rate = root.number_or("rate_hz", out.rate_hz, 0.1, 1000.0);
  if (!rate) return std::move(rate).error();
  out.rate_hz = *rate;
  auto timeout = duration(root, "timeout", out.default_timeout, false);
  if (!timeout) return std::move(timeout).error();
  out.default_timeout = *timeout;
  const Context context{out, 0};
  std::vector<Step> steps;
  if (auto ok = parse_steps(root, "steps", context, 0, steps); !ok) return std::move(ok).error();
  out.steps = std::move(steps);
  return out;
}

Expected<Scenario> load_scenario(const std::string& path) {
  auto root = YamlMap::load_file(path);
  if (!root) return std::move(root).error();
  return parse_scenario(*root);
}

}  // namespace hubrt::hubctl
