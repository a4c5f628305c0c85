// operator-enrol: enrols operators' badges on the operator hub's allow-list as salted hashes
// (hubs/operator_hub/README.md, "The allow-list and enrolling a badge").
#include <string>
#include <vector>

#include "operator_enrol.h"

int main(int argc, char** argv) {
  return hubrt::operator_hub::run_operator_enrol(std::vector<std::string>(argv + 1, argv + argc));
}
