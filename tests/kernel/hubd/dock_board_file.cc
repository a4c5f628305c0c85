#include "dock_board_file.h"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <fstream>
#include <utility>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

namespace hubrt::kernel_test {
namespace {

std::string board_yaml(const std::string& board_name, const GpioSimChip& chip, ChipReference how) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "board" << YAML::Value << board_name;
  out << YAML::Key << "description" << YAML::Value
      << fmt::format("Dock ECU on gpio-sim chip {} ({}), made by the kernel test tier", chip.label,
                     chip.name);
  out << YAML::Key << "arch" << YAML::Value << "x86_64";
  out << YAML::Key << "hub" << YAML::Value << "dock_ecu";
  out << YAML::Key << "gpio" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "chips" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "sim" << YAML::Value << YAML::Flow << YAML::BeginMap;
  if (how == ChipReference::kPath) {
    out << YAML::Key << "path" << YAML::Value << chip.dev_path;
  } else {
    out << YAML::Key << "label" << YAML::Value << chip.label;
  }
  out << YAML::EndMap << YAML::EndMap;
  out << YAML::Key << "inputs" << YAML::Value << YAML::BeginMap;
  for (const DockSlotWiring& slot : kDockSlots) {
    out << YAML::Key << slot.signal << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "chip" << YAML::Value << "sim";
    out << YAML::Key << "line" << YAML::Value << slot.offset;
    out << YAML::Key << "polarity" << YAML::Value << "active_high";
    out << YAML::Key << "bias" << YAML::Value << "pull_down";
    out << YAML::Key << "debounce_ms" << YAML::Value << kDockDebounceMs;
    out << YAML::EndMap;
  }
  out << YAML::EndMap << YAML::EndMap << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace

Expected<DockBoardFile> DockBoardFile::write(const GpioSimChip& chip, ChipReference how,
                                             const std::string& directory) {
  for (const DockSlotWiring& slot : kDockSlots) {
    if (slot.offset >= chip.num_lines) {
      return make_error(ErrorCode::kOutOfRange,
                        fmt::format("gpio-sim chip {} has {} lines; the dock board wants line {} for {}",
                                    chip.label, chip.num_lines, slot.offset, slot.signal));
    }
  }
  // Unique per process and per call: tests of one program may each write one.
  static std::atomic<unsigned> counter{0};
  const std::string name = fmt::format("kernel-dock-{}-{}", ::getpid(), counter++);
  const std::string path = fmt::format("{}/{}.yaml", directory, name);
  std::string text = board_yaml(name, chip, how);
  std::ofstream file(path, std::ios::trunc);
  file << text;
  file.close();
  if (!file) return make_error(ErrorCode::kIo, fmt::format("cannot write the board file {}", path));
  return DockBoardFile(path, std::move(text));
}

DockBoardFile::DockBoardFile(DockBoardFile&& other) noexcept
    : path_(std::exchange(other.path_, {})), text_(std::move(other.text_)) {}

DockBoardFile& DockBoardFile::operator=(DockBoardFile&& other) noexcept {
  if (this != &other) {
    DockBoardFile old(std::move(*this));
    path_ = std::exchange(other.path_, {});
    text_ = std::move(other.text_);
  }
  return *this;
}

DockBoardFile::~DockBoardFile() {
  if (!path_.empty()) std::remove(path_.c_str());
}

}  // namespace hubrt::kernel_test
