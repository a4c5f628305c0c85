#include "hubrt/msgs/msg_to_idl.h"

#include <algorithm>
#include <cctype>
#include <set>
#include <string_view>

#include <fmt/format.h>

namespace hubrt::msgs {
namespace {

using ros::Container;
using ros::MsgConstant;
using ros::MsgField;
using ros::MsgSpec;

// rosidl_adapter's MSG_TYPE_TO_IDL.
std::string_view idl_primitive(std::string_view msg_type) {
  if (msg_type == "bool") return "boolean";
  if (msg_type == "byte") return "octet";
  if (msg_type == "char") return "uint8";
  if (msg_type == "float32") return "float";
  if (msg_type == "float64") return "double";
  return msg_type;  // int8..uint64, string
}

bool is_message(const std::string& element_type) {
  return element_type.find('/') != std::string::npos;
}

// "pkg/Type" -> "pkg::msg::dds_::Type_" (rosidl_generator_dds_idl's idl_typename).
std::string dds_name(std::string_view element_type) {
  const std::size_t slash = element_type.find('/');
  return fmt::format("{}::msg::dds_::{}_", element_type.substr(0, slash), element_type.substr(slash + 1));
}

Error located(const MsgSpec& msg, int line, std::string_view what) {
  return make_error(ErrorCode::kInvalidArgument, fmt::format("{}:{}: {}", msg.file, line, what));
}

std::string element_idl(const MsgField& field) {
  if (is_message(field.element_type)) return dds_name(field.element_type);
  std::string type(idl_primitive(field.element_type));
  if (field.string_bound != 0) type += fmt::format("<{}>", field.string_bound);
  return type;
}

std::string member_idl(const MsgField& field) {
  const std::string element = element_idl(field);
  switch (field.container) {
    case Container::kNone:
      break;
    case Container::kSequence:
      return fmt::format("sequence<{}> {};", element, field.name);
    case Container::kBoundedSequence:
      return fmt::format("sequence<{}, {}> {};", element, field.bound, field.name);
    case Container::kArray:
      return fmt::format("{} {}[{}];", element, field.name, field.bound);
  }
  return fmt::format("{} {};", element, field.name);
}

Expected<std::string> constant_idl(const MsgSpec& msg, const MsgConstant& constant) {
  const std::string_view type = idl_primitive(constant.type);
  if (constant.type == "bool") {
    return fmt::format("const boolean {} = {};", constant.name, constant.value == "true" ? "TRUE" : "FALSE");
  }
  if (constant.type == "string") {
    const bool plain = std::all_of(constant.value.begin(), constant.value.end(),
                                   [](char c) { return c >= 0x20 && c < 0x7f && c != '"' && c != '\\'; });
    if (!plain) {
      return located(
          msg, constant.line,
          fmt::format("constant '{}': a string constant may hold only printable ASCII without '\"' "
                      "and '\\' (idlc 0.10 writes it into the C header unescaped)",
                      constant.name));
    }
    return fmt::format("const string {} = \"{}\";", constant.name, constant.value);
  }
  return fmt::format("const {} {} = {};", type, constant.name, constant.value);
}

// What the generated C types cannot carry (see the header).
Expected<void> check_supported(const MsgSpec& msg) {
  for (const MsgField& field : msg.fields) {
    if (!field.default_value.empty()) {
      return located(msg, field.line,
                     fmt::format("field '{}' has a default value ({}): not supported, idlc's C types have no "
                                 "defaults (a hub would start from zeros where a ROS 2 node starts from the "
                                 "default)",
                                 field.name, field.default_value));
    }
    if (field.element_type == "wstring") {
      return located(msg, field.line,
                     fmt::format("field '{}': wstring is not supported (the reflection tables have no wide "
                                 "strings)",
                                 field.name));
    }
  }
  for (const MsgConstant& constant : msg.constants) {
    if (constant.type == "wstring") {
      return located(msg, constant.line,
                     fmt::format("constant '{}': wstring is not supported", constant.name));
    }
  }
  return {};
}

class IdlWriter {
 public:
  explicit IdlWriter(const IdlFileSpec& file) : file_(file) {}

