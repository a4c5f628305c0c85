#include "scenario_runner.h"

#include <map>
#include <optional>
#include <set>
#include <thread>

#include <fmt/format.h>

#include "hubrt/dds/discovery.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/ros_names.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/json.h"
#include "hubrt/msgs/set_field.h"

#include "node_locator.h"
#include "render.h"
#include "sample_decoder.h"
#include "session.h"

namespace hubrt::hubctl {
namespace {

using SteadyClock = std::chrono::steady_clock;

constexpr std::string_view kStationStateTopic = "/sim/station/state";
constexpr std::string_view kStationCommandTopic = "/sim/station/command";
constexpr std::string_view kSimInputTopic = "/sim/input";
constexpr std::string_view kSimFaultTopic = "/sim/fault";
// How often the loop looks for samples and due commands while a step runs.
constexpr auto kPoll = std::chrono::milliseconds(5);

struct StepResult {
  bool ok = true;
  std::string detail;  // why it failed, several lines
};

StepResult failed(std::string detail) {
  return StepResult{false, std::move(detail)};
}

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

// A State topic being read: the latest sample, as JSON, and how many have arrived.
struct StateChannel {
  std::string topic;
  const msgs::TypeInfo* type = nullptr;
  std::optional<dds::UntypedTopic> dds_topic;
  std::optional<dds::UntypedReader> reader;
  std::optional<dds::UntypedSample> sample;
  std::optional<SampleDecoder> decoder;
  nlohmann::ordered_json latest;
  std::uint64_t generation = 0;
  SteadyClock::time_point received_at{};
};

struct WriterEntry {
  std::optional<dds::UntypedTopic> topic;
  std::optional<dds::UntypedWriter> writer;
};

// A command the planner keeps sending: one node's (node-type layout) or one hub's, with the
// fragments of every node commanded so far (hub layout).
struct Plan {
  std::string hub;
  NodeEndpoints endpoints;
  std::map<std::string, nlohmann::ordered_json> fragments;  // node -> its command
  std::optional<dds::UntypedSample> sample;
  WriterEntry* writer = nullptr;
};

}  // namespace

class ScenarioRunner::Impl {
 public:
  Impl(const dds::Participant& participant, const Scenario& scenario, PlayOptions options, std::FILE* out)
      : participant_(participant),
        scenario_(scenario),
        options_(options),
        out_(out),
        period_(seconds(1.0 / (options.rate_hz > 0 ? options.rate_hz : scenario.rate_hz))) {}

  PlayOutcome run() {
    const auto start = SteadyClock::now();
    const auto since_start = [&start] {
      return std::chrono::duration<double>(SteadyClock::now() - start).count();
    };
    if (!scenario_.description.empty() && !options_.quiet)
      fmt::print(out_, "play: {}\n", scenario_.description);
    std::fflush(out_);  // a pipe or a file sees the run begin, not only its first step's end
    next_send_ = SteadyClock::now();
    std::size_t done = 0;
    for (int round = 1; options_.rounds == 0 || round <= options_.rounds; ++round) {
      if (options_.rounds != 1 && !options_.quiet) fmt::print(out_, "play: round {}\n", round);
      for (std::size_t i = 0; i < scenario_.steps.size(); ++i) {
        const Step& step = scenario_.steps[i];
        const auto step_start = SteadyClock::now();
        StepResult result = stop_requested() ? failed("") : execute(step);
        const double took = std::chrono::duration<double>(SteadyClock::now() - step_start).count();
        // A step that did not pass because Ctrl-C cut it short (a wait that stopped waiting) has
        // not failed: what it waited for may still have come.
        const bool interrupted = !result.ok && stop_requested();
        if (!result.ok || !options_.quiet) {
          fmt::print(out_, "  {}  {:6.2f} s  [{:>3}] {}  {}\n",
                     result.ok ? "PASS" : (interrupted ? "STOP" : "FAIL"), took, i + 1, step.where,
                     step.describe());
        }
        if (interrupted) {
          fmt::print(out_, "play: interrupted at step {} of {} ({}){} after {:.1f} s; {} step(s) passed\n",
                     i + 1, scenario_.steps.size(), step.where,
                     options_.rounds != 1 ? fmt::format(" in round {}", round) : std::string(), since_start(),
                     done);
          std::fflush(out_);
          return PlayOutcome::kInterrupted;
        }
        if (!result.ok) {
          fmt::print(out_, "{}", indent(result.detail, "        "));
          fmt::print(out_, "play: FAILED at step {} of {} ({}) after {:.1f} s\n", i + 1,
                     scenario_.steps.size(), step.where, since_start());
          std::fflush(out_);
          return PlayOutcome::kFailed;
        }
        ++done;
        std::fflush(out_);
      }
      const bool more_rounds = options_.rounds == 0 || round < options_.rounds;
      if (stop_requested() && more_rounds) {  // all rounds done: it passed, signal or not
        fmt::print(out_, "play: interrupted after round {}; {} step(s) passed in {:.1f} s\n", round, done,
                   since_start());
        std::fflush(out_);
        return PlayOutcome::kInterrupted;
      }
    }
    fmt::print(out_, "play: PASSED: {} step(s) in {:.1f} s\n", done, since_start());
    std::fflush(out_);
    return PlayOutcome::kPassed;
  }

