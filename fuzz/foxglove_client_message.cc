// What a Foxglove client sends hubctl foxglove: a sequence of WebSocket messages, text (JSON
// requests) or binary (Client Message Data), into one client session that may publish, with the
// tap's samples arriving in between. Input: records of [kind][length, 2 bytes LE][bytes]; kind bit
// 0: binary, bit 1: then a sample of channel (kind >> 4) & 3, bits 2-3: milliseconds to advance.
// Oracle beyond the sanitizers: every frame the server queues is JSON nlohmann reads back (a
// status quotes the client's text) or a whole Message Data frame, and the queue's byte count
// returns to zero when drained.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

#include <nlohmann/json.hpp>

#include "foxglove_session.h"

namespace {

using namespace hubrt::hubctl::foxglove;

struct Writer final : CommandWriter {
  hubrt::Status write(std::span<const std::uint8_t> cdr) noexcept override {
    return hubrt::Status(cdr.size() < 4 ? hubrt::ErrorCode::kInvalidArgument : hubrt::ErrorCode::kOk);
  }
};

struct Sink final : CommandSink {
  hubrt::Expected<std::shared_ptr<CommandWriter>> open(const std::string& topic,
                                                       std::string_view schema) override {
    if (schema.empty() || topic.size() > 64)
      return hubrt::make_error(hubrt::ErrorCode::kInvalidArgument, "no");
    return std::shared_ptr<CommandWriter>(std::make_shared<Writer>());
  }
};

void check_and_drain(ClientSession& session) {
  while (auto frame = session.next_frame()) {
    if (frame->is_text()) {
      (void)nlohmann::json::parse(*frame->text);  // throws (and the fuzzer reports) if not JSON
    } else if (frame->header[0] != 0x01 ||
               frame->bytes() != frame->header.size() + frame->sample->cdr.size()) {
      __builtin_trap();
    }
  }
  if (session.queued_bytes() != 0) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static Sink sink;
  SessionLimits limits;
  limits.data_bytes = 4096;
  limits.control_bytes = 1 << 20;
  limits.max_subscriptions = 8;
  limits.max_client_channels = 4;
  ClientSession session(1, "fuzz", limits, {true, {}}, &sink, {});
  const std::uint32_t channels[] = {0, 1, 2, 3};
  session.channels_added(channels,
                         std::make_shared<const std::string>(R"({"op":"advertise","channels":[]})"));
  auto sample = std::make_shared<hubrt::hubctl::TapSample>();
  sample->cdr.assign(40, 0x11);
  hubrt::Time now(std::chrono::seconds(1));
  std::span<const std::uint8_t> input(data, size);
  int messages = 0;
  while (input.size() >= 3) {
    const std::uint8_t kind = input[0];
    const std::size_t length = std::min<std::size_t>(input.size() - 3, input[1] | (input[2] << 8));
    const auto message = input.subspan(3, length);
    input = input.subspan(3 + length);
    now += std::chrono::milliseconds((kind >> 2) & 3);
    if ((kind & 1) != 0) {
      session.on_binary(message, now);
    } else {
      session.on_text({reinterpret_cast<const char*>(message.data()), message.size()}, now);
    }
    if ((kind & 2) != 0) session.sample((kind >> 4) & 3, sample);
    if (++messages % 8 == 0) {
      session.report_drops(now);
      check_and_drain(session);
    }
  }
  check_and_drain(session);
  return 0;
}
