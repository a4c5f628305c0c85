// operator-enrol (its main is firmware/operator_enrol/main.cc): puts operators on the allow-list
// (src/allow_list.h) without the badge ever being stored, shown or passed as an argument (a command line is
// visible to every user in /proc and lands in shell history):
//   operator-enrol new <file>          a new, empty allow-list with a fresh random salt (mode 0640,
//                                      group hubrt where it exists)
//   operator-enrol add <file> <name>   reads the badge from stdin (show it to a keyboard-wedge
//                                      reader, or type it; echo is off on a terminal), appends
//                                      "<hash> <name>"; creates the file first if it is missing
// Exit status: 0 done, 1 refused (name or badge already there, malformed badge, bad file), 2 usage.
#include "operator_enrol.h"

#include <fcntl.h>
#include <grp.h>
#include <termios.h>
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <openssl/rand.h>
#include <sys/stat.h>

#include "hubrt/hal/badge_reader.h"

#include "allow_list.h"

namespace {

using hubrt::operator_hub::AllowList;
using hubrt::operator_hub::BadgeDigest;
using hubrt::operator_hub::BadgeHasher;
using hubrt::operator_hub::BadgeSalt;

int fail(const std::string& message) {
  std::cerr << "operator-enrol: " << message << "\n";
  return 1;
}

bool write_new_file(const std::string& path) {
  BadgeSalt salt{};
  if (RAND_bytes(salt.data(), static_cast<int>(salt.size())) != 1) return false;
  std::array<char, 32> hex{};
  hubrt::operator_hub::to_hex(salt, hex);
  const std::string text = fmt::format(
      "# hubrt operator allow-list (hubs/operator_hub/README.md). Badges are stored as\n"
      "# SHA-256(salt || badge) only; add operators with: operator-enrol add <this file> <name>\n"
      "salt {}\n",
      std::string_view(hex.data(), hex.size()));
  // The hub reads it and nobody else: 0640 whatever the umask, group hubrt where that group
  // exists (the board package makes it; hubd runs as user hubrt), else the creator's group.
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) return false;
  if (const group* hubrt_group = ::getgrnam("hubrt"); hubrt_group != nullptr) {
    if (::fchown(fd, static_cast<uid_t>(-1), hubrt_group->gr_gid) != 0) {
      std::cerr << fmt::format(
          "operator-enrol: warning: cannot give {} to group hubrt (run as root); hubd "
          "may not read it\n",
          path);
    }
  }
  ::fchmod(fd, 0640);
  const bool written = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  return ::close(fd) == 0 && written;
}

// One line from stdin, with echo off when it is a terminal.
std::string read_badge() {
  termios saved{};
  const bool tty = ::isatty(STDIN_FILENO) == 1 && ::tcgetattr(STDIN_FILENO, &saved) == 0;
  if (tty) {
    std::cerr << "Show the badge to the reader (or type its ID) and press Enter: " << std::flush;
    termios quiet = saved;
    quiet.c_lflag &= ~static_cast<tcflag_t>(ECHO);
    ::tcsetattr(STDIN_FILENO, TCSANOW, &quiet);
  }
  std::string line;
  std::getline(std::cin, line);
  if (tty) {
    ::tcsetattr(STDIN_FILENO, TCSANOW, &saved);
    std::cerr << "\n";
  }
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return line;
}

bool valid_badge(const std::string& badge) {
  if (badge.empty() || badge.size() > hubrt::hal::BadgeRead::kMaxLength) return false;
  for (char c : badge) {
    if (c < 0x20 || c > 0x7E) return false;
  }
  return true;
}

int add(const std::string& path, const std::string& name) {
  if (::access(path.c_str(), F_OK) != 0 && !write_new_file(path)) {
    return fail(fmt::format("{}: cannot create the allow-list", path));
  }
  auto list = AllowList::load(path);
  if (!list) return fail(list.error().message);
  if (const auto problem = hubrt::operator_hub::name_problem(name); !problem.empty()) {
    return fail(fmt::format("'{}': {}", name, problem));
  }
  for (const auto& entry : list->operators()) {
    if (entry.name == name)
      return fail(fmt::format("{}:{}: '{}' is already enrolled", path, entry.line, name));
  }
  const std::string badge = read_badge();
  if (!valid_badge(badge)) return fail("not a badge: 1 to 32 printable ASCII characters");
  auto hasher = BadgeHasher::create();
  if (!hasher) return fail(hasher.error().message);
  BadgeDigest digest{};
  if (!hasher->hash(list->salt(), badge, digest)) return fail("libcrypto failed to hash the badge");
  if (const auto* known = list->find(digest); known != nullptr) {
    return fail(
        fmt::format("{}:{}: this badge is already enrolled (as '{}')", path, known->line, known->name));
  }
  auto line = hubrt::operator_hub::allow_list_line(digest, name);
  if (!line) return fail(line.error().message);
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd < 0 || ::write(fd, line->data(), line->size()) != static_cast<ssize_t>(line->size())) {
    if (fd >= 0) ::close(fd);
    return fail(fmt::format("{}: cannot append to it", path));
  }
  ::close(fd);
  std::cerr << fmt::format("operator-enrol: '{}' enrolled in {}\n", name, path);
  return 0;
}

}  // namespace

namespace hubrt::operator_hub {

int run_operator_enrol(const std::vector<std::string>& args) {
  if (args.size() == 2 && args[0] == "new") {
    if (!write_new_file(args[1]))
      return fail(fmt::format("{}: cannot create it (does it exist already?)", args[1]));
    return 0;
  }
  if (args.size() == 3 && args[0] == "add") return add(args[1], args[2]);
  std::cerr << "usage: operator-enrol new <file> | operator-enrol add <file> <name>\n";
  return 2;
}

}  // namespace hubrt::operator_hub
