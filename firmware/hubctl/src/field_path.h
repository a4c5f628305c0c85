// Reading one scalar field of a sample by its dotted path, for tools that follow a field (the
// State header's sequence number, fresh_msg) without converting the whole sample.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "hubrt/msgs/type_info.h"

namespace hubrt::hubctl {

struct FieldLocation {
  std::size_t offset = 0;
  msgs::FieldKind kind = msgs::FieldKind::kBool;
};

// Where "header.seq" lives in `type` (structs only, no containers); nothing if absent.
std::optional<FieldLocation> locate(const msgs::TypeInfo& type, std::string_view path);

// The value as a double (bool as 0/1); nothing for strings, structs and containers.
std::optional<double> read_number(const void* sample, const FieldLocation& where);

}  // namespace hubrt::hubctl
