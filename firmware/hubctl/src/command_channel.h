// Commanding a hub the way the planner does: commands built once from a profile's field values,
// written on the node type's (or hub's) command topic.
#pragma once

#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "hubrt/base/status.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/qos.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/type_info.h"

#include "command_qos.h"
#include "conformance_profile.h"

namespace hubrt::hubctl {

// Adds --lifespan-ms (default kDefaultCommandLifespanMs) to a command that writes commands.
void add_lifespan_option(CLI::App& cmd, std::uint32_t& lifespan_ms);

struct PreparedCommand {
  std::string label;  // "probe 1", "reset", for messages
  dds::UntypedSample sample;
  nlohmann::ordered_json json;  // what the hub must echo, field by field
};

// A command of `type` with target_type/target_name set and then `fields` applied (set_field
// syntax); strings left unset go out as "". Errors: a field the type refuses, located at its line
// in the profile.
Expected<PreparedCommand> prepare_command(const msgs::TypeInfo& type, const std::string& target_type,
                                          const std::string& target_name, const FieldAssignments& fields,
                                          std::string label);

// Move-only. Thread-safety: one thread at a time.
class CommandChannel {
 public:
  // Errors: the DDS entity that could not be created.
  static Expected<CommandChannel> open(const dds::Participant& participant, const std::string& ros_topic,
                                       const msgs::TypeInfo& type);
  // Waits until the hub's command reader is matched. Errors: kTimeout naming the topic.
  Expected<void> wait_matched(double timeout_s) const;
  // Errors: Cyclone's code.
  Status send(const PreparedCommand& command) noexcept { return writer_.write(command.sample.data()); }

 private:
  CommandChannel(dds::UntypedTopic topic, dds::UntypedWriter writer)
      : topic_(std::move(topic)), writer_(std::move(writer)) {}
  dds::UntypedTopic topic_;
  dds::UntypedWriter writer_;
};

}  // namespace hubrt::hubctl
