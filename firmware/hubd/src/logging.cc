#include "logging.h"

#include <unistd.h>

#include <cstdlib>

#include <fmt/format.h>
#include <spdlog/pattern_formatter.h>
#include <spdlog/spdlog.h>

#include "hubrt/dds/oversize_samples.h"

#include "log_queue.h"
#include "stderr_sink.h"

namespace hubrt::hubd {
namespace {

// Writes the sd-daemon(3) priority prefix of the message's level.
class SyslogPriorityFlag final : public spdlog::custom_flag_formatter {
 public:
  void format(const spdlog::details::log_msg& msg, const std::tm& /*tm*/,
              spdlog::memory_buf_t& dest) override {
    static constexpr std::array<char, 7> kPriority{'7', '7', '6', '4', '3', '2', '6'};  // trace..off
    const auto level = static_cast<std::size_t>(msg.level);
    const char text[3] = {'<', kPriority[level < kPriority.size() ? level : 6], '>'};
    dest.append(text, text + 3);
  }
  [[nodiscard]] std::unique_ptr<custom_flag_formatter> clone() const override {
    return std::make_unique<SyslogPriorityFlag>();
  }
};

std::atomic<std::uint64_t> g_log_lines_dropped{0};

// The queue to stderr, for the process's life: never destroyed, because its writer thread may be
// left blocked in write(2) at the end (finish_logging); reachable from here, so no leak checker
// reports it.
LogQueue* g_queue = nullptr;

// Cyclone's own log lines (dds::count_oversize_samples forwards them) take the same queue, so
// that a Cyclone thread that logs — or the cycle inside a Cyclone call — never waits for stderr.
void forward_cyclone_line(std::string_view line) noexcept {
  if (g_queue != nullptr) g_queue->push({line});
}

}  // namespace

bool finish_logging(Duration timeout) noexcept {
  return g_queue == nullptr || g_queue->finish(timeout);
}

const std::atomic<std::uint64_t>& log_lines_dropped() noexcept {
  return g_log_lines_dropped;
}

Expected<std::shared_ptr<spdlog::logger>> make_logger(const std::string& name, const std::string& level) {
  const spdlog::level::level_enum parsed = spdlog::level::from_str(level);
  if (parsed == spdlog::level::off && level != "off") {
    return make_error(
        ErrorCode::kInvalidArgument,
        fmt::format("unknown log level '{}' (use trace, debug, info, warn, error, critical or off)", level));
  }
  const char* journal = std::getenv("JOURNAL_STREAM");  // NOLINT(concurrency-mt-unsafe): start-up only
  const bool to_journal = journal != nullptr && *journal != '\0';
  const bool colors = !to_journal && ::isatty(STDERR_FILENO) == 1;
  if (g_queue == nullptr) g_queue = new LogQueue(STDERR_FILENO, g_log_lines_dropped);  // NOLINT: see g_queue
  dds::forward_cyclone_log(&forward_cyclone_line);
  auto logger = std::make_shared<spdlog::logger>(name, std::make_shared<StderrSink>(colors, *g_queue));
  if (to_journal) {
    auto formatter = std::make_unique<spdlog::pattern_formatter>();
    formatter->add_flag<SyslogPriorityFlag>('*').set_pattern("%*%v");
    logger->set_formatter(std::move(formatter));
  } else {
    logger->set_pattern("%Y-%m-%d %H:%M:%S.%e %^%-5l%$ %n: %v");
  }
  logger->set_level(parsed);
  logger->flush_on(spdlog::level::warn);
  spdlog::set_default_logger(logger);
  return logger;
}

}  // namespace hubrt::hubd
