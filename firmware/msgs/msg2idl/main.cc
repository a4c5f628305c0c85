// hubrt_msg2idl: writes one IDL file from .msg files at build time (hubrt_add_messages(),
// firmware/msgs/cmake/HubrtMessages.cmake). A host program, also when cross-compiling.
//
//   hubrt_msg2idl --stem dock --out <dir>/dock.idl --msg hub_msgs=<path>/DockState.msg ...
//                 [--known hub_msgs/StateHeader=hub_msgs_common ...]
//
// The file is written only when its text changes, so that a comment edited in a .msg compiles
// nothing again. Exit 0 on success, 1 with a located message on stderr.
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "hubrt/msgs/msg_to_idl.h"
#include "hubrt/msgs/ros_msg.h"

namespace {

hubrt::Expected<std::string> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in.is_open()) return hubrt::make_error(hubrt::ErrorCode::kIo, fmt::format("{}: cannot open", path));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// "pkg=path/Type.msg" -> the parsed message.
hubrt::Expected<hubrt::msgs::ros::MsgSpec> load(const std::string& entry) {
  const std::size_t eq = entry.find('=');
  if (eq == std::string::npos) {
    return hubrt::make_error(hubrt::ErrorCode::kInvalidArgument,
                             fmt::format("--msg {}: expected <package>=<file.msg>", entry));
  }
  const std::string path = entry.substr(eq + 1);
  auto text = read_file(path);
  if (!text) return std::move(text).error();
  const std::size_t slash = path.find_last_of('/');
  std::string name = path.substr(slash == std::string::npos ? 0 : slash + 1);
  if (!name.ends_with(".msg")) {
    return hubrt::make_error(hubrt::ErrorCode::kInvalidArgument, fmt::format("{}: not a .msg file", path));
  }
  name.resize(name.size() - 4);
  return hubrt::msgs::ros::parse_msg(*text, entry.substr(0, eq), name, path);
}

}  // namespace

int main(int argc, char** argv) {
  std::string stem;
  std::string out;
  std::vector<std::string> msgs;
  std::vector<std::string> known;
  CLI::App app("hubrt_msg2idl: the DDS IDL of ROS 2 .msg files (hubrt/msgs/msg_to_idl.h)");
  app.add_option("--stem", stem, "Name of the IDL file, without .idl")->required();
  app.add_option("--out", out, "The IDL file to write")->required();
  app.add_option("--msg", msgs, "<package>=<file.msg>, one per message of the file")->required();
  app.add_option("--known", known, "<package>/<Type>=<stem>: a type defined by another IDL file");
  CLI11_PARSE(app, argc, argv);

  hubrt::msgs::IdlFileSpec file{stem, {}, {}};
  for (const std::string& entry : msgs) {
    auto spec = load(entry);
    if (!spec) {
      std::fprintf(stderr, "hubrt_msg2idl: %s\n", spec.error().message.c_str());
      return 1;
    }
    file.messages.push_back(std::move(*spec));
  }
  for (const std::string& entry : known) {
    const std::size_t eq = entry.find('=');
    if (eq == std::string::npos) {
      std::fprintf(stderr, "hubrt_msg2idl: --known %s: expected <package>/<Type>=<stem>\n", entry.c_str());
      return 1;
    }
    file.known[entry.substr(0, eq)] = entry.substr(eq + 1);
  }
  auto idl = hubrt::msgs::idl_from_msgs(file);
  if (!idl) {
    std::fprintf(stderr, "hubrt_msg2idl: %s\n", idl.error().message.c_str());
    return 1;
  }
  if (auto old = read_file(out); old && *old == *idl) return 0;
  std::ofstream write(out, std::ios::binary | std::ios::trunc);
  write << *idl;
  write.close();
  if (!write) {
    std::fprintf(stderr, "hubrt_msg2idl: %s: cannot write\n", out.c_str());
    return 1;
  }
  return 0;
}
