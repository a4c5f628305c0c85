#include "field_path.h"

#include <cstring>

namespace hubrt::hubctl {
namespace {

template <class T>
double load(const void* p) {
  T v{};
  std::memcpy(&v, p, sizeof v);
  return static_cast<double>(v);
}

}  // namespace

std::optional<FieldLocation> locate(const msgs::TypeInfo& type, std::string_view path) {
  const msgs::TypeInfo* current = &type;
  std::size_t offset = 0;
  while (true) {
    const auto dot = path.find('.');
    const std::string_view name = path.substr(0, dot);
    const msgs::FieldInfo* found = nullptr;
    for (const msgs::FieldInfo& field : current->fields) {
      if (field.name == name) found = &field;
    }
    if (found == nullptr) return std::nullopt;
    offset += found->offset;
    if (dot == std::string_view::npos) return FieldLocation{offset, found->kind};
    if (found->kind != msgs::FieldKind::kStruct) return std::nullopt;
    current = found->nested;
    path.remove_prefix(dot + 1);
  }
}

std::optional<double> read_number(const void* sample, const FieldLocation& where) {
  const void* p = static_cast<const std::byte*>(sample) + where.offset;
  using msgs::FieldKind;
  switch (where.kind) {
    case FieldKind::kBool: {
      bool v = false;
      std::memcpy(&v, p, sizeof v);
      return v ? 1.0 : 0.0;
    }
    case FieldKind::kOctet:
    case FieldKind::kUInt8:
      return load<std::uint8_t>(p);
    case FieldKind::kInt8:
      return load<std::int8_t>(p);
    case FieldKind::kInt16:
      return load<std::int16_t>(p);
    case FieldKind::kUInt16:
      return load<std::uint16_t>(p);
    case FieldKind::kInt32:
      return load<std::int32_t>(p);
    case FieldKind::kUInt32:
      return load<std::uint32_t>(p);
    case FieldKind::kInt64:
      return load<std::int64_t>(p);
    case FieldKind::kUInt64:
      return load<std::uint64_t>(p);
    case FieldKind::kFloat32:
      return load<float>(p);
    case FieldKind::kFloat64:
      return load<double>(p);
    default:
      return std::nullopt;
  }
}

}  // namespace hubrt::hubctl
