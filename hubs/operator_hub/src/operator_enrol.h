// operator-enrol's commands (operator_enrol.cc): `new <file>` and `add <file> <name>`, the
// arguments after the program name. Returns the exit status: 0 done, 1 refused, 2 usage.
#pragma once

#include <string>
#include <vector>

namespace hubrt::operator_hub {
int run_operator_enrol(const std::vector<std::string>& args);
}  // namespace hubrt::operator_hub
