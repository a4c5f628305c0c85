// Samples going through Cyclone and back: typed and untyped, buffer reuse, QoS on the entities.
#include <array>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"

#include "dds_fixture.h"
#include "test_types_traits.h"

namespace hubrt::dds::test {
namespace {

// A Ping whose strings and sequence point into this object's own storage, the way the cycle
// builds messages in place (no allocation to write).
struct PingToWrite {
  std::string text;
  std::vector<std::int32_t> values;
  Ping ping{};

  PingToWrite(std::uint32_t seq, std::string t, std::vector<std::int32_t> v, double stamp)
      : text(std::move(t)), values(std::move(v)) {
    ping.seq = seq;
    ping.text = text.data();
    ping.values._buffer = values.data();
    ping.values._length = ping.values._maximum = static_cast<std::uint32_t>(values.size());
    ping.values._release = false;
    ping.stamp = stamp;
  }
};

std::vector<std::int32_t> values_of(const Ping& ping) {
  return {ping.values._buffer, ping.values._buffer + ping.values._length};
}

class PubSub : public DdsTest {
 protected:
  void SetUp() override {
    DdsTest::SetUp();
    if (HasFatalFailure()) return;
    auto topic = Topic<Ping>::create(participant(), "/hubrt_test/ping");
    ASSERT_TRUE(topic) << topic.error().message;
    topic_.emplace(std::move(*topic));
    auto writer = Writer<Ping>::create(participant(), *topic_);
    ASSERT_TRUE(writer) << writer.error().message;
    writer_.emplace(std::move(*writer));
    auto reader = Reader<Ping>::create(participant(), *topic_);
    ASSERT_TRUE(reader) << reader.error().message;
    reader_.emplace(std::move(*reader));
    ASSERT_TRUE(writer_->wait_for_readers(1, kDeliveryBound));
  }

  void write(const PingToWrite& p) { ASSERT_TRUE(writer_->write(p.ping).is_ok()); }

