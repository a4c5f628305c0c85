// A DDS peer in another process for tests. Joins the DDS domain its environment names
// (ROS_DOMAIN_ID, CYCLONEDDS_URI), then
//   (no arguments)      waits for a reader on /hubrt_test/probe, publishes one Counter carrying
//                       its pid and prints "probe: wrote <pid>";
//   --read <ros topic>  subscribes to Counter on that topic (keep-last 10, never taken) and
//                       prints "probe: reading";
// and in both cases runs until SIGTERM.
// Exit codes: 0 after SIGTERM, 1 on bad arguments, 2 on a DDS error, 3 if no reader appeared.
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <optional>

#include "hubrt/dds/domain.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"

#include "test_types_traits.h"

namespace {

using hubrt::dds::test::Counter;

int fail(const hubrt::Error& error) {
  std::fprintf(stderr, "probe: %s\n", error.message.c_str());
  return 2;
}

void say(const char* line) {
  std::printf("%s\n", line);
  std::fflush(stdout);
}

int write_one(const hubrt::dds::Participant& participant) {
  auto topic = hubrt::dds::Topic<Counter>::create(participant, "/hubrt_test/probe");
  if (!topic) return fail(topic.error());
  auto writer = hubrt::dds::Writer<Counter>::create(participant, *topic);
  if (!writer) return fail(writer.error());
  // Generous: discovery on a loaded 2-core machine under sanitizers can take seconds.
  if (auto matched = writer->wait_for_readers(1, std::chrono::seconds(30)); !matched) {
    std::fprintf(stderr, "probe: %s\n", matched.error().message.c_str());
    return 3;
  }
  Counter sample{};
  sample.count = getpid();
  sample.value = 0.5;
  if (const hubrt::Status st = writer->write(sample); !st.is_ok()) {
    std::fprintf(stderr, "probe: write failed: %s\n", std::string(hubrt::to_string(st.code())).c_str());
    return 2;
  }
  std::printf("probe: wrote %lld\n", static_cast<long long>(sample.count));
  std::fflush(stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Blocked before any thread exists so that only sigwait() below receives it.
  sigset_t term;
  sigemptyset(&term);
  sigaddset(&term, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &term, nullptr);

  const char* read_topic = nullptr;
  if (argc == 3 && std::strcmp(argv[1], "--read") == 0) {
    read_topic = argv[2];
  } else if (argc != 1) {
    std::fprintf(stderr, "usage: %s [--read <ros topic>]\n", argv[0]);
    return 1;
  }

  auto config = hubrt::dds::domain_config_from_environment();
  if (!config) return fail(config.error());
  auto participant = hubrt::dds::Participant::create(*config, "hubrt_dds_env_probe");
  if (!participant) return fail(participant.error());
  std::printf("probe: joined domain %u\n", config->domain_id);
  std::fflush(stdout);

  // Declared here so that the reader lives until SIGTERM.
  std::optional<hubrt::dds::Topic<Counter>> topic;
  std::optional<hubrt::dds::Reader<Counter>> reader;
  if (read_topic != nullptr) {
    auto created_topic = hubrt::dds::Topic<Counter>::create(*participant, read_topic);
    if (!created_topic) return fail(created_topic.error());
    topic.emplace(std::move(*created_topic));
    auto created_reader = hubrt::dds::Reader<Counter>::create(*participant, *topic);
    if (!created_reader) return fail(created_reader.error());
    reader.emplace(std::move(*created_reader));
    say("probe: reading");
  } else if (const int rc = write_one(*participant); rc != 0) {
    return rc;
  }

  int sig = 0;
  sigwait(&term, &sig);
  return 0;
}
