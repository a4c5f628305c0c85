// A recording as a tap (tap.h): the messages of MCAP files — one, or the parts of a split
// recording one after another — as the events a live tap gives, so that `hubctl echo`, `watch` and
// `play` read a file the way they read the domain (`--from FILE.mcap`). Read with the linear
// reader, so a file cut off by a killed recorder is read up to its last whole chunk (problem()
// says where it stopped).
#pragma once

#include <chrono>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/mcap/linear_reader.h"

#include "tap.h"
#include "tap_selection.h"

namespace hubrt::hubctl {

struct RecordingOptions {
  // 0: as fast as they are read (echo); 1: the recorded pace (watch, play); 2: twice as fast.
  double rate = 0;
  // Seconds from the recording's first message (log time): messages before `start` and after
  // `end` are skipped.
  double start_s = 0;
  std::optional<double> end_s;
  // Which topics (a topic of a type this hubctl does not know is skipped and listed in skipped()).
  TapFilter filter = [](std::string_view, const msgs::TypeInfo&) { return true; };
};

// Not thread-safe: one consumer.
class RecordingSource final : public TapSource {
 public:
  // Opens the first file. Errors: as mcap::LinearReader::open (not an MCAP file, unreadable).
  static Expected<std::unique_ptr<RecordingSource>> open(std::vector<std::string> files,
                                                         RecordingOptions options);

  std::optional<TapEvent> next(Duration timeout) override;
  [[nodiscard]] bool finished() const override { return finished_; }
  [[nodiscard]] std::uint64_t dropped() const override { return 0; }
  // "FILE: <why the reader stopped>" for a file that did not end with its DataEnd record, or an
  // error opening a later part.
  [[nodiscard]] std::string problem() const override { return problem_; }
  // Moves the pace on by `delay` (the consumer was held up, e.g. waiting for a new topic's
  // readers): later samples keep their spacing instead of going out in a burst to catch up.
  void shift(Duration delay) noexcept {
    if (started_) *started_ += delay;
  }
  // Topics not handed out because their type is unknown to this hubctl: "topic (type)".
  [[nodiscard]] const std::vector<std::string>& skipped() const noexcept { return skipped_; }

 private:
  RecordingSource(std::vector<std::string> files, RecordingOptions options, mcap::LinearReader reader);
  // Reads ahead to the next event to hand out (pending_), opening the next file when one ends.
  void read_ahead();
  std::shared_ptr<const TapTopic> topic_of(std::uint16_t channel_id);

  std::vector<std::string> files_;
  std::size_t file_ = 0;
  RecordingOptions options_;
  std::optional<mcap::LinearReader> reader_;
  std::map<std::string, std::shared_ptr<const TapTopic>> topics_;      // by ROS name, across files
  std::map<std::uint16_t, std::shared_ptr<const TapTopic>> channels_;  // of the current file; null: skipped
  std::deque<TapEvent> pending_;  // the next events, in order (a topic before its first sample)
  std::optional<std::uint64_t> first_log_time_;
  // Pacing: when the first sample was handed out, and its log time.
  std::optional<std::chrono::steady_clock::time_point> started_;
  std::int64_t paced_from_ = 0;
  std::vector<std::string> skipped_;
  std::string problem_;
  bool finished_ = false;
};

}  // namespace hubrt::hubctl
