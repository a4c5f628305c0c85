// The reader side of the env probe (dds_env_probe.cc, which publishes one Counter on
// /hubrt_test/probe): a participant of this process in the test's domain, a reader of the probe's
// topic and a waitset that fires on its sample (token 1).
#pragma once

#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "hubrt/dds/participant.h"
#include "hubrt/dds/read_condition.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/waitset.h"
#include "hubrt/test_support/test_domain.h"

#include "test_types_traits.h"

namespace hubrt::test_support {

struct ProbeListener {
  std::optional<dds::Participant> participant;
  std::optional<dds::Topic<dds::test::Counter>> topic;
  std::optional<dds::Reader<dds::test::Counter>> reader;
  std::optional<dds::ReadCondition> condition;
  std::optional<dds::WaitSet> waitset;
};

// Fills `out`, which must stay where it is while the waitset is used. gtest assertions: call it
// through ASSERT_NO_FATAL_FAILURE.
inline void open_probe_listener(const TestDomain& domain, const std::string& participant_name,
                                ProbeListener& out) {
  auto participant = dds::Participant::create(domain.config(), participant_name);
  ASSERT_TRUE(participant) << participant.error().message;
  out.participant.emplace(std::move(*participant));
  auto topic = dds::Topic<dds::test::Counter>::create(*out.participant, "/hubrt_test/probe");
  ASSERT_TRUE(topic) << topic.error().message;
  out.topic.emplace(std::move(*topic));
  auto reader = dds::Reader<dds::test::Counter>::create(*out.participant, *out.topic);
  ASSERT_TRUE(reader) << reader.error().message;
  out.reader.emplace(std::move(*reader));
  auto condition = dds::ReadCondition::create(*out.reader);
  ASSERT_TRUE(condition) << condition.error().message;
  out.condition.emplace(std::move(*condition));
  auto waitset = dds::WaitSet::create(*out.participant);
  ASSERT_TRUE(waitset) << waitset.error().message;
  out.waitset.emplace(std::move(*waitset));
  ASSERT_TRUE(out.waitset->attach(*out.condition, 1));
}

}  // namespace hubrt::test_support
