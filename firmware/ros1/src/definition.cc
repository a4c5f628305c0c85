// md5sums, full definitions and comparisons of ROS 1 messages (genmsg's rules, see the header).
#include "hubrt/ros1/definition.h"

#include <algorithm>
#include <map>
#include <vector>

#include <fmt/format.h>
#include <openssl/evp.h>

namespace hubrt::ros1 {
namespace {

Error missing(std::string_view name) {
  return make_error(ErrorCode::kNotFound, fmt::format("no definition of message type {}", name));
}

std::string md5_hex(std::string_view text) {
  // OpenSSL's one-shot digest (EVP_Digest, openssl/evp.h; EVP_md5 is in the default provider).
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  if (EVP_Digest(text.data(), text.size(), digest, &size, EVP_md5(), nullptr) != 1) return {};
  std::string hex;
  for (unsigned int i = 0; i < size; ++i) hex += fmt::format("{:02x}", digest[i]);
  return hex;
}

// Dependencies of `name`, depth first, each once (genmsg get_all_depends + _unique_deps: the first
// occurrences of a full depth-first walk are those of a walk that skips a type seen before). The
// skip also ends the walk of a definition that contains itself (a ROS 1 peer's: found by fuzzing).
Expected<void> collect_depends(const Messages& messages, std::string_view name,
                               std::vector<std::string>& out) {
  const auto it = messages.find(name);
  if (it == messages.end()) return missing(name);
  for (const Field& f : it->second.fields) {
    if (f.builtin() || std::find(out.begin(), out.end(), f.type) != out.end()) continue;
    out.push_back(f.type);
    if (auto ok = collect_depends(messages, f.type, out); !ok) return ok;
  }
  return {};
}

std::string describe_field(const Field& f) {
  return fmt::format("'{}'", f.text());
}

std::string difference_in(const Messages& expected, const Messages& announced, std::string_view name,
                          const std::string& path) {
  const auto want = expected.find(name);
  if (want == expected.end()) return fmt::format("{}: the bridge has no definition of {}", path, name);
  const auto got = announced.find(name);
  if (got == announced.end()) return fmt::format("{}: the ROS 1 definition does not include {}", path, name);
  const Message& w = want->second;
  const Message& g = got->second;
  const std::size_t n = std::max(w.fields.size(), g.fields.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (i >= g.fields.size()) {
      return fmt::format("{}.{}: missing from the ROS 1 definition (hub_msgs has {})", path, w.fields[i].name,
                         describe_field(w.fields[i]));
    }
    if (i >= w.fields.size()) {
      return fmt::format("{}.{}: the ROS 1 definition has extra field {} that hub_msgs does not", path,
                         g.fields[i].name, describe_field(g.fields[i]));
    }
    const Field& wf = w.fields[i];
    const Field& gf = g.fields[i];
    if (wf.name != gf.name || wf.type != gf.type || wf.array != gf.array) {
      return fmt::format("{}.{}: the ROS 1 definition has {} where hub_msgs has {}", path, wf.name,
                         describe_field(gf), describe_field(wf));
    }
    if (!wf.builtin()) {
      std::string nested = difference_in(expected, announced, wf.type, fmt::format("{}.{}", path, wf.name));
      if (!nested.empty()) return nested;
    }
  }
  const std::size_t nc = std::max(w.constants.size(), g.constants.size());
  for (std::size_t i = 0; i < nc; ++i) {
    const Constant* wc = i < w.constants.size() ? &w.constants[i] : nullptr;
    const Constant* gc = i < g.constants.size() ? &g.constants[i] : nullptr;
    if (wc == nullptr || gc == nullptr || wc->type != gc->type || wc->name != gc->name ||
        wc->value != gc->value) {
      return fmt::format("{}: constant {} differs (the ROS 1 definition: '{}', hub_msgs: '{}')", path,
                         wc != nullptr ? wc->name : gc->name,
                         gc != nullptr ? fmt::format("{} {}={}", gc->type, gc->name, gc->value) : "none",
                         wc != nullptr ? fmt::format("{} {}={}", wc->type, wc->name, wc->value) : "none");
    }
  }
  return {};
}

// The ROS 1 type a reflected field's element has: "int32", "string", "time", "hub_msgs/DockSlot".
std::string ros1_type_of(msgs::FieldKind kind, const msgs::FieldInfo& field) {
  using msgs::FieldKind;
  switch (kind) {
    case FieldKind::kBool:
      return "bool";
    case FieldKind::kOctet:
      return "byte";
    case FieldKind::kString:
      return "string";
    case FieldKind::kStruct:
      return ros1_name_of(*field.nested);
    default:
      return std::string(msgs::to_string(kind));
  }
}

bool same_scalar(std::string_view ros1, std::string_view reflected) {
  // ROS 1 `char` is uint8 and `byte` int8 on the wire (genmsg); both are one byte like the IDL's.
  if (ros1 == reflected) return true;
  if (ros1 == "char") return reflected == "uint8";
  if (ros1 == "byte") return reflected == "int8" || reflected == "byte";
  return false;
}

Expected<void> check_struct(const Messages& messages, std::string_view name, const msgs::TypeInfo& type,
                            const std::string& path) {
  const auto it = messages.find(name);
  if (it == messages.end()) return missing(name);
  const auto& fields = it->second.fields;
  if (fields.size() != type.fields.size()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: the ROS 1 message has {} fields, the IDL type {} has {}", path,
                                  fields.size(), type.dds_name, type.fields.size()));
  }
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const Field& f = fields[i];
    const msgs::FieldInfo& r = type.fields[i];
    const std::string where = fmt::format("{}.{}", path, f.name);
    const bool container = r.kind == msgs::FieldKind::kSequence || r.kind == msgs::FieldKind::kArray;
    const msgs::FieldKind kind = container ? r.element_kind : r.kind;
    const std::string want_array = r.kind == msgs::FieldKind::kSequence ? "[]"
                                   : r.kind == msgs::FieldKind::kArray  ? fmt::format("[{}]", r.bound)
                                                                        : "";
    const std::string want_type = ros1_type_of(kind, r);
    if (f.name != r.name || f.array != want_array || !same_scalar(f.type, want_type)) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: ROS 1 '{}' does not match the IDL field '{}' ({}{})", where,
                                    f.text(), r.name, want_type, want_array));
    }
    if (kind == msgs::FieldKind::kStruct && !f.builtin()) {
      if (auto ok = check_struct(messages, f.type, *r.nested, where); !ok) return ok;
    }
  }
  return {};
}

}  // namespace

