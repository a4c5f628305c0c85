#include "hubrt/blackbox/black_box.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "hubrt/mcap/writer.h"

namespace hubrt::blackbox {
namespace {

namespace fs = std::filesystem;

std::uint64_t wall_now_ns() noexcept {
  timespec now{};
  clock_gettime(CLOCK_REALTIME, &now);
  return static_cast<std::uint64_t>(now.tv_sec) * 1'000'000'000U + static_cast<std::uint64_t>(now.tv_nsec);
}

// "2026-11-28_14-03-59" in local time.
std::string file_time() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d_%H-%M-%S", &local);
  return text;
}

bool valid_reason(std::string_view reason) {
  return !reason.empty() && std::all_of(reason.begin(), reason.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-';
  });
}

// write(2) until done; false on an error (async-signal-safe).
bool write_all(int fd, const void* data, std::size_t size) noexcept {
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, bytes, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    bytes += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

void put_le(std::uint8_t* out, std::uint64_t value, int bytes) noexcept {
  for (int i = 0; i < bytes; ++i) out[i] = static_cast<std::uint8_t>(value >> (8 * i));
}

}  // namespace

// Copies each sample it is shown into the ring, stamped with this machine's wall clock.
class BlackBox::StreamHook final : public dds::SampleHook {
 public:
  StreamHook(Ring& ring, std::uint16_t stream) : ring_(&ring), stream_(stream) {}
  void on_sample(std::span<const std::uint8_t> serialized, WallTime source_time) noexcept override {
    const std::uint64_t now = wall_now_ns();
    const std::uint64_t source =
        source_time.ns_since_epoch > 0 ? static_cast<std::uint64_t>(source_time.ns_since_epoch) : now;
    ring_->record(stream_, serialized, now, source);
  }

 private:
  Ring* ring_;
  std::uint16_t stream_;
};

BlackBox::BlackBox(BlackBoxOptions options) : options_(std::move(options)), ring_(options_.memory_bytes) {}
BlackBox::~BlackBox() = default;

Expected<std::unique_ptr<BlackBox>> BlackBox::create(BlackBoxOptions options) {
  if (options.hub_name.empty() || options.directory.empty())
    return make_error(ErrorCode::kInvalidArgument, "black box: a hub name and a directory are needed");
  std::error_code error;
  fs::create_directories(options.directory, error);
  if (error || !fs::is_directory(options.directory)) {
    return make_error(ErrorCode::kIo, fmt::format("black box: make the directory {}: {}", options.directory,
                                                  error ? error.message() : "not a directory"));
  }
  return std::unique_ptr<BlackBox>(new BlackBox(std::move(options)));
}

dds::SampleHook& BlackBox::add_stream(StreamSpec spec) {
  streams_.push_back(std::move(spec));
  hooks_.push_back(std::make_unique<StreamHook>(ring_, static_cast<std::uint16_t>(streams_.size() - 1)));
  return *hooks_.back();
}

void BlackBox::seal() {
  // What every file says first: the crash path writes these bytes as they are, and then records
  // outside chunks (MCAP spec, "Data Section": Schema, Channel and Message records may stand there).
  crash_prologue_.assign(mcap::kMagic.begin(), mcap::kMagic.end());
  mcap::append_record(crash_prologue_, mcap::Header{"ros2", "hubrt hubd black box (crash)"});
  std::map<std::string, std::uint16_t> schemas;
  for (std::size_t i = 0; i < streams_.size(); ++i) {
    const StreamSpec& s = streams_[i];
    auto [schema, added] = schemas.emplace(s.type_name, static_cast<std::uint16_t>(schemas.size() + 1));
    if (added)
      mcap::append_record(crash_prologue_, mcap::Schema{schema->second, s.type_name, "ros2msg", s.schema});
    mcap::append_record(crash_prologue_, mcap::Channel{static_cast<std::uint16_t>(i),
                                                       schema->second,
                                                       s.topic,
                                                       "cdr",
                                                       {{"offered_qos_profiles", s.offered_qos_yaml}}});
  }
  crash_prefix_ = fmt::format("{}/{}_", options_.directory, options_.hub_name);
  sealed_ = true;
}

