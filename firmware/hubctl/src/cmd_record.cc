// hubctl record: the station's traffic into MCAP files that Foxglove and `ros2 bag` open (ros2
// profile: recorder.h), topics that appear later included, until Ctrl-C/SIGTERM — which finish the
// file — or --duration; split by --max-size / --max-duration. A killed recorder leaves the chunks it
// wrote (one a second at least); `hubctl record --recover FILE` writes the summary again.
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <thread>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "hubrt/mcap/recover.h"
#include "hubrt/mcap/summary.h"

#include "commands.h"
#include "plant_tap.h"
#include "recorder.h"
#include "session.h"
#include "station_tap.h"

namespace hubrt::hubctl {
namespace {

struct RecordOptions {
  PlantOptions plant;
  std::string output;
  TapChoice choice;
  std::uint64_t max_size = 0;
  double max_duration_s = 0;
  double duration_s = 0;
  std::string compression = "zstd";
  double chunk_s = 1.0;
  std::size_t queue = 200'000;
  bool quiet = false;
  std::string recover;
};

// "hubrt_2026-11-28_14-03-59.mcap" in the current directory.
std::string default_name() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char text[64];
  std::strftime(text, sizeof text, "hubrt_%Y-%m-%d_%H-%M-%S.mcap", &local);
  return text;
}

std::string megabytes(std::uint64_t bytes) {
  if (bytes < 1'000'000) return fmt::format("{:.1f} kB", static_cast<double>(bytes) / 1e3);
  return fmt::format("{:.1f} MB", static_cast<double>(bytes) / 1e6);
}

int run_recover(const RecordOptions& options) {
  const std::string& input = options.recover;
  if (auto source = mcap::open_file(input); source && mcap::read_summary(**source)) {
    fmt::print("{} is complete (its summary reads); nothing to recover\n", input);
    return kExitOk;
  }
  // Written next to the input and renamed over it (or to --output) once complete and synced.
  const std::string output = options.output.empty() ? input : options.output;
  const std::string partial = output + ".recovering";
  ::unlink(partial.c_str());
  mcap::WriterOptions writer;
  writer.library = "hubrt hubctl record --recover";
  auto recovered = mcap::recover(input, partial, writer);
  if (!recovered) {
    fmt::print(stderr, "hubctl record --recover: {}\n", recovered.error().message);
    return recovered.error().code == ErrorCode::kProtocol ? kExitUsage : kExitFailed;
  }
  if (std::rename(partial.c_str(), output.c_str()) != 0) {
    fmt::print(stderr, "hubctl record --recover: rename {} to {}: {}\n", partial, output,
               std::strerror(errno));
    return kExitFailed;
  }
  fmt::print(
      "{}: {} message(s) of {} whole chunk(s) kept ({} of {} bytes); {}\n", output, recovered->messages,
      recovered->chunks_read, recovered->bytes_kept, recovered->bytes_kept + recovered->bytes_dropped,
      recovered->stop.reason == mcap::StopReason::kDataEnd ? "the data was whole, the summary rewritten"
                                                           : "then: " + recovered->stop.message);
  return kExitOk;
}

void print_progress(const RecorderProgress& p, std::uint64_t dropped, bool tty, bool last) {
  const std::string line =
      fmt::format("recording: {} messages, {}, {} topics{}", p.messages, megabytes(p.bytes), p.topics,
                  dropped > 0 ? fmt::format(", {} dropped (the disk is too slow)", dropped) : "");
  if (tty) {
    fmt::print(stderr, "\r{}\x1b[K{}", line, last ? "\n" : "");  // one line, redrawn
  } else {
    fmt::print(stderr, "{}\n", line);
  }
  std::fflush(stderr);
}

int run_record(const RecordOptions& options) {
  install_stop_handler();
  auto filter = make_tap_filter(options.choice);
  const auto compression =
      mcap::compression_from_name(options.compression == "none" ? "" : options.compression);
  if (!filter || !compression) {
    fmt::print(stderr, "hubctl record: {}\n",
               filter ? fmt::format("--compression '{}': zstd, lz4 or none", options.compression)
                      : filter.error().message);
    return kExitUsage;
  }
  RecorderOptions recorder_options;
  recorder_options.path = options.output.empty() ? default_name() : options.output;
  recorder_options.writer.compression = *compression;
  recorder_options.writer.library = "hubrt hubctl record";
  recorder_options.split.max_bytes = options.max_size;
  recorder_options.split.max_duration = seconds(options.max_duration_s);
  recorder_options.chunk_period = seconds(options.chunk_s);
  // One participant per station's domain (plant_session.h): a plant's stations in one file.
  auto members = join_plant(options.plant, "hubctl-record");
  if (!members) {
    fmt::print(stderr, "hubctl record: {}\n", members.error().message);
    return kExitUsage;
  }
  auto recorder = Recorder::create(recorder_options);
  if (!recorder) {
    fmt::print(stderr, "hubctl record: {}\n", recorder.error().message);
    return kExitFailed;
  }
  TapOptions tap_options;
  tap_options.filter = *filter;
  auto tap = PlantTap::start(*members, tap_options);
  if (!tap) {
    fmt::print(stderr, "hubctl record: {}\n", tap.error().message);
    return kExitFailed;
  }
  auto source = (*tap)->subscribe(options.queue);
  fmt::print(stderr, "recording into {} (Ctrl-C finishes the file)\n", recorder->progress().files.back());
  const bool tty = isatty(STDERR_FILENO) != 0;
  const auto start = std::chrono::steady_clock::now();
  auto next_progress = start;
  Expected<void> written;
  while (written && !stop_requested()) {
    const auto now = std::chrono::steady_clock::now();
    if (options.duration_s > 0 && now - start >= seconds(options.duration_s)) break;
    if (auto event = source->next(std::chrono::milliseconds(100))) written = recorder->take(*event, now);
    if (written) written = recorder->tick(std::chrono::steady_clock::now());
    if (!options.quiet && now >= next_progress) {
      print_progress(recorder->progress(), source->dropped(), tty, false);
      next_progress = now + (tty ? std::chrono::seconds(1) : std::chrono::seconds(10));
    }
  }
  // Stopped: the tap takes nothing more; what it took is written, then the summary.
  tap->reset();
  while (written) {
    auto event = source->next(Duration::zero());
    if (!event) break;
    written = recorder->take(*event, std::chrono::steady_clock::now());
  }
  auto finished = written ? recorder->finish() : std::move(written);
  const RecorderProgress done = recorder->progress();
  if (!options.quiet) print_progress(done, source->dropped(), tty, true);
  for (const auto& [topic, type] : recorder->unrecordable())
    fmt::print(stderr, "hubctl record: {} not recorded: this hubctl has no .msg definition of {}\n", topic,
               type);
  if (!finished) {
    fmt::print(stderr,
               "hubctl record: {}; the chunks written so far are readable (hubctl record --recover {})\n",
               finished.error().message, done.files.back());
    return kExitFailed;
  }
  fmt::print("recorded {} messages on {} topics into {} ({})\n", done.messages, done.topics,
             fmt::join(done.files, ", "), megabytes(done.bytes));
  return kExitOk;
}

}  // namespace

