// What the MCAP tests share: a scratch folder, a small recording written with known messages, and
// the file's bytes.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/mcap/linear_reader.h"
#include "hubrt/mcap/writer.h"

namespace hubrt::mcap::test {

// A folder of its own per test, removed afterwards.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            fmt::format("hubrt-mcap-{}-{}-{}", getpid(), info->test_suite_name(), info->name());
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  [[nodiscard]] std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

// A message as the tests expect to read it back (the data owned).
struct RecordedMessage {
  std::string topic;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0;
  std::uint64_t publish_time = 0;
  std::vector<std::uint8_t> data;
  bool operator==(const RecordedMessage&) const = default;
};

inline std::vector<std::uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

// Every message a reader hands out, with its channel's topic, until it stops.
inline std::vector<RecordedMessage> read_all(LinearReader& reader) {
  std::vector<RecordedMessage> out;
  while (auto m = reader.next()) {
    out.push_back({reader.channels().at(m->channel_id).topic, m->sequence, m->log_time, m->publish_time,
                   std::vector<std::uint8_t>(m->data.begin(), m->data.end())});
  }
  return out;
}

// Payload bytes that differ per message and compress somewhat, like CDR of a State.
inline std::vector<std::uint8_t> payload(std::uint32_t n, std::size_t size) {
  std::vector<std::uint8_t> data(size);
  for (std::size_t i = 0; i < size; ++i) data[i] = static_cast<std::uint8_t>((n * 7 + i / 5) & 0xff);
  if (size >= 4) {
    data[0] = 0;  // an XCDR1 little-endian header, as the ros2 profile's cdr carries
    data[1] = 1;
    data[2] = 0;
    data[3] = 0;
  }
  return data;
}

// Writes `count` messages over three topics of two schemas into `path`, `topic_c` starting only
// after a third of them (a topic that appears later); returns what was written.
inline std::vector<RecordedMessage> write_sample_file(const std::string& path, const WriterOptions& options,
                                                      std::uint32_t count) {
  auto writer = Writer::create(path, options);
  EXPECT_TRUE(writer) << writer.error().message;
  const auto state =
      writer->add_schema({0, "hub_msgs/msg/DockState", "ros2msg", "bool docked\nstring name\n"});
  const auto command = writer->add_schema({0, "hub_msgs/msg/DockCommand", "ros2msg", "string action\n"});
  EXPECT_TRUE(state && command);
  const std::map<std::string, std::string> qos = {
      {"offered_qos_profiles", "- history: keep_last\n  depth: 10\n"}};
  const auto a = writer->add_channel({0, *state, "/dock/state", "cdr", qos});
  const auto b = writer->add_channel({0, *command, "/dock/command", "cdr", qos});
  std::optional<std::uint16_t> c;
  std::vector<RecordedMessage> written;
  for (std::uint32_t n = 0; n < count; ++n) {
    if (n == count / 3) {
      auto added = writer->add_channel({0, *state, "/rsp/state", "cdr", {}});
      EXPECT_TRUE(added);
      c = *added;
    }
    const std::uint16_t channel = c && n % 3 == 2 ? *c : (n % 2 == 0 ? *a : *b);
    const std::string topic = channel == *a ? "/dock/state" : channel == *b ? "/dock/command" : "/rsp/state";
    auto data = payload(n, 40 + (n % 13) * 9);
    const std::uint64_t log_time = 1'700'000'000'000'000'000ULL + n * 10'000'000ULL;
    const std::uint64_t publish_time = log_time - 250'000 - n;
    EXPECT_TRUE(writer->write({channel, n, log_time, publish_time, data}));
    written.push_back({topic, n, log_time, publish_time, std::move(data)});
  }
  EXPECT_TRUE(writer->finish());
  return written;
}

}  // namespace hubrt::mcap::test
