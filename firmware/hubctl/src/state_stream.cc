#include "state_stream.h"

#include <array>
#include <chrono>
#include <cmath>
#include <thread>

#include <fmt/format.h>

#include "hubrt/msgs/json.h"

namespace hubrt::hubctl {

double steady_seconds() noexcept {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double wall_seconds() noexcept {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

Observation observe(nlohmann::ordered_json state_json, double arrival_s) {
  Observation o;
  o.arrival_s = arrival_s;
  o.state = std::move(state_json);
  const auto& state = o.state;
  if (const auto header = state.find("header"); header != state.end() && header->is_object()) {
    o.seq = header->value("seq", std::uint64_t{0});
    if (const auto stamp = header->find("stamp"); stamp != header->end() && stamp->is_object()) {
      o.stamp_s = static_cast<double>(stamp->value("sec", std::int64_t{0})) +
                  static_cast<double>(stamp->value("nanosec", std::int64_t{0})) * 1e-9;
    }
  }
  o.fresh = state.value("fresh_msg", false);
  const auto t_plus = state.find("t_plus");
  o.t_plus = t_plus != state.end() && t_plus->is_number() ? t_plus->get<double>() : std::nan("");
  o.got_reset = state.value("got_reset", false);
  if (const auto echo = state.find("echo"); echo != state.end()) o.echo = *echo;
  if (const auto errors = state.find("error_list"); errors != state.end() && errors->is_array()) {
    for (const auto& e : *errors) {
      if (e.is_string()) o.errors.push_back(e.get<std::string>());
    }
  }
  return o;
}

Expected<StateStream> StateStream::open(const dds::Participant& participant, const std::string& ros_topic,
                                        const msgs::TypeInfo& type) {
  if (type.descriptor == nullptr) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{} has no topic descriptor", type.dds_name));
  }
  auto topic = dds::UntypedTopic::create(participant, *type.descriptor, ros_topic);
  if (!topic) return std::move(topic).error();
  auto reader = dds::UntypedReader::create(participant, *topic);
  if (!reader) return std::move(reader).error();
  auto condition = dds::ReadCondition::create(*reader);
  if (!condition) return std::move(condition).error();
  auto waitset = dds::WaitSet::create(participant);
  if (!waitset) return std::move(waitset).error();
  if (auto attached = waitset->attach(*condition, 1); !attached) return std::move(attached).error();
  return StateStream(type, std::move(*topic), std::move(*reader), std::move(*condition), std::move(*waitset));
}

Expected<double> StateStream::wait_matched(double timeout_s) {
  // Polled: Cyclone offers a status condition for it, but a few milliseconds of polling only
  // blur a figure reported as "since discovered" anyway.
  const double deadline = steady_seconds() + timeout_s;
  for (;;) {
    const Result<std::uint32_t> matched = reader_.matched_writers();
    if (matched.is_ok() && matched.value() > 0) return steady_seconds();
    if (steady_seconds() >= deadline) {
      return make_error(ErrorCode::kTimeout, fmt::format("no hub publishes {} (waited {:.1f} s)",
                                                         reader_.topic_name(), timeout_s));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

Result<std::size_t> StateStream::pump(double deadline_s) noexcept {
  std::array<dds::WaitSet::Token, 2> fired{};
  const double wait_s = std::max(0.0, deadline_s - steady_seconds());
  const Result<std::size_t> woke =
      waitset_.wait(fired, std::chrono::nanoseconds(static_cast<std::int64_t>(wait_s * 1e9)));
  if (!woke.is_ok()) return woke.status();
  // One arrival time per wake-up: samples that queued up meanwhile share it.
  const double arrival = steady_seconds();
  std::size_t appended = 0;
  for (;;) {
    const Result<bool> taken = reader_.take_next(sample_.data());
    if (!taken.is_ok()) return taken.status();
    if (!taken.value()) break;
    // A State that cannot be read is reported by the decoder and skipped (it shows as a seq gap).
    auto state = decoder_.decode(*type_, sample_.data());
    if (!state) continue;
    try {
      log_.push_back(observe(std::move(*state), arrival));
    } catch (const std::exception&) {
      return Status(ErrorCode::kInternal);  // out of memory: the tool cannot go on
    }
    if (!first_arrival_s_) first_arrival_s_ = arrival;
    ++appended;
  }
  return appended;
}

Result<std::size_t> StateStream::restart() noexcept {
  const Result<std::size_t> drained = pump(0.0);
  log_.clear();
  return drained;
}

}  // namespace hubrt::hubctl
