// The write pool (src/serdata_pool.h) hands Cyclone exactly the bytes Cyclone's own dds_write path
// makes of the same sample (ddsi_serdata_from_sample with the topic's sertype: what dds_write
// calls), header and padding included, for every padding case and for a sample that outgrows a
// block; and its serdata deserialise back into the sample (what a reader in this process gets).
#include "../src/serdata_pool.h"

#include <string>
#include <vector>

#include <dds/ddsi/ddsi_serdata.h>
#include <gtest/gtest.h>

#include "hubrt/dds/topic.h"

#include "../src/sertype_probe.h"
#include "dds_fixture.h"
#include "test_types_traits.h"

namespace hubrt::dds::test {
namespace {

std::vector<unsigned char> bytes_of(ddsi_serdata* serdata) {
  std::vector<unsigned char> bytes(ddsi_serdata_size(serdata));
  ddsi_serdata_to_ser(serdata, 0, bytes.size(), bytes.data());
  return bytes;
}

class SerdataPoolTest : public DdsTest {};

TEST_F(SerdataPoolTest, SerialisesAsCyclonesOwnWritePath) {
  auto topic = Topic<Ping>::create(participant(), "/hubrt_test/pool_bytes");
  ASSERT_TRUE(topic) << topic.error().message;
  const ddsi_sertype* sertype =
      detail::probe_topic_sertype(participant().handle(), topic->handle(), TopicTraits<Ping>::descriptor());
  ASSERT_NE(sertype, nullptr);
  detail::SerdataPool* pool = detail::SerdataPool::create(sertype, 0);

  std::size_t compared = 0;
  // Text lengths 0..8 cover every padding count; 3000 and 9000 bytes outgrow the first block
  // (512 bytes) and Cyclone's first 4 KiB step.
  for (const std::size_t text_length : {0, 1, 2, 3, 4, 5, 6, 7, 8, 3000, 9000}) {
    for (const std::uint32_t value_count : {0u, 1u, 5u}) {
      std::string text(text_length, 'x');
      for (std::size_t i = 0; i < text.size(); ++i) text[i] = static_cast<char>('a' + i % 26);
      std::vector<std::int32_t> values(value_count);
      for (std::uint32_t i = 0; i < value_count; ++i) values[i] = static_cast<std::int32_t>(i * 7919 - 3);
      Ping ping{};
      ping.seq = static_cast<std::uint32_t>(text_length * 10 + value_count);
      ping.text = text.data();
      ping.values._length = value_count;
      ping.values._maximum = value_count;
      ping.values._buffer = values.data();
      ping.stamp = 1.5 * static_cast<double>(text_length);

      ddsi_serdata* ours = pool->serialize(&ping);
      ASSERT_NE(ours, nullptr);
      ddsi_serdata* cyclones = ddsi_serdata_from_sample(sertype, SDK_DATA, &ping);
      ASSERT_NE(cyclones, nullptr);
      EXPECT_EQ(bytes_of(ours), bytes_of(cyclones)) << "text " << text_length << ", values " << value_count;
      EXPECT_EQ(ours->hash, cyclones->hash);

      Ping back{};
      ASSERT_TRUE(ddsi_serdata_to_sample(ours, &back, nullptr, nullptr));
      EXPECT_EQ(back.seq, ping.seq);
      EXPECT_STREQ(back.text, text.c_str());
      ASSERT_EQ(back.values._length, value_count);
      for (std::uint32_t i = 0; i < value_count; ++i) EXPECT_EQ(back.values._buffer[i], values[i]);
      EXPECT_EQ(back.stamp, ping.stamp);
      dds_sample_free(&back, &hubrt_test_msg_dds__Ping__desc, DDS_FREE_CONTENTS);
      ddsi_serdata_unref(cyclones);
      ddsi_serdata_unref(ours);
      ++compared;
    }
  }
  EXPECT_EQ(compared, 33u);
  // One serdata at a time was out: the pool reused one block (and the instance's key one).
  EXPECT_LE(pool->blocks(), 2u);
  pool->release();
}

}  // namespace
}  // namespace hubrt::dds::test