  Expected<std::string> write() {
    for (const MsgSpec& msg : file_.messages) {
      if (auto ok = check_supported(msg); !ok) return std::move(ok).error();
      if (auto ok = resolve_uses(msg); !ok) return std::move(ok).error();
    }
    for (const MsgSpec& msg : file_.messages) {
      if (auto ok = place(msg, {}); !ok) return std::move(ok).error();
    }
    std::string body;
    std::string open_package;
    for (const MsgSpec* msg : ordered_) {
      if (msg->package != open_package) {
        if (!open_package.empty()) body += "    };\n  };\n};\n\n";
        body += fmt::format("module {} {{\n  module msg {{\n    module dds_ {{\n", msg->package);
        open_package = msg->package;
      }
      auto text = struct_idl(*msg);
      if (!text) return std::move(text).error();
      body += *text;
    }
    if (!open_package.empty()) body += "    };\n  };\n};\n";
    return header() + body + "\n#endif\n";
  }

 private:
  // Every nested type is in this file or in a known one; the known ones become includes.
  Expected<void> resolve_uses(const MsgSpec& msg) {
    for (const MsgField& field : msg.fields) {
      if (!is_message(field.element_type) || find(field.element_type) != nullptr) continue;
      const auto known = file_.known.find(field.element_type);
      if (known == file_.known.end()) {
        return located(
            msg, field.line,
            fmt::format("field '{}': no .msg of this message target or of its DEPENDS defines '{}'",
                        field.name, field.element_type));
      }
      if (known->second != file_.stem) includes_.insert(known->second);
    }
    return {};
  }

  [[nodiscard]] const MsgSpec* find(std::string_view element_type) const {
    for (const MsgSpec& msg : file_.messages) {
      if (fmt::format("{}/{}", msg.package, msg.name) == element_type) return &msg;
    }
    return nullptr;
  }

  // Depth first: what `msg` uses from this file comes before it (IDL declares before use).
  Expected<void> place(const MsgSpec& msg, std::vector<const MsgSpec*> path) {
    if (std::find(ordered_.begin(), ordered_.end(), &msg) != ordered_.end()) return {};
    if (std::find(path.begin(), path.end(), &msg) != path.end()) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: {}/{} contains itself through its fields: a message cannot hold "
                                    "itself",
                                    msg.file, msg.package, msg.name));
    }
    path.push_back(&msg);
    for (const MsgField& field : msg.fields) {
      if (const MsgSpec* used = find(field.element_type); used != nullptr) {
        if (auto ok = place(*used, path); !ok) return ok;
      }
    }
    ordered_.push_back(&msg);
    return {};
  }

  [[nodiscard]] Expected<std::string> struct_idl(const MsgSpec& msg) const {
    std::string out;
    if (!msg.constants.empty()) {
      out += fmt::format("      module {}_Constants {{\n", msg.name);
      for (const MsgConstant& constant : msg.constants) {
        auto line = constant_idl(msg, constant);
        if (!line) return std::move(line).error();
        out += fmt::format("        {}\n", *line);
      }
      out += "      };\n";
    }
    out += fmt::format("      @final\n      struct {}_ {{\n", msg.name);
    for (const MsgField& field : msg.fields) out += fmt::format("        {}\n", member_idl(field));
    if (msg.fields.empty()) out += "        uint8 structure_needs_at_least_one_member;\n";
    out += "      };\n";
    return out;
  }

  [[nodiscard]] std::string header() const {
    std::string sources;
    for (const MsgSpec& msg : file_.messages) {
      sources += fmt::format("//   {}/msg/{}.msg\n", msg.package, msg.name);
    }
    std::string guard = "HUBRT_" + file_.stem + "_IDL";
    for (char& c : guard)
      c = std::isalnum(static_cast<unsigned char>(c)) != 0 ? static_cast<char>(std::toupper(c)) : '_';
    std::string includes;
    for (const std::string& stem : includes_) includes += fmt::format("#include \"{}.idl\"\n", stem);
    return fmt::format(
        "// Generated by hubrt_msg2idl from these .msg files (the mapping: hubrt/msgs/msg_to_idl.h). "
        "Do not edit.\n{}#ifndef {}\n#define {}\n\n{}{}",
        sources, guard, guard, includes, includes.empty() ? "" : "\n");
  }

  const IdlFileSpec& file_;
  std::set<std::string> includes_;  // sorted, as rosidl_adapter sorts them
  std::vector<const MsgSpec*> ordered_;
};

}  // namespace

Expected<std::string> idl_from_msgs(const IdlFileSpec& file) {
  return IdlWriter(file).write();
}

}  // namespace hubrt::msgs
