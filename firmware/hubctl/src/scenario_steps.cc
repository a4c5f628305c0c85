#include "scenario_steps.h"

#include <thread>

#include <fmt/format.h>

#include "hubrt/dds/sample.h"
#include "hubrt/msgs/json.h"
#include "hubrt/msgs/set_field.h"

#include "render.h"
#include "session.h"

namespace hubrt::hubctl {
namespace {

// A sample of `type` with `assignments` set, as JSON (strings not given are "").
Expected<nlohmann::ordered_json> build(const msgs::TypeInfo& type,
                                       const std::vector<std::pair<std::string, std::string>>& assignments) {
  if (type.descriptor == nullptr) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{} cannot be sent on its own", type.ros_name));
  }
  dds::UntypedSample sample(*type.descriptor);
  for (const auto& [path, text] : assignments) {
    if (auto set = msgs::set_field(type, sample.data(), path, text); !set) return std::move(set).error();
  }
  return msgs::to_json(type, sample.data());
}

std::vector<std::pair<std::string, std::string>> assignments(const Step& step) {
  std::vector<std::pair<std::string, std::string>> out;
  out.emplace_back("action", step.action);
  for (const auto& field : step.fields) out.emplace_back(field.path, field.text);
  return out;
}

// Turns the plan's fragments into the sample it sends.
Expected<void> rebuild(Plan& plan) {
  const NodeEndpoints& e = plan.endpoints;
  nlohmann::ordered_json document;
  if (e.layout == Layout::kNodeType) {
    document = plan.fragments.begin()->second;
  } else {
    document["target_type"] = e.target_type;
    document["target_name"] = plan.hub;
    document["action"] = "apply";
    for (const auto& [node, fragment] : plan.fragments) document[node] = fragment;
  }
  dds::UntypedSample sample(*e.command_type->descriptor);
  // Unset strings go on the wire as "", not as a null the serializer refuses.
  if (auto ok =
          msgs::from_json(*e.command_type, msgs::to_json(*e.command_type, sample.data()), sample.data());
      !ok)
    return ok;
  if (auto ok = msgs::from_json(*e.command_type, document, sample.data()); !ok) return ok;
  plan.sample.emplace(std::move(sample));
  return {};
}

// Evaluates every condition on `state`: all hold, or the first that does not (and whether it
// never can).
struct Check {
  bool holds = true;
  bool broken = false;
  std::string detail;
};
Check check(const std::vector<Predicate>& conditions, const nlohmann::ordered_json& state) {
  for (const Predicate& condition : conditions) {
    const PredicateVerdict verdict = evaluate(condition, state);
    if (!verdict.holds)
      return Check{false, verdict.broken, fmt::format("{}: {}", condition.text, verdict.detail)};
  }
  return {};
}

const nlohmann::ordered_json& view(const StateChannel& channel, const std::string& field) {
  if (field.empty() || !channel.latest.contains(field)) return channel.latest;
  return channel.latest[field];
}

std::string last_state(const StateChannel& channel, const std::string& field) {
  if (channel.generation == 0) return fmt::format("no State received on {}\n", channel.topic);
  const double age = std::chrono::duration<double>(SteadyClock::now() - channel.received_at).count();
  return fmt::format("last State on {}{} ({:.2f} s ago):\n{}", channel.topic,
                     field.empty() ? std::string() : fmt::format(", field {}", field), age,
                     indent(render_human(view(channel, field)), "  "));
}

StepResult write_once(WriterEntry& entry, const msgs::TypeInfo& type,
                      const nlohmann::ordered_json& document) {
  dds::UntypedSample sample(*type.descriptor);
  if (auto ok = msgs::from_json(type, document, sample.data()); !ok) return failed(ok.error().message);
  if (auto written = entry.writer->write(sample.data()); !written.is_ok()) {
    return failed(
        fmt::format("writing {} failed: {}", entry.writer->topic_name(), to_string(written.code())));
  }
  return {};
}

}  // namespace

std::string indent(const std::string& text, std::string_view pad) {
  std::string out;
  std::size_t start = 0;
  while (start < text.size()) {
    auto end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    out += fmt::format("{}{}\n", pad, std::string_view(text).substr(start, end - start));
    start = end + 1;
  }
  return out;
}

