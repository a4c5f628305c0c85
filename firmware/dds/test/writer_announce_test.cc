// UntypedWriter::announce: a sample without data whose acknowledgement shows a reader has heard
// the writer. Here the reader and the writer share one process, so they match at once and the
// race announce() closes (a reader that has not heard the writer yet, in another process) does
// not arise: what is shown is that readers take nothing from it, that a disposing QoS and a keyed
// topic are refused, and that what is written next arrives. The race itself is
// tests/integration/hubctl_send_test.cc's WaitForNReadersWaitsForALateOne.
#include <array>

#include <gtest/gtest.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"

#include "dds_fixture.h"
#include "test_types_traits.h"

namespace hubrt::dds::test {
namespace {

using Announce = DdsTest;

Qos announcing_qos() {
  Qos qos = Qos::ros2_default();
  qos.dispose_on_unregister(false);
  return qos;
}

// How many samples, valid or not, `reader` holds (read, so they stay).
int held_samples(const UntypedReader& reader) {
  std::array<void*, 4> samples{};
  std::array<dds_sample_info_t, 4> infos{};
  const dds_return_t n =
      dds_read(reader.handle(), samples.data(), infos.data(), samples.size(), samples.size());
  if (n > 0) (void)dds_return_loan(reader.handle(), samples.data(), n);
  return n;
}

TEST_F(Announce, ReadersTakeNothingFromItAndGetWhatIsWrittenNext) {
  const dds_topic_descriptor_t& desc = hubrt_test_msg_dds__Counter__desc;
  auto topic = UntypedTopic::create(participant(), desc, "/hubrt_test/announce");
  ASSERT_TRUE(topic) << topic.error().message;
  // The instance is known to the reader through another writer's sample, as a hub's /sim/fault
  // reader knows it from an earlier `hubctl send`.
  auto earlier = UntypedWriter::create(participant(), *topic);
  ASSERT_TRUE(earlier) << earlier.error().message;
  auto writer = UntypedWriter::create(participant(), *topic, announcing_qos());
  ASSERT_TRUE(writer) << writer.error().message;
  auto reader = UntypedReader::create(participant(), *topic);
  ASSERT_TRUE(reader) << reader.error().message;
  ASSERT_TRUE(writer->wait_for_readers(1, kDeliveryBound));
  ASSERT_TRUE(earlier->wait_for_readers(1, kDeliveryBound));

  UntypedSample out(desc);
  static_cast<Counter*>(out.data())->count = 1;
  ASSERT_TRUE(earlier->write(out.data()).is_ok());
  ASSERT_TRUE(wait_for_data(*reader));
  UntypedSample in(desc);
  ASSERT_TRUE(reader->take_next(in.data()).value());

  ASSERT_TRUE(writer->announce().is_ok());
  ASSERT_TRUE(writer->wait_for_acks(kDeliveryBound));
  // Not even an invalid sample: Cyclone ignores an unregistration from a writer it holds no
  // registration of. Had the writer disposed on unregister, the reader would hold one here.
  EXPECT_EQ(held_samples(*reader), 0);

  static_cast<Counter*>(out.data())->count = 2;
  ASSERT_TRUE(writer->write(out.data()).is_ok());
  ASSERT_TRUE(wait_for_data(*reader));
  ASSERT_TRUE(reader->take_next(in.data()).value());
  EXPECT_EQ(static_cast<const Counter*>(in.data())->count, 2);
  EXPECT_EQ(held_samples(*reader), 0) << "the announcement left nothing behind";
}

TEST_F(Announce, AWriterThatWouldDisposeTheInstanceIsRefused) {
  auto topic =
      UntypedTopic::create(participant(), hubrt_test_msg_dds__Counter__desc, "/hubrt_test/disposing");
  ASSERT_TRUE(topic) << topic.error().message;
  auto writer = UntypedWriter::create(participant(), *topic);  // Cyclone's default: disposes
  ASSERT_TRUE(writer) << writer.error().message;
  auto reader = UntypedReader::create(participant(), *topic);
  ASSERT_TRUE(reader) << reader.error().message;
  ASSERT_TRUE(writer->wait_for_readers(1, kDeliveryBound));
  EXPECT_EQ(writer->announce().code(), ErrorCode::kFailedPrecondition);
  EXPECT_TRUE(writer->wait_for_acks(kDeliveryBound));
  EXPECT_EQ(held_samples(*reader), 0) << "nothing was written";
}

TEST_F(Announce, AKeyedTopicIsRefused) {
  auto topic = UntypedTopic::create(participant(), hubrt_test_msg_dds__Keyed__desc, "/hubrt_test/keyed");
  ASSERT_TRUE(topic) << topic.error().message;
  auto writer = UntypedWriter::create(participant(), *topic, announcing_qos());
  ASSERT_TRUE(writer) << writer.error().message;
  // Unregistering one instance of many says nothing about the others; refused before any write.
  EXPECT_EQ(writer->announce().code(), ErrorCode::kFailedPrecondition);
}

}  // namespace
}  // namespace hubrt::dds::test
