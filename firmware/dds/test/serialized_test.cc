// Samples as bytes: what a reader takes serialized is what Cyclone's serialiser makes of the sample
// (header and padding), decodes back to it, and sent again as it is reaches another reader as the
// same sample; bytes Cyclone would refuse from the network are refused here too.
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/dds/cdr_codec.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"

#include "dds_fixture.h"
#include "test_types_traits.h"

namespace hubrt::dds::test {
namespace {

class SerializedTest : public DdsTest {};

TEST_F(SerializedTest, TakenBytesAreCyclonesSerialisationAndSentAgainTheyArriveAsTheSameSample) {
  auto topic = Topic<Ping>::create(participant(), "/hubrt_test/serialized");
  ASSERT_TRUE(topic) << topic.error().message;
  auto writer = Writer<Ping>::create(participant(), *topic);
  auto raw_reader = UntypedReader::create(participant(), topic->untyped());
  ASSERT_TRUE(writer && raw_reader);
  auto codec = CdrCodec::create(participant(), TopicTraits<Ping>::descriptor());
  ASSERT_TRUE(codec) << codec.error().message;

  std::vector<std::int32_t> values = {3, -7, 1 << 20};
  std::string text = "seven";  // 5 bytes + NUL: the payload needs padding at its end
  Ping ping{};
  ping.seq = 41;
  ping.text = text.data();
  ping.values._length = ping.values._maximum = static_cast<std::uint32_t>(values.size());
  ping.values._buffer = values.data();
  ping.stamp = 2.5;
  ASSERT_TRUE(writer->write(ping).is_ok());
  ASSERT_TRUE(wait_for_data(*raw_reader));
  std::vector<std::uint8_t> bytes;
  SampleInfo info;
  const auto taken = raw_reader->take_serialized(bytes, &info);
  ASSERT_TRUE(taken.is_ok() && taken.value());
  EXPECT_GT(info.source_time.ns_since_epoch, 0);
  auto encoded = codec->encode(&ping);
  ASSERT_TRUE(encoded);
  EXPECT_EQ(bytes, *encoded);
  ASSERT_GE(bytes.size(), 4U);
  EXPECT_EQ(bytes[0], 0);  // CDR_LE: XCDR1, little-endian (DDS-XTypes 7.6.3.1.2)
  EXPECT_EQ(bytes[1], 1);

  Sample<Ping> decoded;
  ASSERT_TRUE(codec->decode(bytes, &decoded.get()));
  EXPECT_EQ(decoded->seq, 41U);
  EXPECT_STREQ(decoded->text, "seven");
  ASSERT_EQ(decoded->values._length, 3U);
  EXPECT_EQ(decoded->values._buffer[2], 1 << 20);

  // Sent again as bytes: another reader gets the very sample.
  auto other = Participant::create(config(), "other");
  ASSERT_TRUE(other);
  auto other_topic = Topic<Ping>::create(*other, "/hubrt_test/serialized");
  ASSERT_TRUE(other_topic);
  auto other_reader = Reader<Ping>::create(*other, *other_topic);
  ASSERT_TRUE(other_reader);
  ASSERT_TRUE(writer->untyped().wait_for_readers(2, kDeliveryBound));
  auto raw_writer = UntypedWriter::create(participant(), topic->untyped());
  ASSERT_TRUE(raw_writer);
  ASSERT_TRUE(raw_writer->wait_for_readers(2, kDeliveryBound));
  ASSERT_TRUE(raw_writer->write_serialized(bytes).is_ok());
  ASSERT_TRUE(wait_for_data(*other_reader, *other));
  Sample<Ping> received;
  const auto got = other_reader->take_next(received);
  ASSERT_TRUE(got.is_ok() && got.value());
  EXPECT_EQ(received->seq, 41U);
  EXPECT_STREQ(received->text, "seven");
  EXPECT_EQ(received->stamp, 2.5);
}

TEST_F(SerializedTest, BytesCycloneWouldRefuseFromTheNetworkAreRefused) {
  auto topic = Topic<Ping>::create(participant(), "/hubrt_test/refused");
  ASSERT_TRUE(topic);
  auto writer = UntypedWriter::create(participant(), topic->untyped());
  ASSERT_TRUE(writer);
  auto codec = CdrCodec::create(participant(), TopicTraits<Ping>::descriptor());
  ASSERT_TRUE(codec);
  // seq, then a string whose length runs past the end of the payload.
  const std::vector<std::uint8_t> bad = {0, 1, 0, 0, 1, 0, 0, 0, 0xff, 0xff, 0, 0, 'a', 'b', 0, 0};
  Sample<Ping> sample;
  EXPECT_FALSE(codec->decode(bad, &sample.get()));
  EXPECT_EQ(writer->write_serialized(bad).code(), ErrorCode::kInvalidArgument);
  const std::vector<std::uint8_t> no_header = {0x42};
  EXPECT_FALSE(codec->decode(no_header, &sample.get()));
  EXPECT_EQ(writer->write_serialized(no_header).code(), ErrorCode::kInvalidArgument);
}

TEST(CdrCodec, WorksOnAnIsolatedParticipant) {
  auto participant = Participant::create(DomainConfig{231, isolated_config_xml()}, "codec");
  ASSERT_TRUE(participant) << participant.error().message;
  auto codec = CdrCodec::create(*participant, TopicTraits<Counter>::descriptor());
  ASSERT_TRUE(codec) << codec.error().message;
  const Counter counter{-5, 0.25};
  auto bytes = codec->encode(&counter);
  ASSERT_TRUE(bytes);
  EXPECT_EQ(bytes->size(), 4U + 16U);
  Counter back{};
  ASSERT_TRUE(codec->decode(*bytes, &back));
  EXPECT_EQ(back.count, -5);
  EXPECT_EQ(back.value, 0.25);
}

}  // namespace
}  // namespace hubrt::dds::test