StepResult StepExecutor::execute(const Step& step) {
  switch (step.kind) {
    case StepKind::kCommand:
      return command(step);
    case StepKind::kWait:
      return wait(step);
    case StepKind::kHold:
      return hold(step);
    case StepKind::kStation:
      return station(step);
    case StepKind::kSimInput:
      return sim_input(step);
    case StepKind::kBadge:
      return badge(step);
    case StepKind::kInstruction:
      return instruction(step);
    case StepKind::kFault:
      return fault(step);
    case StepKind::kStopSending:
      return stop_sending(step);
    case StepKind::kSleep:
      traffic_.pump_for(step.duration);
      return {};
  }
  return failed("unknown step");
}

StepResult StepExecutor::command(const Step& step) {
  auto endpoints = traffic_.locate(step.target);
  if (!endpoints) return failed(endpoints.error().message);
  auto fields = assignments(step);
  if (endpoints->layout == Layout::kNodeType) {
    fields.emplace(fields.begin(), "target_name", step.target.node);
    fields.emplace(fields.begin(), "target_type", endpoints->target_type);
  }
  auto fragment = build(*endpoints->node_command_type, fields);
  if (!fragment) return failed(fragment.error().message);
  const std::string key = endpoints->layout == Layout::kNodeType
                              ? fmt::format("{}/{}", step.target.hub, step.target.node)
                              : step.target.hub;
  auto w = traffic_.command_writer(endpoints->command_topic, *endpoints->command_type);
  if (!w) return failed(w.error().message);
  Plan& plan = traffic_.plans()[key];
  plan.hub = step.target.hub;
  plan.endpoints = *endpoints;
  plan.writer = *w;
  plan.fragments[step.target.node] = std::move(*fragment);
  if (auto ok = rebuild(plan); !ok) return failed(ok.error().message);
  ScenarioTraffic::send(plan);  // at once, as the planner does with a new command; then at the rate
  return {};
}

StepResult StepExecutor::stop_sending(const Step& step) {
  auto& plans = traffic_.plans();
  for (auto it = plans.begin(); it != plans.end();) {
    Plan& plan = it->second;
    if (plan.hub != step.target.hub) {
      ++it;
      continue;
    }
    if (!step.target.node.empty()) {
      plan.fragments.erase(step.target.node);
      if (!plan.fragments.empty()) {
        if (auto ok = rebuild(plan); !ok) return failed(ok.error().message);
        ++it;
        continue;
      }
    }
    it = plans.erase(it);
  }
  return {};
}

StepResult StepExecutor::wait(const Step& step) {
  auto state = traffic_.state_of(step.target);
  if (!state) return failed(state.error().message);
  const auto& [channel, field] = *state;
  const std::uint64_t seen = channel->generation;  // only States that arrive from now on count
  const auto deadline = SteadyClock::now() + step.timeout;
  Check last{false, false, "no State arrived since the step began"};
  std::uint64_t judged = seen;
  while (!stop_requested()) {
    traffic_.pump();
    if (channel->generation > judged) {
      judged = channel->generation;
      last = check(step.conditions, view(*channel, field));
      if (last.holds) return {};
      if (last.broken)
        return failed(fmt::format("cannot be evaluated: {}\n{}", last.detail, last_state(*channel, field)));
    }
    if (SteadyClock::now() >= deadline) break;
    std::this_thread::sleep_for(kPoll);
  }
  return failed(fmt::format("not met within {:.1f} s: {}\n{}", to_seconds(step.timeout), last.detail,
                            last_state(*channel, field)));
}

StepResult StepExecutor::hold(const Step& step) {
  auto state = traffic_.state_of(step.target);
  if (!state) return failed(state.error().message);
  const auto& [channel, field] = *state;
  std::uint64_t judged = channel->generation;
  const std::uint64_t first = judged;
  const auto until = SteadyClock::now() + step.duration;
  while (SteadyClock::now() < until && !stop_requested()) {
    traffic_.pump();
    if (channel->generation > judged) {
      judged = channel->generation;
      const Check c = check(step.conditions, view(*channel, field));
      if (!c.holds) return failed(fmt::format("broken: {}\n{}", c.detail, last_state(*channel, field)));
    }
    std::this_thread::sleep_for(kPoll);
  }
  if (judged == first) return failed(fmt::format("no State arrived on {} to check", channel->topic));
  return {};
}