 private:
  StepResult execute(const Step& step) {
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
      case StepKind::kFault:
        return fault(step);
      case StepKind::kStopSending:
        return stop_sending(step);
      case StepKind::kSleep:
        pump_for(step.duration);
        return {};
    }
    return failed("unknown step");
  }

  // ---- the loop: samples in, due commands out ---------------------------------------------------

  void pump() {
    for (auto& [topic, channel] : states_) {
      for (int i = 0; i < 256; ++i) {
        const Result<bool> taken = channel->reader->take_next(channel->sample->data());
        if (!taken.is_ok() || !taken.value()) break;
        // A sample that cannot be read is reported and skipped; the scenario goes on.
        auto value = channel->decoder->decode(*channel->type, channel->sample->data());
        if (!value) continue;
        channel->latest = std::move(*value);
        channel->received_at = SteadyClock::now();
        ++channel->generation;
      }
    }
    const auto now = SteadyClock::now();
    if (now >= next_send_) {
      for (auto& [key, plan] : plans_) send(plan);
      next_send_ += std::chrono::duration_cast<SteadyClock::duration>(period_);
      if (next_send_ < now) next_send_ = now;  // a stall: do not burst to catch up
    }
  }

  void pump_for(Duration span) {
    const auto until = SteadyClock::now() + span;
    while (SteadyClock::now() < until && !stop_requested()) {
      pump();
      std::this_thread::sleep_for(kPoll);
    }
  }

  void send(Plan& plan) {
    if (plan.sample && plan.writer != nullptr) plan.writer->writer->write(plan.sample->data()).ignore();
  }

  // ---- where things are --------------------------------------------------------------------------

  Expected<NodeEndpoints> locate(const StepTarget& target) {
    const std::string key = fmt::format("{}/{}", target.hub, target.node);
    if (auto known = located_.find(key); known != located_.end()) return known->second;
    auto found =
        find_node(participant_, msgs::all_types(), target.hub, target.node, options_.discovery_timeout);
    if (!found) return found;
    located_.emplace(key, *found);
    return found;
  }

  Expected<const msgs::TypeInfo*> known_type(std::string_view ros_name) {
    const msgs::TypeInfo* type = msgs::all_types().find(ros_name);
    if (type == nullptr || type->descriptor == nullptr) {
      return make_error(ErrorCode::kNotFound, fmt::format("this hubctl does not know the type {}", ros_name));
    }
    return type;
  }

  Expected<StateChannel*> channel(const std::string& topic, const msgs::TypeInfo& type) {
    if (auto it = states_.find(topic); it != states_.end()) return it->second.get();
    auto entry = std::make_unique<StateChannel>();
    entry->topic = topic;
    entry->type = &type;
    auto t = dds::UntypedTopic::create(participant_, *type.descriptor, topic);
    if (!t) return std::move(t).error();
    entry->dds_topic.emplace(std::move(*t));
    auto r = dds::UntypedReader::create(participant_, *entry->dds_topic);
    if (!r) return std::move(r).error();
    entry->reader.emplace(std::move(*r));
    entry->sample.emplace(*type.descriptor);
    entry->decoder.emplace("hubctl play", topic);
    StateChannel* raw = entry.get();
    states_.emplace(topic, std::move(entry));
    return raw;
  }

  // Where the State of `target` arrives, and which part of it is the node's (empty: all of it).
  Expected<std::pair<StateChannel*, std::string>> state_of(const StepTarget& target) {
    if (target.station) {
      auto type = known_type("hub_msgs/msg/StationState");
      if (!type) return std::move(type).error();
      auto c = channel(std::string(kStationStateTopic), **type);
      if (!c) return std::move(c).error();
      return std::make_pair(*c, std::string());
    }
    auto endpoints = locate(target);
    if (!endpoints) return std::move(endpoints).error();
    auto c = channel(endpoints->state_topic, *endpoints->state_type);
    if (!c) return std::move(c).error();
    return std::make_pair(*c, endpoints->field);
  }

