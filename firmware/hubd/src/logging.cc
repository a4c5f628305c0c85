#include "logging.h"

#include <unistd.h>

#include <cstdlib>

#include <fmt/format.h>
#include <spdlog/pattern_formatter.h>
#include <spdlog/spdlog.h>

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

}  // namespace

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
  auto logger =
      std::make_shared<spdlog::logger>(name, std::make_shared<StderrSink>(colors, g_log_lines_dropped));
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
