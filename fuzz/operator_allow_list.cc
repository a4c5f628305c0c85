// The operator hub's allow-list file (hubs/operator_hub/src/allow_list.h) as hubd reads it at
// start and `hubd --check` checks it: any text through AllowList::parse, and a hash looked up in
// what it accepted.
#include <cstddef>
#include <cstdint>
#include <string>

#include "allow_list.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  auto list = hubrt::operator_hub::AllowList::parse(text, "fuzz.list");
  if (list) {
    hubrt::operator_hub::BadgeDigest digest{};
    if (size >= digest.size()) {
      for (std::size_t i = 0; i < digest.size(); ++i) digest[i] = data[i];
    }
    (void)list->find(digest);
    for (const auto& entry : list->operators()) {
      if (!hubrt::operator_hub::name_problem(entry.name).empty()) __builtin_trap();  // accepted a bad name
    }
  }
  return 0;
}
