// Command validation of a node type from raw CDR: the bytes are deserialised by Cyclone into the
// node's Command type (cdr_sample.h) and handed to a real runtime::Node<Logic> — the generic
// intake (string and number checks, target, action), the logic's own validate(), the echo copy —
// which then runs a few cycles with and without it. A node is made afresh for every input, so
// every finding reproduces from its input alone.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

#include <spdlog/sinks/null_sink.h>
#include <spdlog/spdlog.h>

#include "hubrt/base/time.h"
#include "hubrt/msgs/type_info.h"
#include "hubrt/msgs/typed.h"
#include "hubrt/runtime/node.h"
#include "hubrt/runtime/ports.h"
#include "hubrt/runtime/reflected_message_ops.h"

#include "cdr_sample.h"

namespace hubrt::fuzz {

// Gives one command per post(), like a reader with one sample waiting.
template <class Command>
class OneShotSource final : public runtime::CommandSource<Command> {
 public:
  void post(const Command* command) noexcept { pending_ = command; }
  // Built in-process: no source timestamp, as old as its arrival.
  Result<runtime::ReceivedCommand<Command>> next() noexcept override {
    return runtime::ReceivedCommand<Command>{std::exchange(pending_, nullptr), std::nullopt, std::nullopt};
  }

 private:
  const Command* pending_ = nullptr;
};

template <class State>
class DiscardingSink final : public runtime::StateSink<State> {
 public:
  Status publish(const State& /*state*/) noexcept override { return Status::ok(); }
};

// A logger that drops everything: a rejected command is logged, and the fuzzer makes millions.
inline std::shared_ptr<spdlog::logger> quiet_logger() {
  static const auto logger =
      std::make_shared<spdlog::logger>("fuzz", std::make_shared<spdlog::sinks::null_sink_mt>());
  return logger;
}

// The MessageOps of a generated type (as hubrt::hub_api::message_ops does for hubs).
template <class T>
const runtime::MessageOps& ops_of() {
  static const runtime::ReflectedMessageOps ops(msgs::type_info_of<T>());
  return ops;
}

// The cycle period the harness steps the node with, and how many cycles follow the command.
inline constexpr Duration kCycle = std::chrono::milliseconds(10);
inline constexpr int kCyclesAfter = 3;

// Decodes `input` as a Command and runs it through a fresh node built by `make_logic()` named
// `node_name`. The command goes in once, then the node cycles kCyclesAfter times without one.
template <runtime::NodeLogic Logic, class MakeLogic>
void run_command(std::span<const std::uint8_t> input, const std::string& node_name, ManualClock& clock,
                 MakeLogic&& make_logic,
                 runtime::Addressing addressing = runtime::Addressing::kIgnoreOthers) {
  using Command = msgs::typed::wire_t<typename Logic::Command>;  // the C structs behind the typed classes
  using State = msgs::typed::wire_t<typename Logic::State>;
  const CdrDecoder& decoder = CdrDecoder::of(msgs::type_info_of<Command>());
  Command command{};
  if (!decoder.decode(input, &command)) return;
  {
    OneShotSource<Command> source;
    DiscardingSink<State> sink;
    runtime::NodeOptions options;
    options.name = node_name;
    options.command_timeout = std::chrono::milliseconds(100);
    options.addressing = addressing;
    options.log = quiet_logger();
    runtime::Node<Logic> node(std::move(options), make_logic(), source, sink, ops_of<Command>());
    source.post(&command);
    for (int cycle = 0; cycle <= kCyclesAfter; ++cycle) {
      clock.advance(kCycle);
      node.step(clock.now());
      node.publish(clock.now()).ignore();
    }
    node.enter_safe_state();
  }
  decoder.free_sample(&command);
}

}  // namespace hubrt::fuzz
