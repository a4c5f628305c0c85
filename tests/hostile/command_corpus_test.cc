// Hostile command text (issue 11): every string field of every Command type of the message
// registry — the real generated types, found, not listed (every Command/State pair the registered
// message targets generate, hubrt/msgs/all_command_state_pairs.h), walked through their reflection
// tables — fed a corpus of byte strings
// that are not acceptable UTF-8. Each must be rejected, the rejection in error_list must show the
// bytes escaped (\xED...), and every string of the State must stay valid UTF-8, so that a ROS 2
// client or a JSON tool can still read it. (Length is not in the corpus: over the IDL bound
// (string<64>) a command is dropped by Cyclone's deserialiser before any intake sees it,
// firmware/msgs/README.md; the corpus fits the bound.)
#include <algorithm>
#include <array>
#include <cstring>
#include <deque>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/base/utf8.h"
#include "hubrt/msgs/all_command_state_pairs.h"
#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/typed.h"
#include "hubrt/runtime/escaped_text.h"
#include "hubrt/runtime/node.h"
#include "hubrt/runtime/reflected_message_ops.h"

#include "dock_reflect.h"
#include "dock_typed.h"

namespace hubrt::runtime {
namespace {

using msgs::FieldInfo;
using msgs::FieldKind;
using msgs::TypeInfo;

struct Bad {
  std::string_view bytes;
  const char* why;
};

// What a hostile or broken peer may put in a string: each class of ill-formed UTF-8 (RFC 3629
// §4), control characters, and a mix with valid text around it.
const std::array kCorpus{
    Bad{"\xed\xa0\x80", "encoded high surrogate U+D800 (issue 11: it used to pass)"},
    Bad{"id\xed\xbf\xbfle", "encoded low surrogate inside text"},
    Bad{"\xed\xa0\xbd\xed\xb8\x80", "CESU-8 surrogate pair"},
    Bad{"\xc0\xaf", "overlong '/'"},
    Bad{"\xe0\x80\xaf", "overlong 3-byte '/'"},
    Bad{"\xf0\x80\x80\xaf", "overlong 4-byte '/'"},
    Bad{"\xf4\x90\x80\x80", "U+110000"},
    Bad{"\xf8\x88\x80\x80\x80", "5-byte form"},
    Bad{"\xff\xfe", "bytes that never occur in UTF-8"},
    Bad{"\x80\x81", "stray continuation bytes"},
    Bad{"abc\xe2\x82", "truncated sequence at the end"},
    Bad{"\xc3(", "lead byte without its continuation"},
    Bad{"line\nbreak", "control character"},
    Bad{"esc\x1b[31m", "terminal escape sequence"},
    Bad{"del\x7f", "DEL"},
};

// A node type that accepts anything valid: the corpus must be stopped by the generic intake.
// C and S are the generated typed classes (a Command View, an owning State).
template <class C, class S>
struct CorpusLogic {
  using Command = C;
  using State = S;
  static constexpr std::string_view kType = "corpus";
  static constexpr std::array<std::string_view, 2> kActions{"probe", "reset"};
  bool validate(const Command& /*command*/, Problem& /*problem*/) const noexcept { return true; }
  void read_inputs(Time /*now*/) noexcept {}
  NodeCondition condition() const noexcept { return NodeCondition::kOk; }
  void update(const Command* /*command*/, Time /*now*/) noexcept {}
  void reset() noexcept {}
  void report(State& /*state*/, ErrorList& /*errors*/, Time /*now*/) noexcept {}
  void enter_safe_state() noexcept {}
};

template <class C>
class OneCommandSource final : public CommandSource<C> {
 public:
  void post(const C& command) { pending_ = &command; }
  Result<ReceivedCommand<C>> next() noexcept override {
    return ReceivedCommand<C>{std::exchange(pending_, nullptr), std::nullopt, std::nullopt};
  }