  // A writer on `topic`, matched with at least `readers` readers (waits up to the discovery
  // timeout; a writer that is not matched yet would send into the void).
  Expected<WriterEntry*> writer(const std::string& topic, const msgs::TypeInfo& type,
                                std::uint32_t readers = 1) {
    auto it = writers_.find(topic);
    if (it == writers_.end()) {
      auto entry = std::make_unique<WriterEntry>();
      auto t = dds::UntypedTopic::create(participant_, *type.descriptor, topic);
      if (!t) return std::move(t).error();
      entry->topic.emplace(std::move(*t));
      auto w = dds::UntypedWriter::create(participant_, *entry->topic);
      if (!w) return std::move(w).error();
      entry->writer.emplace(std::move(*w));
      it = writers_.emplace(topic, std::move(entry)).first;
    }
    if (auto matched = wait_for_readers(*it->second, readers); !matched) return std::move(matched).error();
    return it->second.get();
  }

  Expected<void> wait_for_readers(const WriterEntry& entry, std::uint32_t count) {
    const auto deadline = SteadyClock::now() + options_.discovery_timeout;
    while (true) {
      const auto matched = entry.writer->matched_readers();
      if (matched.is_ok() && matched.value() >= count) return {};
      if (SteadyClock::now() >= deadline || stop_requested()) {
        return make_error(ErrorCode::kTimeout,
                          fmt::format("nobody reads {} ({} of {} reader(s) matched after {:.1f} s)",
                                      entry.writer->topic_name(), matched.is_ok() ? matched.value() : 0,
                                      count, to_seconds(options_.discovery_timeout)));
      }
      pump();
      std::this_thread::sleep_for(kPoll);
    }
  }

