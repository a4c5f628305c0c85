#include "hubrt/msgs/drift.h"

#include <map>
#include <set>
#include <string_view>

#include <fmt/format.h>

namespace hubrt::msgs {
namespace {

std::string_view msg_primitive(FieldKind kind) {
  switch (kind) {
    case FieldKind::kOctet:
      return "byte";
    default:
      return to_string(kind);  // bool, int8..uint64, float32, float64, string share names
  }
}

// "pkg/msg/Type" -> "pkg/Type", as .msg files name nested types.
std::string msg_name_of(const TypeInfo& type) {
  if (type.ros_name.empty()) return std::string(type.dds_name);
  const auto first = type.ros_name.find('/');
  const auto last = type.ros_name.rfind('/');
  return fmt::format("{}/{}", type.ros_name.substr(0, first), type.ros_name.substr(last + 1));
}

std::string_view shape_of(const FieldInfo& f) {
  if (f.kind == FieldKind::kArray) return "fixed-size array";
  if (f.kind == FieldKind::kSequence) return f.bound != 0 ? "bounded sequence" : "sequence";
  return "single value";
}

std::string_view shape_of(const ros::MsgField& f) {
  switch (f.container) {
    case ros::Container::kArray:
      return "fixed-size array";
    case ros::Container::kSequence:
      return "sequence";
    case ros::Container::kBoundedSequence:
      return "bounded sequence";
    case ros::Container::kNone:
      break;
  }
  return "single value";
}

// The .msg type as the IDL must spell it: ROS 2 maps char to uint8.
std::string comparable_type(ros::MsgField field) {
  if (field.element_type == "char") field.element_type = "uint8";
  return ros::canonical_type(field);
}

class DriftReport {
 public:
  void add(std::string sentence) { sentences_.push_back(std::move(sentence)); }
  std::vector<std::string> take() { return std::move(sentences_); }

  void compare(const ros::MsgSpec& msg, const TypeInfo& idl) {
    const std::string where =
        fmt::format("{} ({} vs IDL {} in {})", idl.ros_name, msg.file, idl.dds_name, idl.idl_file);
    // rosidl gives a message without fields one placeholder member (rosidl_adapter, struct.idl.em).
    if (msg.fields.empty() && idl.fields.size() == 1 &&
        idl.fields[0].name == "structure_needs_at_least_one_member" &&
        idl.fields[0].kind == FieldKind::kUInt8) {
      return;
    }
    const std::size_t n = std::max(msg.fields.size(), idl.fields.size());
    for (std::size_t i = 0; i < n; ++i) {
      if (i >= msg.fields.size()) {
        const FieldInfo& f = idl.fields[i];
        add(fmt::format("{}: IDL field {} '{}' ({}) is missing from the .msg", where, i + 1, f.name,
                        msg_type_of(f)));
        continue;
      }
      const ros::MsgField& m = msg.fields[i];
      if (i >= idl.fields.size()) {
        add(fmt::format("{}: .msg field {} '{}' ({}, line {}) is not in the IDL", where, i + 1, m.name,
                        ros::canonical_type(m), m.line));
        continue;
      }
      const FieldInfo& f = idl.fields[i];
      if (m.name != f.name) {
        std::string hint;
        for (std::size_t j = 0; j < idl.fields.size(); ++j) {
          if (idl.fields[j].name == m.name)
            hint = fmt::format(" (the IDL has '{}' as field {}: order differs)", m.name, j + 1);
        }
        add(fmt::format("{}: field {} is named '{}' in the .msg (line {}) but '{}' in the IDL{}", where,
                        i + 1, m.name, m.line, f.name, hint));
      }
      const std::string msg_type = comparable_type(m);
      const std::string idl_type = msg_type_of(f);
      if (msg_type != idl_type) {
        std::string hint;
        if (shape_of(m) != shape_of(f)) {
          hint = fmt::format(": a {} in the .msg, a {} in the IDL", shape_of(m), shape_of(f));
        } else if (f.element_kind == FieldKind::kStruct && f.nested != nullptr) {
          hint = fmt::format(" (IDL type {})", f.nested->dds_name);
        }
        add(fmt::format("{}: field {} '{}' (line {}) is {} in the .msg but {} in the IDL{}", where, i + 1,
                        f.name, m.line, ros::canonical_type(m), idl_type, hint));
      }
    }
  }

 private:
  std::vector<std::string> sentences_;
};

}  // namespace

std::string msg_type_of(const FieldInfo& field) {
  std::string element = field.element_kind == FieldKind::kStruct && field.nested != nullptr
                            ? msg_name_of(*field.nested)
                            : std::string(msg_primitive(field.element_kind));
  // ROS 2 writes IDL string<N> as string<=N.
  if (field.element_kind == FieldKind::kString && field.string_bound != 0)
    element += fmt::format("<={}", field.string_bound);
  if (field.kind == FieldKind::kArray) return fmt::format("{}[{}]", element, field.bound);
  if (field.kind == FieldKind::kSequence) {
    return field.bound != 0 ? fmt::format("{}[<={}]", element, field.bound) : element + "[]";
  }
  return element;
}

std::vector<std::string> find_drift(std::span<const ros::MsgSpec> msgs,
                                    std::span<const TypeInfo* const> idl_types) {
  DriftReport report;
  std::set<std::string> packages;
  std::map<std::string, const ros::MsgSpec*> msg_by_name;
  for (const auto& m : msgs) {
    packages.insert(m.package);
    msg_by_name.emplace(m.ros_name(), &m);
  }
  std::map<std::string, const TypeInfo*> idl_by_name;
  for (const TypeInfo* t : idl_types) {
    if (t->ros_name.empty()) {
      report.add(
          fmt::format("IDL type {} (in {}) is not named like a ROS 2 type (<pkg>::msg::dds_::<Type>_), so no "
                      "ROS 2 node can use it",
                      t->dds_name, t->idl_file));
    } else {
      idl_by_name.emplace(std::string(t->ros_name), t);
    }
  }
  for (const auto& [name, t] : idl_by_name) {
    const std::string pkg = name.substr(0, name.find('/'));
    const std::string msg_file = fmt::format("{}/msg/{}.msg", pkg, name.substr(name.rfind('/') + 1));
    if (!packages.contains(pkg)) {
      report.add(fmt::format("{} (IDL {} in {}) has no .msg: there is no ROS 2 package '{}' with a {}", name,
                             t->dds_name, t->idl_file, pkg, msg_file));
    } else if (const auto it = msg_by_name.find(name); it == msg_by_name.end()) {
      report.add(fmt::format("{} is in the IDL ({} in {}) but {} does not exist", name, t->dds_name,
                             t->idl_file, msg_file));
    } else {
      report.compare(*it->second, *t);
    }
  }
  for (const auto& [name, m] : msg_by_name) {
    if (!idl_by_name.contains(name)) {
      report.add(fmt::format(
          "{} defines {}, but no IDL type {}::msg::dds_::{}_ exists (no hubrt_add_messages() target "
          "declares it)",
          m->file, name, m->package, m->name));
    }
  }
  return report.take();
}

}  // namespace hubrt::msgs