Expected<DumpResult> BlackBox::dump(std::string_view reason) {
  if (!valid_reason(reason)) return make_error(ErrorCode::kInvalidArgument, "black box: bad reason");
  const std::lock_guard lock(dump_mutex_);
  const RingSnapshot snapshot = ring_.snapshot(options_.span);
  DumpResult result;
  result.path = fmt::format("{}/{}_{}_{}.mcap", options_.directory, options_.hub_name, file_time(), reason);
  // Two dumps in one second (a fault, then the exit): the second gets a number.
  for (int n = 2; fs::exists(result.path); ++n)
    result.path =
        fmt::format("{}/{}_{}_{}-{}.mcap", options_.directory, options_.hub_name, file_time(), reason, n);
  const std::string part = result.path + ".part";
  ::unlink(part.c_str());
  mcap::WriterOptions writer_options;
  writer_options.library = "hubrt hubd black box";
  writer_options.compression = options_.compression;
  auto writer = mcap::Writer::create(part, writer_options);
  if (!writer) return std::move(writer).error();
  const auto fail = [&](Error error) -> Expected<DumpResult> {
    (void)writer->finish();
    ::unlink(part.c_str());
    return error;
  };
  std::vector<std::optional<std::uint16_t>> channels(streams_.size());
  std::vector<std::uint32_t> sequences(streams_.size(), 0);
  for (const RingSnapshot::Item& item : snapshot.items) {
    if (item.stream >= streams_.size()) continue;
    auto& channel = channels[item.stream];
    if (!channel) {
      const StreamSpec& s = streams_[item.stream];
      auto schema = writer->add_schema({0, s.type_name, "ros2msg", s.schema});
      if (!schema) return fail(std::move(schema).error());
      auto id =
          writer->add_channel({0, *schema, s.topic, "cdr", {{"offered_qos_profiles", s.offered_qos_yaml}}});
      if (!id) return fail(std::move(id).error());
      channel = *id;
    }
    const mcap::Message message{*channel, ++sequences[item.stream], item.log_time, item.publish_time,
                                snapshot.bytes_of(item)};
    if (auto written = writer->write(message); !written) return fail(std::move(written).error());
  }
  result.messages = writer->statistics().message_count;
  if (result.messages > 0) {
    result.seconds =
        static_cast<double>(writer->statistics().message_end_time - writer->statistics().message_start_time) *
        1e-9;
  }
  if (auto finished = writer->finish(); !finished) return fail(std::move(finished).error());
  result.bytes = writer->file_bytes();
  if (::rename(part.c_str(), result.path.c_str()) != 0) {
    const int err = errno;
    ::unlink(part.c_str());
    return make_error(ErrorCode::kIo, fmt::format("black box: rename {}: {}", part, std::strerror(err)));
  }
  dumps_.fetch_add(1, std::memory_order_relaxed);
  trim_directory(result.path);
  return result;
}

void BlackBox::trim_directory(const std::string& keep) const {
  // This hub's complete files, oldest first; a crash file counts too.
  struct File {
    fs::file_time_type time;
    std::string path;
    std::uintmax_t size;
  };
  std::vector<File> files;
  std::uintmax_t total = 0;
  std::error_code error;
  const std::string prefix = options_.hub_name + "_";
  for (const auto& entry : fs::directory_iterator(options_.directory, error)) {
    const std::string name = entry.path().filename().string();
    if (!name.starts_with(prefix) || !name.ends_with(".mcap") || !entry.is_regular_file(error)) continue;
    const std::uintmax_t size = entry.file_size(error);
    if (error) continue;
    files.push_back({entry.last_write_time(error), entry.path().string(), size});
    total += size;
  }
  std::sort(files.begin(), files.end(), [](const File& a, const File& b) { return a.time < b.time; });
  for (const File& file : files) {
    if (total <= options_.directory_bytes) break;
    if (file.path == keep) continue;
    if (fs::remove(file.path, error)) total -= file.size;
  }
}

void BlackBox::crash_dump() noexcept {
  if (!sealed_) return;
  // The name: <directory>/<hub>_<unix seconds>_crash.mcap, made without allocating.
  char path[4096];
  const std::size_t prefix = std::min(crash_prefix_.size(), sizeof path - 64);
  std::memcpy(path, crash_prefix_.data(), prefix);
  std::size_t at = prefix;
  char digits[24];
  int count = 0;
  for (std::uint64_t s = wall_now_ns() / 1'000'000'000U; s > 0 || count == 0; s /= 10)
    digits[count++] = static_cast<char>('0' + s % 10);
  while (count > 0) path[at++] = digits[--count];
  static constexpr char kSuffix[] = "_crash.mcap";
  std::memcpy(path + at, kSuffix, sizeof kSuffix);
  const int fd = ::open(path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return;
  bool ok = write_all(fd, crash_prologue_.data(), crash_prologue_.size());
  std::uint32_t sequence = 0;
  ring_.visit_unlocked([&](const RingEntry& entry) {
    // A Message record (spec, "Message"): opcode, length, channel, sequence, log and publish time.
    std::uint8_t head[mcap::kRecordPrefixBytes + 22];
    head[0] = static_cast<std::uint8_t>(mcap::Opcode::kMessage);
    put_le(head + 1, 22 + entry.bytes.size(), 8);
    put_le(head + 9, entry.stream, 2);
    put_le(head + 11, ++sequence, 4);
    put_le(head + 15, entry.log_time, 8);
    put_le(head + 23, entry.publish_time, 8);
    ok = ok && write_all(fd, head, sizeof head) && write_all(fd, entry.bytes.data(), entry.bytes.size());
  });
  // DataEnd without a CRC, a Footer without a summary, the magic (spec, "Footer": 0 = none).
  std::uint8_t tail[mcap::kRecordPrefixBytes + 4 + mcap::kRecordPrefixBytes + mcap::kFooterContentBytes +
                    mcap::kMagic.size()] = {};
  tail[0] = static_cast<std::uint8_t>(mcap::Opcode::kDataEnd);
  put_le(tail + 1, 4, 8);
  std::uint8_t* footer = tail + mcap::kRecordPrefixBytes + 4;
  footer[0] = static_cast<std::uint8_t>(mcap::Opcode::kFooter);
  put_le(footer + 1, mcap::kFooterContentBytes, 8);
  std::memcpy(footer + mcap::kRecordPrefixBytes + mcap::kFooterContentBytes, mcap::kMagic.data(),
              mcap::kMagic.size());
  ok = ok && write_all(fd, tail, sizeof tail);
  (void)ok;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace hubrt::blackbox
