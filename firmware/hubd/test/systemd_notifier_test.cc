// SystemdNotifier speaks systemd's notification protocol itself (sd_notify(3), NOTES): checked
// here against a datagram socket standing in for systemd's, at a path and in the abstract
// namespace, with the watchdog variables of sd_watchdog_enabled(3).
#include "systemd_notifier.h"

#include <unistd.h>

#include <array>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/un.h>

namespace hubrt::hubd {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

// A bound AF_UNIX datagram socket: what systemd listens on.
class FakeSystemd {
 public:
  explicit FakeSystemd(bool abstract) {
    fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    const std::string name = fmt::format("hubrt-notify-test-{}", ::getpid());
    if (abstract) {
      name_ = "@" + name;
      std::memcpy(address.sun_path + 1, name.data(), name.size());
    } else {
      path_ = std::filesystem::temp_directory_path() / name;
      std::filesystem::remove(path_);
      name_ = path_.string();
      std::memcpy(address.sun_path, name_.data(), name_.size());
    }
    const auto length = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + name_.size());
    EXPECT_EQ(::bind(fd_, reinterpret_cast<const sockaddr*>(&address), length), 0) << std::strerror(errno);
    timeval timeout{2, 0};  // generous: a loaded machine; nothing here waits unless a test fails
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  }
  ~FakeSystemd() {
    ::close(fd_);
    if (!path_.empty()) std::filesystem::remove(path_);
  }
  [[nodiscard]] const std::string& name() const { return name_; }
  std::string receive() const {
    std::array<char, 512> buffer{};
    const ssize_t n = ::recv(fd_, buffer.data(), buffer.size(), 0);
    return n > 0 ? std::string(buffer.data(), static_cast<std::size_t>(n)) : std::string("<nothing>");
  }

 private:
  int fd_ = -1;
  std::filesystem::path path_;
  std::string name_;
};

class SystemdNotifierTest : public ::testing::Test {
 protected:
  void TearDown() override {
    ::unsetenv("NOTIFY_SOCKET");  // NOLINT(concurrency-mt-unsafe): single-threaded test
    ::unsetenv("WATCHDOG_USEC");  // NOLINT(concurrency-mt-unsafe)
    ::unsetenv("WATCHDOG_PID");   // NOLINT(concurrency-mt-unsafe)
  }
  static void set(const char* name, const std::string& value) {
    ASSERT_EQ(::setenv(name, value.c_str(), 1), 0);  // NOLINT(concurrency-mt-unsafe)
  }
};

TEST_F(SystemdNotifierTest, OutsideSystemdItIsSilent) {
  const SystemdNotifier notifier;
  EXPECT_FALSE(notifier.under_systemd());
  EXPECT_EQ(notifier.watchdog_interval(), Duration::zero());
  notifier.ready("running");  // nothing to send to, nothing happens
}

TEST_F(SystemdNotifierTest, SendsReadyStatusWatchdogAndStoppingToAPathSocket) {
  const FakeSystemd systemd(false);
  set("NOTIFY_SOCKET", systemd.name());
  set("WATCHDOG_USEC", "2000000");
  set("WATCHDOG_PID", std::to_string(::getpid()));
  SystemdNotifier notifier;
  ASSERT_TRUE(notifier.under_systemd());
  EXPECT_EQ(notifier.watchdog_interval(), seconds(2));

  notifier.allow_startup(seconds(30));
  EXPECT_EQ(systemd.receive(), "WATCHDOG_USEC=30000000\nWATCHDOG=1");
  notifier.ready("running hub 'dock_ecu'");
  EXPECT_EQ(systemd.receive(), "READY=1\nWATCHDOG_USEC=2000000\nWATCHDOG=1\nSTATUS=running hub 'dock_ecu'");
  notifier.cycle_done(Time(seconds(10)));
  EXPECT_EQ(systemd.receive(), "WATCHDOG=1");
  notifier.cycle_done(Time(seconds(10) + milliseconds(500)));  // within half the watchdog: no ping
  notifier.stopping();
  EXPECT_EQ(systemd.receive(), "STOPPING=1");
}

TEST_F(SystemdNotifierTest, ReachesAnAbstractNamespaceSocket) {
  const FakeSystemd systemd(true);
  set("NOTIFY_SOCKET", systemd.name());
  const SystemdNotifier notifier;
  ASSERT_TRUE(notifier.under_systemd());
  EXPECT_EQ(notifier.watchdog_interval(), Duration::zero());  // no WATCHDOG_USEC: no watchdog
  notifier.ready("up");
  EXPECT_EQ(systemd.receive(), "READY=1\nSTATUS=up");
}

TEST_F(SystemdNotifierTest, AWatchdogMeantForAnotherProcessIsNotOurs) {
  const FakeSystemd systemd(false);
  set("NOTIFY_SOCKET", systemd.name());
  set("WATCHDOG_USEC", "2000000");
  set("WATCHDOG_PID", std::to_string(::getpid() + 1));
  const SystemdNotifier notifier;
  EXPECT_TRUE(notifier.under_systemd());
  EXPECT_EQ(notifier.watchdog_interval(), Duration::zero());
}

}  // namespace
}  // namespace hubrt::hubd
