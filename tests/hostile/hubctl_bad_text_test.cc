// hubctl never stops on what it receives (issue 11): a State whose strings are not valid UTF-8 —
// written here directly, as a hostile or broken hub would — made `hubctl echo --json` abort
// (nlohmann::json type_error 316 from dump()). Now it prints the State with the bad bytes
// escaped, reports them on stderr and goes on with the next sample.
#include <optional>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hubrt/base/utf8.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/test_support/child_process.h"
#include "hubrt/test_support/test_domain.h"

#include "dock_messages.h"

namespace hubrt::integration {
namespace {

using dock_ecu::DockState;
using std::chrono::milliseconds;
using std::chrono::seconds;

TEST(HubctlBadText, EchoJsonShowsAStateWithBadUtf8EscapedAndGoesOn) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  auto participant = dds::Participant::create(domain->config(), "hostile-hub");
  ASSERT_TRUE(participant) << participant.error().message;
  auto topic = dds::Topic<DockState>::create(*participant, "/dock_ecu/dock/state");
  ASSERT_TRUE(topic) << topic.error().message;
  auto writer = dds::Writer<DockState>::create(*participant, *topic);
  ASSERT_TRUE(writer) << writer.error().message;

  constexpr int kSamples = 4;
  auto hubctl = test_support::ChildProcess::start(
      HUBRT_HUBCTL_PATH,
      {"echo", "/dock_ecu/dock/state", "--json", "-n", std::to_string(kSamples), "--timeout", "30"},
      domain->env());
  ASSERT_TRUE(hubctl) << hubctl.error().message;
  ASSERT_TRUE(writer->wait_for_readers(1, seconds(30))) << hubctl->stderr_text();

  // A surrogate in an error, an overlong in the name, a stray byte in the echo: the bytes the
  // hub of issue 11 copied into error_list.
  std::string name =
      "do\xc0\xaf"
      "ck";
  std::string error = "rejected command: unknown action 'a\xed\xa0\x80'";
  std::string action = "\xff";
  char errors[1][192] = {};
  error.copy(errors[0], sizeof errors[0] - 1);
  DockState state{};
  name.copy(state.name, sizeof state.name - 1);  // raw bytes: the typed setters are for hubs
  action.copy(state.echo.action, sizeof state.echo.action - 1);
  state.error_list._buffer = errors;
  state.error_list._length = state.error_list._maximum = 1;
  // Until hubctl has printed its samples and exited (or died): it may still be matching when the
  // first ones go out. Generous: a loaded machine running sanitizer builds.
  const auto deadline = std::chrono::steady_clock::now() + seconds(60);
  std::uint64_t seq = 0;
  std::optional<test_support::ExitStatus> status;
  while (!status && std::chrono::steady_clock::now() < deadline) {
    state.header.seq = ++seq;
    ASSERT_TRUE(writer->write(state).is_ok());
    std::this_thread::sleep_for(milliseconds(50));
    if (auto ended = hubctl->wait(milliseconds(1))) status = *ended;
  }
  ASSERT_TRUE(status) << "hubctl echo did not finish\n" << hubctl->stderr_text();
  const std::string out = hubctl->stdout_text();
  const std::string err = hubctl->stderr_text();
  ASSERT_TRUE(status->exited_with(0)) << status->describe() << "\nstdout:\n" << out << "\nstderr:\n" << err;

  // Every sample printed, each line valid UTF-8 and valid JSON, the bad bytes escaped.
  std::istringstream lines(out);
  std::string line;
  int printed = 0;
  while (std::getline(lines, line)) {
    ++printed;
    EXPECT_TRUE(is_valid_utf8(line)) << line;
    const auto json = nlohmann::json::parse(line, nullptr, false);
    ASSERT_FALSE(json.is_discarded()) << line;
    EXPECT_EQ(json["name"], "do\\xC0\\xAFck");
    EXPECT_EQ(json["error_list"][0], "rejected command: unknown action 'a\\xED\\xA0\\x80'");
    EXPECT_EQ(json["echo"]["action"], "\\xFF");
  }
  EXPECT_EQ(printed, kSamples);
  // Reported once (not once per sample), naming the fields.
  EXPECT_NE(err.find("not valid UTF-8 in name, echo.action, error_list[0]"), std::string::npos) << err;
}

}  // namespace
}  // namespace hubrt::integration