Expected<std::string> full_definition(const Messages& messages, std::string_view full_name) {
  const auto it = messages.find(full_name);
  if (it == messages.end()) return missing(full_name);
  std::vector<std::string> depends;
  if (auto ok = collect_depends(messages, full_name, depends); !ok) return std::move(ok).error();
  std::string out = msg_text(it->second);
  for (const std::string& d : depends) {
    out += std::string(80, '=') + "\n";
    out += fmt::format("MSG: {}\n", d);
    out += msg_text(messages.find(d)->second);
  }
  if (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
}

namespace {

// genmsg's md5sum of one type, each nested type's sum computed once (`done`). The definitions may
// come from a ROS 1 peer: a type that contains itself, directly or through others (`open`), is an
// error instead of endless recursion, and a wide tree of shared types costs one sum per type.
Expected<std::string> md5sum_of(const Messages& messages, std::string_view full_name,
                                std::map<std::string, std::string, std::less<>>& done,
                                std::vector<std::string_view>& open) {
  if (const auto known = done.find(full_name); known != done.end()) return known->second;
  const auto it = messages.find(full_name);
  if (it == messages.end()) return missing(full_name);
  if (std::find(open.begin(), open.end(), full_name) != open.end()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: the message definition contains itself", full_name));
  }
  open.push_back(full_name);
  std::string text;
  for (const Constant& c : it->second.constants) text += fmt::format("{} {}={}\n", c.type, c.name, c.value);
  for (const Field& f : it->second.fields) {
    if (f.builtin()) {
      text += f.text() + "\n";
    } else {
      auto nested = md5sum_of(messages, f.type, done, open);
      if (!nested) return nested;
      text += fmt::format("{} {}\n", *nested, f.name);
    }
  }
  open.pop_back();
  while (!text.empty() && text.back() == '\n') text.pop_back();
  std::string sum = md5_hex(text);
  done.emplace(std::string(full_name), sum);
  return sum;
}

}  // namespace

Expected<std::string> md5sum(const Messages& messages, std::string_view full_name) {
  std::map<std::string, std::string, std::less<>> done;
  std::vector<std::string_view> open;
  return md5sum_of(messages, full_name, done, open);
}

std::string first_difference(const Messages& expected, const Messages& announced,
                             std::string_view full_name) {
  return difference_in(expected, announced, full_name, std::string(full_name));
}

Expected<void> check_matches(const Messages& messages, std::string_view full_name,
                             const msgs::TypeInfo& type) {
  return check_struct(messages, full_name, type, std::string(full_name));
}

}  // namespace hubrt::ros1