  // The number of remote readers of `ros_topic`, once the hub `hub` is among them.
  Expected<std::uint32_t> readers_including(std::string_view ros_topic, std::string_view hub) {
    auto dds_name = dds::ros_to_dds_topic(ros_topic);
    if (!dds_name) return std::move(dds_name).error();
    const auto deadline = SteadyClock::now() + options_.discovery_timeout;
    while (true) {
      auto snapshot = dds::discover(participant_);
      if (!snapshot) return std::move(snapshot).error();
      std::set<dds::Guid> hub_keys;
      for (const auto& p : snapshot->participants) {
        if (!p.local && p.name == hub) hub_keys.insert(p.key);
      }
      std::uint32_t readers = 0;
      bool hub_listens = false;
      for (const auto& e : snapshot->endpoints) {
        if (e.local || e.direction != dds::EndpointDirection::kReader || e.topic_name != *dds_name) continue;
        ++readers;
        hub_listens |= hub_keys.count(e.participant_key) != 0;
      }
      if (hub_listens) return readers;
      if (SteadyClock::now() >= deadline || stop_requested()) {
        return make_error(ErrorCode::kNotFound,
                          fmt::format("hub '{}' does not listen to {} (is it running on the fake backend?)",
                                      hub, ros_topic));
      }
      pump();
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }

  // ---- the steps ---------------------------------------------------------------------------------

  // A sample of `type` with `assignments` set, as JSON (strings not given are "").
  static Expected<nlohmann::ordered_json> build(
      const msgs::TypeInfo& type, const std::vector<std::pair<std::string, std::string>>& assignments) {
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

  static std::vector<std::pair<std::string, std::string>> assignments(const Step& step) {
    std::vector<std::pair<std::string, std::string>> out;
    out.emplace_back("action", step.action);
    for (const auto& field : step.fields) out.emplace_back(field.path, field.text);
    return out;
  }

  // Turns the plan's fragments into the sample it sends.
  static Expected<void> rebuild(Plan& plan) {
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

  StepResult command(const Step& step) {
    auto endpoints = locate(step.target);
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
    auto w = writer(endpoints->command_topic, *endpoints->command_type);
    if (!w) return failed(w.error().message);
    Plan& plan = plans_[key];
    plan.hub = step.target.hub;
    plan.endpoints = *endpoints;
    plan.writer = *w;
    plan.fragments[step.target.node] = std::move(*fragment);
    if (auto ok = rebuild(plan); !ok) return failed(ok.error().message);
    send(plan);  // at once, as the planner does with a new command; then at the rate
    return {};
  }

  StepResult stop_sending(const Step& step) {
    for (auto it = plans_.begin(); it != plans_.end();) {
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
      it = plans_.erase(it);
    }
    return {};
  }

  // Evaluates every condition on `state`: all hold, or the first that does not (and whether it
  // never can).
  struct Check {
    bool holds = true;
    bool broken = false;
    std::string detail;
  };
  static Check check(const std::vector<Predicate>& conditions, const nlohmann::ordered_json& state) {
    for (const Predicate& condition : conditions) {
      const Verdict verdict = evaluate(condition, state);
      if (!verdict.holds)
        return Check{false, verdict.broken, fmt::format("{}: {}", condition.text, verdict.detail)};
    }
    return {};
  }

  static const nlohmann::ordered_json& view(const StateChannel& channel, const std::string& field) {
    if (field.empty() || !channel.latest.contains(field)) return channel.latest;
    return channel.latest[field];
  }

  static std::string last_state(const StateChannel& channel, const std::string& field) {
    if (channel.generation == 0) return fmt::format("no State received on {}\n", channel.topic);
    const double age = std::chrono::duration<double>(SteadyClock::now() - channel.received_at).count();
    return fmt::format("last State on {}{} ({:.2f} s ago):\n{}", channel.topic,
                       field.empty() ? std::string() : fmt::format(", field {}", field), age,
                       indent(render_human(view(channel, field)), "  "));
  }

  StepResult wait(const Step& step) {
    auto state = state_of(step.target);
    if (!state) return failed(state.error().message);
    const auto& [channel, field] = *state;
    const std::uint64_t seen = channel->generation;  // only States that arrive from now on count
    const auto deadline = SteadyClock::now() + step.timeout;
    Check last{false, false, "no State arrived since the step began"};
    std::uint64_t judged = seen;
    while (!stop_requested()) {
      pump();
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

  StepResult hold(const Step& step) {
    auto state = state_of(step.target);
    if (!state) return failed(state.error().message);
    const auto& [channel, field] = *state;
    std::uint64_t judged = channel->generation;
    const std::uint64_t first = judged;
    const auto until = SteadyClock::now() + step.duration;
    while (SteadyClock::now() < until && !stop_requested()) {
      pump();
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

  StepResult station(const Step& step) {
    auto type = known_type("hub_msgs/msg/StationCommand");
    if (!type) return failed(type.error().message);
    auto fields = assignments(step);
    fields.emplace(fields.begin(), "target_name", "station");
    fields.emplace(fields.begin(), "target_type", "station");
    auto document = build(**type, fields);
    if (!document) return failed(document.error().message);
    auto w = writer(std::string(kStationCommandTopic), **type);
    if (!w) return failed(fmt::format("{} (is hubsim running?)", w.error().message));
    return write_once(**w, **type, *document);
  }

  StepResult sim_input(const Step& step) {
    auto type = known_type("hub_msgs/msg/SimInput");
    if (!type) return failed(type.error().message);
    auto document = build(
        **type,
        {{"hub", step.target.hub}, {"signal", step.signal}, {"active", step.active ? "true" : "false"}});
    if (!document) return failed(document.error().message);
    return to_hub(std::string(kSimInputTopic), step.target.hub, **type, *document);
  }

  StepResult fault(const Step& step) {
    auto type = known_type("hub_msgs/msg/SimFault");
    if (!type) return failed(type.error().message);
    auto document = build(**type, {{"hub", step.target.hub},
                                   {"device", step.device},
                                   {"fault", step.fault},
                                   {"value", std::to_string(step.value)}});
    if (!document) return failed(document.error().message);
    return to_hub(std::string(kSimFaultTopic), step.target.hub, **type, *document);
  }

  // Once, to every hub's sim bridge, after the one addressed is matched.
  StepResult to_hub(const std::string& topic, const std::string& hub, const msgs::TypeInfo& type,
                    const nlohmann::ordered_json& document) {
    auto readers = readers_including(topic, hub);
    if (!readers) return failed(readers.error().message);
    auto w = writer(topic, type, *readers);
    if (!w) return failed(w.error().message);
    return write_once(**w, type, document);
  }

  static StepResult write_once(WriterEntry& entry, const msgs::TypeInfo& type,
                               const nlohmann::ordered_json& document) {
    dds::UntypedSample sample(*type.descriptor);
    if (auto ok = msgs::from_json(type, document, sample.data()); !ok) return failed(ok.error().message);
    if (auto written = entry.writer->write(sample.data()); !written.is_ok()) {
      return failed(
          fmt::format("writing {} failed: {}", entry.writer->topic_name(), to_string(written.code())));
    }
    return {};
  }

  const dds::Participant& participant_;
  const Scenario& scenario_;
  PlayOptions options_;
  std::FILE* out_;
  Duration period_;
  SteadyClock::time_point next_send_{};
  std::map<std::string, NodeEndpoints> located_;
  std::map<std::string, std::unique_ptr<StateChannel>> states_;
  std::map<std::string, std::unique_ptr<WriterEntry>> writers_;
  std::map<std::string, Plan> plans_;
};

ScenarioRunner::ScenarioRunner(const dds::Participant& participant, const Scenario& scenario,
                               PlayOptions options, std::FILE* out)
    : impl_(std::make_unique<Impl>(participant, scenario, options, out)) {}

ScenarioRunner::~ScenarioRunner() = default;

PlayOutcome ScenarioRunner::run() {
  return impl_->run();
}

}  // namespace hubrt::hubctl
