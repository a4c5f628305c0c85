// Our topics carry no XTypes type information (topic.cc, without_type_information): endpoints
// announce their type by name only, as rmw_cyclonedds' do on Humble, so that the type library of
// Cyclone 0.10.2, which can read a peer's endpoint after it was freed, is never consulted. Shown on
// the topic itself, and across processes as discovery reports a peer (Cyclone leaves type
// information out of what its builtin topics say of local endpoints): the probe's reader is
// announced without it, and a plain Cyclone writer, whose topic has it (idlc's default), matches.
#include <chrono>
#include <string_view>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/dds/entity.h"
#include "hubrt/dds/topic.h"
#include "hubrt/test_support/child_process.h"

#include "dds_fixture.h"
#include "test_types_traits.h"

namespace hubrt::dds::test {
namespace {

using TopicTypeInformation = DdsTest;

enum class Announced { kNotSeen, kWithTypeInformation, kWithoutTypeInformation };

// What DCPSSubscription says of the reader on DDS topic `dds_topic`, waiting for it to be
// discovered.
Announced announced_reader(const Participant& participant, std::string_view dds_topic) {
  EntityHandle reader(
      dds_create_reader(participant.handle(), DDS_BUILTIN_TOPIC_DCPSSUBSCRIPTION, nullptr, nullptr));
  if (reader.get() < 0) return Announced::kNotSeen;
  const auto deadline = std::chrono::steady_clock::now() + kDeliveryBound;
  while (std::chrono::steady_clock::now() < deadline) {
    void* sample = nullptr;
    dds_sample_info_t info{};
    while (dds_take(reader.get(), &sample, &info, 1, 1) == 1) {
      auto* endpoint = static_cast<dds_builtintopic_endpoint_t*>(sample);
      Announced found = Announced::kNotSeen;
      if (info.valid_data && endpoint->topic_name != nullptr && endpoint->topic_name == dds_topic) {
        const dds_typeinfo_t* type_info = nullptr;
        const dds_return_t rc = dds_builtintopic_get_endpoint_type_info(endpoint, &type_info);
        found = (rc == DDS_RETCODE_OK && type_info != nullptr) ? Announced::kWithTypeInformation
                                                               : Announced::kWithoutTypeInformation;
      }
      (void)dds_return_loan(reader.get(), &sample, 1);
      if (found != Announced::kNotSeen) return found;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return Announced::kNotSeen;
}

bool has_type_information(dds_entity_t topic) {
  dds_typeinfo_t* type_info = nullptr;
  if (dds_get_typeinfo(topic, &type_info) != DDS_RETCODE_OK || type_info == nullptr) return false;
  (void)dds_free_typeinfo(type_info);
  return true;
}

TEST_F(TopicTypeInformation, TopicsAreCreatedWithoutIt) {
  // idlc put type information in the descriptor; the topic made of it leaves it out.
  ASSERT_NE(hubrt_test_msg_dds__Ping__desc.m_flagset & DDS_TOPIC_XTYPES_METADATA, 0U);
  auto topic = UntypedTopic::create(participant(), hubrt_test_msg_dds__Ping__desc, "/hubrt_test/by_name");
  ASSERT_TRUE(topic) << topic.error().message;
  EXPECT_FALSE(has_type_information(topic->handle()));
}

// The probe (tests/support/test/dds_env_probe.cc) reads through our topic in its own process.
TEST_F(TopicTypeInformation, PeersSeeOurEndpointsByNameAndAPlainWriterMatchesThem) {
  auto probe = test_support::ChildProcess::start(HUBRT_DDS_ENV_PROBE, {"--read", "/hubrt_test/by_name"},
                                                 domain_->env());
  ASSERT_TRUE(probe) << probe.error().message;
  ASSERT_TRUE(probe->wait_for_output("probe: reading", kDeliveryBound)) << probe->stderr_text();
  EXPECT_EQ(announced_reader(participant(), "rt/hubrt_test/by_name"), Announced::kWithoutTypeInformation);

  // A plain Cyclone program's writer, its topic made by idlc's descriptor as it is.
  const dds_topic_descriptor_t& desc = hubrt_test_msg_dds__Counter__desc;
  EntityHandle plain_topic(
      dds_create_topic(participant().handle(), &desc, "rt/hubrt_test/by_name", nullptr, nullptr));
  ASSERT_GT(plain_topic.get(), 0) << dds_strretcode(plain_topic.get());
  ASSERT_TRUE(has_type_information(plain_topic.get()))
      << "the plain topic is meant to carry type information";
  EntityHandle plain_writer(dds_create_writer(participant().handle(), plain_topic.get(), nullptr, nullptr));
  ASSERT_GT(plain_writer.get(), 0) << dds_strretcode(plain_writer.get());
  dds_publication_matched_status_t matched{};
  const auto deadline = std::chrono::steady_clock::now() + kDeliveryBound;
  while (matched.current_count == 0 && std::chrono::steady_clock::now() < deadline) {
    ASSERT_EQ(dds_get_publication_matched_status(plain_writer.get(), &matched), DDS_RETCODE_OK);
    if (matched.current_count == 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_EQ(matched.current_count, 1U) << "a writer with type information did not match our reader";

  expect_probe_ends_cleanly(*probe);
}

}  // namespace
}  // namespace hubrt::dds::test