void add_record_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<RecordOptions>();
  CLI::App* cmd = app.add_subcommand(
      "record", "Record the station's traffic into MCAP (ros2 profile: Foxglove and ros2 bag open it)");
  cmd->footer(
      "By default every State, command, /diagnostics and /sim topic, those that appear later included. "
      "Ctrl-C or SIGTERM finish the file; a recorder killed otherwise leaves every chunk it wrote (one a "
      "second at least): hubctl record --recover FILE makes the file whole. Exit status: 0 recorded; 1 "
      "writing failed; 2 bad arguments.");
  cmd->add_option("-o,--output", options->output,
                  "The file (default hubrt_<date>_<time>.mcap here); split parts are <name>_0.mcap, _1, ...; "
                  "with --recover: where the whole file goes (default: over FILE)");
  cmd->add_option("--topics", options->choice.topics, "Only these topics (ROS names)");
  cmd->add_option("--regex", options->choice.regex, "Only topics whose whole ROS name matches (ECMAScript)");
  cmd->add_flag("--all", options->choice.all, "Every topic of a type this hubctl knows");
  cmd->add_option("--max-size", options->max_size,
                  "Begin a new file before one would pass this size (e.g. 100M)")
      ->transform(CLI::AsSizeValue(false));
  cmd->add_option("--max-duration", options->max_duration_s, "Begin a new file after this many seconds")
      ->check(CLI::Range(1.0, 1e7));
  cmd->add_option("--duration", options->duration_s, "Stop after this many seconds (default: until Ctrl-C)")
      ->check(CLI::Range(0.0, 1e7));
  cmd->add_option("--compression", options->compression, "Chunk compression: zstd (default), lz4 or none");
  cmd->add_option("--chunk-seconds", options->chunk_s,
                  "Close a chunk at least this often: what a killed recorder can lose at most")
      ->check(CLI::Range(0.05, 60.0));
  cmd->add_option("--queue", options->queue, "Samples held for the file while the disk is busy")
      ->check(CLI::Range(std::size_t{100}, std::size_t{10'000'000}));
  cmd->add_flag("--quiet,-q", options->quiet, "No progress line (the file's name and the summary stay)");
  cmd->add_option("--recover", options->recover,
                  "Make a cut-off recording whole again (its whole chunks, a new summary) and exit");
  add_plant_options(*cmd, options->plant);
  cmd->callback([options, &exit_code] {
    exit_code = options->recover.empty() ? run_record(*options) : run_recover(*options);
  });
}

}  // namespace hubrt::hubctl