  std::optional<Topic<Ping>> topic_;
  std::optional<Writer<Ping>> writer_;
  std::optional<Reader<Ping>> reader_;
};

TEST_F(PubSub, RoundTripCarriesEveryField) {
  EXPECT_EQ(topic_->dds_name(), "rt/hubrt_test/ping");
  write(PingToWrite(7, "hello hub", {1, -2, 3}, 1.5));
  ASSERT_TRUE(wait_for_data(*reader_));
  Sample<Ping> got;
  SampleInfo info;
  auto taken = reader_->take_next(got, &info);
  ASSERT_TRUE(taken.is_ok());
  ASSERT_TRUE(taken.value());
  EXPECT_EQ(got->seq, 7u);
  EXPECT_STREQ(got->text, "hello hub");
  EXPECT_EQ(values_of(*got), (std::vector<std::int32_t>{1, -2, 3}));
  EXPECT_EQ(got->stamp, 1.5);
  EXPECT_GT(info.source_time.ns_since_epoch, 0);
  EXPECT_NE(info.publication_handle, 0u);
  auto again = reader_->take_next(got);
  ASSERT_TRUE(again.is_ok());
  EXPECT_FALSE(again.value()) << "a sample is taken only once";
}

TEST_F(PubSub, TakeNextReusesTheSamplesBuffers) {
  Sample<Ping> got;
  write(PingToWrite(1, std::string(40, 'a'), {1, 2, 3, 4, 5, 6, 7, 8}, 0));
  ASSERT_TRUE(wait_for_data(*reader_));
  ASSERT_TRUE(reader_->take_next(got).value());
  const char* text_buffer = got->text;
  const std::int32_t* values_buffer = got->values._buffer;
  ASSERT_NE(text_buffer, nullptr);
  ASSERT_NE(values_buffer, nullptr);

  // Smaller contents fit into what the first take allocated: same buffers, new values.
  write(PingToWrite(2, "short", {9, 10}, 0));
  ASSERT_TRUE(wait_for_data(*reader_));
  ASSERT_TRUE(reader_->take_next(got).value());
  EXPECT_EQ(got->seq, 2u);
  EXPECT_EQ(got->text, text_buffer);
  EXPECT_STREQ(got->text, "short");
  EXPECT_EQ(got->values._buffer, values_buffer);
  EXPECT_EQ(values_of(*got), (std::vector<std::int32_t>{9, 10}));
  EXPECT_GE(got->values._maximum, 8u);

  // Larger contents grow the buffers; the old ones are released by Cyclone (ASan checks both).
  write(PingToWrite(3, std::string(200, 'z'), std::vector<std::int32_t>(100, 4), 0));
  ASSERT_TRUE(wait_for_data(*reader_));
  ASSERT_TRUE(reader_->take_next(got).value());
  EXPECT_EQ(std::string(got->text), std::string(200, 'z'));
  EXPECT_EQ(values_of(*got), std::vector<std::int32_t>(100, 4));
}

TEST_F(PubSub, TakeNextIntoPlainZeroedStruct) {
  write(PingToWrite(5, "plain", {42}, 2.0));
  ASSERT_TRUE(wait_for_data(*reader_));
  Ping plain{};
  ASSERT_TRUE(reader_->take_next(plain).value());
  EXPECT_STREQ(plain.text, "plain");
  EXPECT_EQ(values_of(plain), std::vector<std::int32_t>{42});
  dds_sample_free(&plain, &hubrt_test_msg_dds__Ping__desc, DDS_FREE_CONTENTS);
}

TEST_F(PubSub, TakeNextReturnsFalseWhenNothingWaits) {
  Sample<Ping> got;
  auto taken = reader_->take_next(got);
  ASSERT_TRUE(taken.is_ok());
  EXPECT_FALSE(taken.value());
}

TEST_F(PubSub, TakeNextSkipsInvalidSamples) {
  PingToWrite p(1, "first", {}, 0);
  write(p);
  ASSERT_TRUE(wait_for_data(*reader_));
  Sample<Ping> got;
  ASSERT_TRUE(reader_->take_next(got).value());
  // Disposing the (keyless) instance queues a sample without data.
  ASSERT_EQ(dds_dispose(writer_->handle(), &p.ping), DDS_RETCODE_OK);
  ASSERT_TRUE(wait_for_data(*reader_));
  std::array<void*, 1> peek{};
  dds_sample_info_t info{};
  ASSERT_EQ(dds_read(reader_->handle(), peek.data(), &info, 1, 1), 1);
  EXPECT_FALSE(info.valid_data) << "the test needs an invalid sample to skip";
  (void)dds_return_loan(reader_->handle(), peek.data(), 1);

  auto taken = reader_->take_next(got);
  ASSERT_TRUE(taken.is_ok());
  EXPECT_FALSE(taken.value()) << "an invalid sample must not be handed out";
  // Cyclone releases the target's contents when it takes an invalid sample into it: the sample
  // is zeroed, never left half-written.
  EXPECT_EQ(got->text, nullptr);

  write(PingToWrite(2, "after dispose", {}, 0));
  ASSERT_TRUE(wait_for_data(*reader_));
  ASSERT_TRUE(reader_->take_next(got).value());
  EXPECT_STREQ(got->text, "after dispose");
}

TEST_F(PubSub, TakeEachIsBoundedAndKeepsOrder) {
  for (std::uint32_t i = 1; i <= 5; ++i) write(PingToWrite(i, "n", {}, 0));
  // Everything written by one local writer is in the reader once the last one is.
  Sample<Ping> scratch;
  std::vector<std::uint32_t> seen;
  const auto collect = [&](const Ping& ping, const SampleInfo&) { seen.push_back(ping.seq); };
  ASSERT_TRUE(wait_for_data(*reader_));
  auto first = reader_->take_each(scratch, 3, collect);
  ASSERT_TRUE(first.is_ok());
  EXPECT_EQ(first.value(), 3u);
  auto rest = reader_->take_each(scratch, 100, collect);
  ASSERT_TRUE(rest.is_ok());
  EXPECT_EQ(rest.value(), 2u);
  EXPECT_EQ(seen, (std::vector<std::uint32_t>{1, 2, 3, 4, 5}));
}

TEST_F(PubSub, EndpointQosIsReliableVolatileKeepLast10Xcdr1) {
  for (const dds_entity_t entity : {writer_->handle(), reader_->handle()}) {
    dds_qos_t* qos = dds_create_qos();
    ASSERT_EQ(dds_get_qos(entity, qos), DDS_RETCODE_OK);
    dds_reliability_kind_t reliability{};
    dds_duration_t blocking = 0;
    ASSERT_TRUE(dds_qget_reliability(qos, &reliability, &blocking));
    EXPECT_EQ(reliability, DDS_RELIABILITY_RELIABLE);
    dds_durability_kind_t durability{};
    ASSERT_TRUE(dds_qget_durability(qos, &durability));
    EXPECT_EQ(durability, DDS_DURABILITY_VOLATILE);
    dds_history_kind_t history{};
    std::int32_t depth = 0;
    ASSERT_TRUE(dds_qget_history(qos, &history, &depth));
    EXPECT_EQ(history, DDS_HISTORY_KEEP_LAST);
    EXPECT_EQ(depth, 10);
    std::uint32_t n = 0;
    dds_data_representation_id_t* values = nullptr;
    ASSERT_TRUE(dds_qget_data_representation(qos, &n, &values));
    ASSERT_EQ(n, 1u);
    EXPECT_EQ(values[0], DDS_DATA_REPRESENTATION_XCDR1);
    dds_free(values);
    dds_delete_qos(qos);
  }
}

TEST_F(PubSub, SensorDataReaderIsBestEffortAndStillMatchesAReliableWriter) {
  auto reader = Reader<Ping>::create(participant(), *topic_, Qos::sensor_data());
  ASSERT_TRUE(reader) << reader.error().message;
  dds_qos_t* qos = dds_create_qos();
  ASSERT_EQ(dds_get_qos(reader->handle(), qos), DDS_RETCODE_OK);
  dds_reliability_kind_t reliability{};
  dds_duration_t blocking = 0;
  ASSERT_TRUE(dds_qget_reliability(qos, &reliability, &blocking));
  EXPECT_EQ(reliability, DDS_RELIABILITY_BEST_EFFORT);
  dds_history_kind_t history{};
  std::int32_t depth = 0;
  ASSERT_TRUE(dds_qget_history(qos, &history, &depth));
  EXPECT_EQ(depth, 5);
  dds_delete_qos(qos);
  EXPECT_TRUE(writer_->wait_for_readers(2, kDeliveryBound));
}

TEST_F(PubSub, MatchedCountsFollowEndpoints) {
  EXPECT_EQ(writer_->matched_readers().value_or(99), 1u);
  EXPECT_EQ(reader_->matched_writers().value_or(99), 1u);
  {
    auto second = Reader<Ping>::create(participant(), *topic_);
    ASSERT_TRUE(second);
    ASSERT_TRUE(writer_->wait_for_readers(2, kDeliveryBound));
    EXPECT_EQ(writer_->matched_readers().value_or(99), 2u);
  }
  EXPECT_EQ(writer_->matched_readers().value_or(99), 1u);
}

TEST_F(PubSub, WaitForReadersTimesOutNamingTheTopic) {
  auto lonely_topic = Topic<Ping>::create(participant(), "/hubrt_test/lonely");
  ASSERT_TRUE(lonely_topic);
  auto lonely = Writer<Ping>::create(participant(), *lonely_topic);
  ASSERT_TRUE(lonely);
  EXPECT_EQ(lonely->matched_readers().value_or(99), 0u);
  auto waited = lonely->wait_for_readers(1, std::chrono::milliseconds(20));
  ASSERT_FALSE(waited);
  EXPECT_EQ(waited.error().code, ErrorCode::kTimeout);
  EXPECT_NE(waited.error().message.find("'rt/hubrt_test/lonely'"), std::string::npos)
      << waited.error().message;
  EXPECT_NE(waited.error().message.find("0 matched"), std::string::npos) << waited.error().message;
}

TEST_F(DdsTest, UntypedRoundTripFromTheDescriptorAlone) {
  const dds_topic_descriptor_t& desc = hubrt_test_msg_dds__Ping__desc;
  auto topic = UntypedTopic::create(participant(), desc, "/hubrt_test/untyped");
  ASSERT_TRUE(topic) << topic.error().message;
  EXPECT_EQ(&topic->descriptor(), &desc);
  auto writer = UntypedWriter::create(participant(), *topic);
  ASSERT_TRUE(writer) << writer.error().message;
  auto reader = UntypedReader::create(participant(), *topic);
  ASSERT_TRUE(reader) << reader.error().message;
  ASSERT_TRUE(writer->wait_for_readers(1, kDeliveryBound));

  UntypedSample out(desc);
  auto* ping = static_cast<Ping*>(out.data());
  ping->seq = 11;
  ping->text = dds_string_dup("untyped");
  ASSERT_TRUE(writer->write(out.data()).is_ok());
  ASSERT_TRUE(wait_for_data(*reader));
  UntypedSample in(desc);
  auto taken = reader->take_next(in.data());
  ASSERT_TRUE(taken.is_ok());
  ASSERT_TRUE(taken.value());
  EXPECT_EQ(static_cast<Ping*>(in.data())->seq, 11u);
  EXPECT_STREQ(static_cast<Ping*>(in.data())->text, "untyped");
}

TEST_F(DdsTest, TypedAndUntypedEndpointsInteroperate) {
  auto typed_topic = Topic<Counter>::create(participant(), "/hubrt_test/mixed");
  ASSERT_TRUE(typed_topic);
  auto writer = Writer<Counter>::create(participant(), *typed_topic);
  ASSERT_TRUE(writer);
  auto reader = UntypedReader::create(participant(), typed_topic->untyped());
  ASSERT_TRUE(reader);
  ASSERT_TRUE(writer->wait_for_readers(1, kDeliveryBound));
  Counter c{};
  c.count = -5;
  c.value = 2.25;
  ASSERT_TRUE(writer->write(c).is_ok());
  ASSERT_TRUE(wait_for_data(*reader));
  UntypedSample in(reader->descriptor());
  ASSERT_TRUE(reader->take_next(in.data()).value());
  EXPECT_EQ(static_cast<const Counter*>(in.data())->count, -5);
  EXPECT_EQ(static_cast<const Counter*>(in.data())->value, 2.25);
}

}  // namespace
}  // namespace hubrt::dds::test
