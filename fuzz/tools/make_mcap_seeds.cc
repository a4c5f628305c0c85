// Writes the seeds of fuzz/corpus/mcap_reader/: small recordings as hubctl record writes them
// (zstd, lz4 and uncompressed chunks), one cut off in the middle of a chunk as a killed recorder
// leaves it, and one with its messages outside chunks as other writers may make them. Run by
// hand when the writer changes:  build/fuzz/fuzz/fuzz_make_mcap_seeds fuzz/corpus/mcap_reader
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "hubrt/mcap/summary.h"
#include "hubrt/mcap/writer.h"

namespace {

namespace fs = std::filesystem;
using hubrt::mcap::Compression;

std::vector<std::uint8_t> recording(const fs::path& scratch, Compression compression) {
  hubrt::mcap::WriterOptions options;
  options.compression = compression;
  options.chunk_bytes = 200;
  fs::remove(scratch);
  {
    auto writer = hubrt::mcap::Writer::create(scratch.string(), options);
    if (!writer) return {};
    const auto schema = *writer->add_schema({0, "hub_msgs/msg/DockCommand", "ros2msg", "string action\n"});
    const auto state = *writer->add_schema({0, "hub_msgs/msg/DockState", "ros2msg", "bool docked\n"});
    const auto command =
        *writer->add_channel({0,
                              schema,
                              "/dock/command",
                              "cdr",
                              {{"offered_qos_profiles", "- history: keep_last\n  depth: 10\n"}}});
    const auto states = *writer->add_channel({0, state, "/dock/state", "cdr", {}});
    for (std::uint32_t n = 0; n < 12; ++n) {
      const std::vector<std::uint8_t> cdr = {0, 1, 0, 0, 8, 0, 0, 0, 'm', 'o', 'n', 'i', 't', 'o', 'r', 0};
      const std::uint64_t t = 1'700'000'000'000'000'000ULL + n * 10'000'000ULL;
      (void)writer->write({n % 3 == 0 ? command : states, n, t, t - 1000, cdr});
    }
    (void)writer->finish();
  }
  std::ifstream in(scratch, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Schema, Channel and Message records straight in the data section, then DataEnd and a Footer
// without a summary.
std::vector<std::uint8_t> unchunked() {
  std::vector<std::uint8_t> out(hubrt::mcap::kMagic.begin(), hubrt::mcap::kMagic.end());
  hubrt::mcap::append_record(out, hubrt::mcap::Header{"ros2", "other"});
  hubrt::mcap::append_record(out, hubrt::mcap::Schema{1, "std_msgs/msg/String", "ros2msg", "string data\n"});
  hubrt::mcap::append_record(out, hubrt::mcap::Channel{3, 1, "/chatter", "cdr", {}});
  const std::uint8_t cdr[] = {0, 1, 0, 0, 3, 0, 0, 0, 'h', 'i', 0, 0};
  hubrt::mcap::append_record(out, hubrt::mcap::Message{3, 1, 5, 5, cdr});
  hubrt::mcap::append_record(out, hubrt::mcap::DataEnd{0});
  hubrt::mcap::append_record(out, hubrt::mcap::Footer{0, 0, 0});
  out.insert(out.end(), hubrt::mcap::kMagic.begin(), hubrt::mcap::kMagic.end());
  return out;
}

void write(const fs::path& folder, const std::string& name, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(folder / name, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  std::printf("%s (%zu bytes)\n", (folder / name).c_str(), bytes.size());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <corpus folder of mcap_reader>\n", argv[0]);
    return 2;
  }
  const fs::path folder = argv[1];
  fs::create_directories(folder);
  const fs::path scratch = fs::temp_directory_path() / "hubrt-mcap-seed.mcap";
  const auto zstd = recording(scratch, Compression::kZstd);
  write(folder, "zstd", zstd);
  write(folder, "lz4", recording(scratch, Compression::kLz4));
  write(folder, "uncompressed", recording(scratch, Compression::kNone));
  // Cut in the middle of the middle chunk, as a recorder killed while writing it leaves the file.
  auto summary = hubrt::mcap::read_summary(*hubrt::mcap::memory_source(zstd));
  if (!summary || summary->chunk_indexes.empty()) return 1;
  const auto& middle = summary->chunk_indexes[summary->chunk_indexes.size() / 2];
  const auto cut = static_cast<std::ptrdiff_t>(middle.chunk_start_offset + middle.chunk_length / 2);
  write(folder, "cut-in-a-chunk", std::vector<std::uint8_t>(zstd.begin(), zstd.begin() + cut));
  write(folder, "unchunked", unchunked());
  fs::remove(scratch);
  return 0;
}