StepResult StepExecutor::station(const Step& step) {
  auto type = ScenarioTraffic::known_type("hub_msgs/msg/StationCommand");
  if (!type) return failed(type.error().message);
  auto fields = assignments(step);
  fields.emplace(fields.begin(), "target_name", "station");
  fields.emplace(fields.begin(), "target_type", "station");
  auto document = build(**type, fields);
  if (!document) return failed(document.error().message);
  auto w = traffic_.writer(traffic_.station_topic(kStationCommandTopic), **type);
  if (!w) return failed(fmt::format("{} (is hubsim running?)", w.error().message));
  return write_once(**w, **type, *document);
}

StepResult StepExecutor::sim_input(const Step& step) {
  auto type = ScenarioTraffic::known_type("hub_msgs/msg/SimInput");
  if (!type) return failed(type.error().message);
  auto document =
      build(**type,
            {{"hub", step.target.hub}, {"signal", step.signal}, {"active", step.active ? "true" : "false"}});
  if (!document) return failed(document.error().message);
  return to_hub(traffic_.station_topic(kSimInputTopic), step.target.hub, **type, *document);
}

StepResult StepExecutor::badge(const Step& step) {
  auto type = ScenarioTraffic::known_type("hub_msgs/msg/SimBadge");
  if (!type) return failed(type.error().message);
  auto document = build(**type, {{"hub", step.target.hub}, {"reader", step.signal}, {"text", step.text}});
  if (!document) return failed(document.error().message);
  return to_hub(traffic_.station_topic(kSimBadgeTopic), step.target.hub, **type, *document);
}

// To the operator screens discovery knows (the writer waits until they are matched, so an
// instruction is not lost to a writer matched too late). A station may run without a screen: only
// the first instruction of a run gives discovery up to kFirstScreenPatience to find one (this
// hubctl may have just joined); a screen opened later gets the instruction's next repetition.
StepResult StepExecutor::instruction(const Step& step) {
  constexpr auto kFirstScreenPatience = std::chrono::seconds(1);
  auto type = ScenarioTraffic::known_type("hub_msgs/msg/OperatorInstruction");
  if (!type) return failed(type.error().message);
  if (!looked_for_screens_) {
    looked_for_screens_ = true;
    const auto until = SteadyClock::now() + kFirstScreenPatience;
    for (auto known = traffic_.readers_now(traffic_.station_topic(kInstructionTopic));
         known && *known == 0 && SteadyClock::now() < until;
         known = traffic_.readers_now(traffic_.station_topic(kInstructionTopic))) {
      traffic_.pump_for(kPoll);
    }
  }
  auto document = build(
      **type, {{"step", step.signal}, {"text", step.text}, {"seq", std::to_string(++instruction_seq_)}});
  if (!document) return failed(document.error().message);
  auto screens = traffic_.readers_now(traffic_.station_topic(kInstructionTopic));
  if (!screens) return failed(screens.error().message);
  auto w = traffic_.writer(traffic_.station_topic(kInstructionTopic), **type, *screens);
  if (!w) return failed(w.error().message);
  // Like a command, the instruction is a state (docs/operator-screen.md): sent at once, then again
  // at the scenario's rate until the next one, so a screen opened later shows it too.
  Plan& plan = traffic_.plans()[traffic_.station_topic(kInstructionTopic)];
  plan.writer = *w;
  plan.sample.emplace(*(*type)->descriptor);
  if (auto ok = msgs::from_json(**type, *document, plan.sample->data()); !ok)
    return failed(ok.error().message);
  ScenarioTraffic::send(plan);
  return {};
}

StepResult StepExecutor::fault(const Step& step) {
  auto type = ScenarioTraffic::known_type("hub_msgs/msg/SimFault");
  if (!type) return failed(type.error().message);
  auto document = build(**type, {{"hub", step.target.hub},
                                 {"device", step.device},
                                 {"fault", step.fault},
                                 {"value", std::to_string(step.value)}});
  if (!document) return failed(document.error().message);
  return to_hub(traffic_.station_topic(kSimFaultTopic), step.target.hub, **type, *document);
}

// Once, to every hub's sim bridge, after the one addressed is matched.
StepResult StepExecutor::to_hub(const std::string& topic, const std::string& hub, const msgs::TypeInfo& type,
                                const nlohmann::ordered_json& document) {
  auto readers = traffic_.readers_including(topic, hub);
  if (!readers) return failed(readers.error().message);
  auto w = traffic_.writer(topic, type, *readers);
  if (!w) return failed(w.error().message);
  return write_once(**w, type, document);
}

}  // namespace hubrt::hubctl