 private:
  const C* pending_ = nullptr;
};

template <class S>
class NullSink final : public StateSink<S> {
 public:
  Status publish(const S& /*state*/) noexcept override { return Status::ok(); }
};

// One string slot of a command type: its path as the intake names it ("dock.action",
// "tags[0]") and where it is in a sample.
struct StringSlot {
  std::string path;
  std::function<void*(void* sample)> locate;  // the char* or, bounded, the char[N+1]
  std::uint32_t string_bound = 0;

  // Puts `text` in the slot of `sample`; `text` must outlive it when the string is unbounded.
  void put(void* sample, std::string& text) const {
    void* where = locate(sample);
    if (string_bound == 0) {
      *static_cast<char**>(where) = text.data();
    } else {
      const std::size_t n = std::min<std::size_t>(text.size(), string_bound);
      std::memcpy(where, text.data(), n);
      static_cast<char*>(where)[n] = '\0';
    }
  }
};

// Storage for sequence elements the test adds, alive for the whole test.
std::deque<std::vector<std::max_align_t>>& element_storage() {
  static std::deque<std::vector<std::max_align_t>> storage;
  return storage;
}

std::byte* at(void* base, std::size_t offset) {
  return static_cast<std::byte*>(base) + offset;
}

using Locate = std::function<void*(void* sample)>;

void collect(const TypeInfo& type, const std::string& prefix, const Locate& base,
             std::vector<StringSlot>& out);

// Element 0 of an array or a sequence (given one element first), then the element's slots.
void collect_element(const FieldInfo& field, const std::string& path, const Locate& field_at,
                     std::vector<StringSlot>& out) {
  Locate element_at = [field, field_at](void* sample) -> void* {
    void* f = field_at(sample);
    if (field.kind == FieldKind::kArray) return f;
    auto* seq = static_cast<dds_sequence_t*>(f);
    if (seq->_length == 0) {
      auto& storage = element_storage().emplace_back(field.element_size / sizeof(std::max_align_t) + 1);
      seq->_buffer = reinterpret_cast<std::uint8_t*>(storage.data());  // NOLINT: idlc's untyped buffer
      seq->_length = seq->_maximum = 1;
      seq->_release = false;
    }
    return seq->_buffer;
  };
  const std::string element_path = path + "[0]";
  if (field.element_kind == FieldKind::kString) {
    out.push_back({element_path, element_at, field.string_bound});
  } else if (field.element_kind == FieldKind::kStruct) {
    collect(*field.nested, element_path, element_at, out);
  }
}

void collect(const TypeInfo& type, const std::string& prefix, const Locate& base,
             std::vector<StringSlot>& out) {
  for (const FieldInfo& field : type.fields) {
    const std::string path =
        prefix.empty() ? std::string(field.name) : prefix + "." + std::string(field.name);
    Locate field_at = [base, offset = field.offset](void* sample) -> void* {
      return at(base(sample), offset);
    };
    if (field.kind == FieldKind::kString) {
      out.push_back({path, field_at, field.string_bound});
    } else if (field.kind == FieldKind::kStruct) {
      collect(*field.nested, path, field_at, out);
    } else if (field.kind == FieldKind::kArray || field.kind == FieldKind::kSequence) {
      collect_element(field, path, field_at, out);
    }
  }
}

std::vector<StringSlot> string_slots(const TypeInfo& type) {
  std::vector<StringSlot> out;
  collect(
      type, "", [](void* s) { return s; }, out);
  return out;
}

// Every string of a State, however deep, for the UTF-8 check.
void visit_strings(const TypeInfo& type, const void* msg,
                   const std::function<void(std::string_view)>& visit) {
  for (const FieldInfo& field : type.fields) {
    const auto* f = static_cast<const std::byte*>(msg) + field.offset;
    const auto visit_element = [&](const void* e) {
      if (field.element_kind == FieldKind::kString) visit(msgs::string_at(field, e));
      if (field.element_kind == FieldKind::kStruct) visit_strings(*field.nested, e, visit);
    };
    if (field.kind == FieldKind::kSequence) {
      const auto* seq = reinterpret_cast<const dds_sequence_t*>(f);  // NOLINT: idlc layout
      for (std::uint32_t i = 0; i < seq->_length; ++i) visit_element(seq->_buffer + i * field.element_size);
    } else if (field.kind == FieldKind::kArray) {
      for (std::uint32_t i = 0; i < field.bound; ++i) visit_element(f + i * field.element_size);
    } else {
      visit_element(f);
    }
  }
}

std::string escaped(std::string_view bytes) {
  std::array<char, Escaped::kMaxBytes> out{};
  const EscapedUtf8 r = append_escaped_utf8(bytes, out);
  return std::string(out.data(), r.written);
}

std::set<const TypeInfo*>& covered() {
  static std::set<const TypeInfo*> types;
  return types;
}

// Runs the corpus through every string slot of C, in a Node whose State is S.
template <class CommandView, class State>
void run_corpus() {
  using C = typename CommandView::Wire;
  using S = typename State::Wire;
  using Logic = CorpusLogic<CommandView, State>;
  const TypeInfo& command_type = msgs::type_info_of<C>();
  const TypeInfo& state_type = msgs::type_info_of<S>();
  covered().insert(&command_type);
  SCOPED_TRACE(std::string(command_type.ros_name));
  const ReflectedMessageOps ops(command_type);
  OneCommandSource<C> source;
  NullSink<S> sink;
  NodeOptions options;
  options.name = "n1";
  // As routed by the hub layout, so that every field is validated: on a shared node-type topic a
  // command whose target_name is not this node's (bad bytes included) is simply not for it.
  options.addressing = Addressing::kRejectOthers;
  Node<Logic> node(options, Logic{}, source, sink, ops);
  ManualClock clock;

  const std::vector<StringSlot> slots = string_slots(command_type);
  ASSERT_GE(slots.size(), 3U) << "target_type, target_name and action at least";
  std::string target_type = "corpus";
  std::string target_name = "n1";
  std::string action = "probe";
  for (const StringSlot& slot : slots) {
    for (const Bad& bad : kCorpus) {
      SCOPED_TRACE(slot.path + ": " + bad.why);
      // A valid command (every string "", the three routing fields set) with one string bad.
      C command{};
      std::string none;
      for (const StringSlot& s : slots) s.put(&command, none);
      slots[0].put(&command, target_type);
      slots[1].put(&command, target_name);
      slots[2].put(&command, action);
      std::string bytes(bad.bytes);
      slot.put(&command, bytes);
      source.post(command);
      clock.advance(std::chrono::milliseconds(1));
      const std::uint64_t rejected_before = node.rejected();
      EXPECT_FALSE(node.step(clock.now())) << "a bad command never takes effect";
      EXPECT_EQ(node.rejected(), rejected_before + 1);

      const S& state = node.state().wire();
      ASSERT_EQ(node.state().error_list().size(), 1U);
      const std::string error(node.state().error_list()[0]);
      EXPECT_NE(error.find("field '" + slot.path + "'"), std::string::npos) << error;
      EXPECT_NE(error.find(escaped(bad.bytes)), std::string::npos) << error;
      visit_strings(state_type, &state, [&](std::string_view text) {
        EXPECT_TRUE(is_valid_utf8(text)) << "State string: " << escaped(text);
      });
    }
  }
}

// For a command type no hub node takes (one without typed classes, e.g. the simulated station's,
// taken by hubsim's StationBridge): the check every intake applies,
// ReflectedMessageOps::check_fields(), on a sample laid out by its table.
void run_check_fields_corpus(const TypeInfo& command_type) {
  covered().insert(&command_type);
  SCOPED_TRACE(std::string(command_type.ros_name));
  const ReflectedMessageOps ops(command_type);
  const std::vector<StringSlot> slots = string_slots(command_type);
  std::vector<char> empty(1, '\0');
  for (const StringSlot& slot : slots) {
    for (const Bad& bad : kCorpus) {
      SCOPED_TRACE(slot.path + ": " + bad.why);
      std::vector<std::max_align_t> command(command_type.size / sizeof(std::max_align_t) + 1);  // zeroed
      for (const StringSlot& s : slots) {
        std::string none;
        if (s.string_bound == 0) {
          *static_cast<char**>(s.locate(command.data())) = empty.data();
        } else {
          s.put(command.data(), none);
        }
      }
      std::string bytes(bad.bytes);
      slot.put(command.data(), bytes);
      Problem problem;
      EXPECT_FALSE(ops.check_fields(command.data(), kMaxCommandString, problem));
      EXPECT_NE(problem.view().find("field '" + slot.path + "'"), std::string::npos) << problem.view();
      EXPECT_NE(problem.view().find(escaped(bad.bytes)), std::string::npos) << problem.view();
      EXPECT_TRUE(is_valid_utf8(problem.view()));
    }
  }
}

bool is_command(const TypeInfo& type) {
  const auto& f = type.fields;
  return f.size() >= 3 && f[0].name == "target_type" && f[1].name == "target_name" && f[2].name == "action";
}

TEST(CommandCorpus, EveryStringFieldOfEveryCommandTypeRejectsBadTextAndReportsItEscaped) {
  // Through a real Node: every Command type a State echoes, both with typed classes.
  std::size_t through_nodes = 0;
  msgs::typed::for_each_command_state_pair([&]<class CommandView, class State>() {
    run_corpus<CommandView, State>();
    ++through_nodes;
  });
  // Guard against a vacuous pass: the hubs' node types and hub layouts are among them.
  EXPECT_TRUE(covered().contains(&msgs::type_info_of<hub_msgs_msg_dds__DockCommand_>()));
  EXPECT_GE(through_nodes, 14U) << "the station's hubs alone have 14 Command/State pairs";

  // Every other Command type of the registry (target_type, target_name, action first) through
  // the check every intake applies.
  std::size_t commands = 0;
  for (const TypeInfo* type : msgs::all_types().types()) {
    if (!is_command(*type)) continue;
    ++commands;
    if (!covered().contains(type)) run_check_fields_corpus(*type);
  }
  EXPECT_EQ(covered().size(), commands) << "every Command type of the registry, each once";
  EXPECT_TRUE(covered().contains(msgs::all_types().find("hub_msgs/msg/StationCommand")));
}

TEST(CommandCorpus, ValidUnicodeIsAcceptedAndAnUnknownValidActionIsQuotedAsItIs) {
  using Logic = CorpusLogic<hub_msgs::DockCommandView, hub_msgs::DockState>;
  const ReflectedMessageOps ops(msgs::type_info_of<hub_msgs_msg_dds__DockCommand_>());
  OneCommandSource<hub_msgs_msg_dds__DockCommand_> source;
  NullSink<hub_msgs_msg_dds__DockState_> sink;
  NodeOptions options;
  options.name = "n1";
  Node<Logic> node(options, Logic{}, source, sink, ops);
  ManualClock clock;
  // U+D7FF and U+E000 (either side of the surrogates), U+10FFFF: valid, so only unknown.
  std::string action = "\xed\x9f\xbf\xee\x80\x80\xf4\x8f\xbf\xbf";
  hub_msgs_msg_dds__DockCommand_ command{};
  hubrt::msgs::typed::assign(command.target_type, "corpus");
  hubrt::msgs::typed::assign(command.target_name, "n1");
  hubrt::msgs::typed::assign(command.action, action);
  source.post(command);
  EXPECT_FALSE(node.step(clock.now()));
  ASSERT_EQ(node.state().error_list().size(), 1U);
  EXPECT_EQ(std::string(node.state().error_list()[0]),
            "rejected command: unknown action '" + action + "' (expected one of: probe, reset)");
}

}  // namespace
}  // namespace hubrt::runtime
