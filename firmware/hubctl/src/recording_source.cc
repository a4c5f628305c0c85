#include "recording_source.h"

#include <thread>

#include <fmt/format.h>

#include "hubrt/msgs/all_types.h"

#include "ros2_qos_yaml.h"

namespace hubrt::hubctl {
namespace {

Expected<mcap::LinearReader> open_reader(const std::string& file) {
  auto source = mcap::open_file(file);
  if (!source) return std::move(source).error();
  return mcap::LinearReader::open(std::move(*source));
}

}  // namespace

RecordingSource::RecordingSource(std::vector<std::string> files, RecordingOptions options,
                                 mcap::LinearReader reader)
    : files_(std::move(files)), options_(std::move(options)), reader_(std::move(reader)) {}

Expected<std::unique_ptr<RecordingSource>> RecordingSource::open(std::vector<std::string> files,
                                                                 RecordingOptions options) {
  if (files.empty()) return make_error(ErrorCode::kInvalidArgument, "no recording given");
  auto reader = open_reader(files.front());
  if (!reader) return std::move(reader).error();
  return std::unique_ptr<RecordingSource>(
      new RecordingSource(std::move(files), std::move(options), std::move(*reader)));
}

std::shared_ptr<const TapTopic> RecordingSource::topic_of(std::uint16_t channel_id) {
  if (const auto known = channels_.find(channel_id); known != channels_.end()) return known->second;
  const mcap::Channel& channel = reader_->channels().at(channel_id);
  const auto schema = reader_->schemas().find(channel.schema_id);
  const std::string type_name = schema != reader_->schemas().end() ? schema->second.name : std::string();
  const msgs::TypeInfo* type = type_name.empty() ? nullptr : msgs::all_types().find(type_name);
  std::shared_ptr<const TapTopic>& slot = channels_[channel_id];
  if (type == nullptr || type->descriptor == nullptr) {
    skipped_.push_back(fmt::format("{} ({})", channel.topic, type_name.empty() ? "no schema" : type_name));
    return nullptr;
  }
  if (!options_.filter(channel.topic, *type)) return nullptr;
  auto& topic = topics_[channel.topic];
  if (!topic) {
    auto made = std::make_shared<TapTopic>();
    made->id = static_cast<std::uint32_t>(topics_.size() - 1);
    made->ros_name = channel.topic;
    made->type = type;
    made->type_name = type_name;
    made->schema = schema->second.data;
    if (const auto qos = channel.metadata.find("offered_qos_profiles"); qos != channel.metadata.end())
      made->offered = parse_offered_qos_yaml(qos->second);
    topic = made;
    pending_.push_back({TapEvent::Kind::kTopic, topic, nullptr});
  }
  slot = topic;
  return slot;
}

void RecordingSource::read_ahead() {
  while (pending_.empty() && reader_) {
    auto message = reader_->next();
    if (!message) {
      const mcap::ReadStop& stop = reader_->stop();
      if (stop.reason != mcap::StopReason::kDataEnd) {
        problem_ +=
            fmt::format("{}{}: read up to byte {} of {}: {}", problem_.empty() ? "" : "; ", files_[file_],
                        reader_->whole_bytes(), reader_->source().size(), stop.message);
      }
      reader_.reset();
      channels_.clear();
      while (!reader_ && ++file_ < files_.size()) {
        auto next = open_reader(files_[file_]);
        if (next) {
          reader_.emplace(std::move(*next));
        } else {
          problem_ += fmt::format("{}{}", problem_.empty() ? "" : "; ", next.error().message);
        }
      }
      continue;
    }
    if (!first_log_time_) first_log_time_ = message->log_time;
    const double at_s =
        static_cast<double>(static_cast<std::int64_t>(message->log_time - *first_log_time_)) * 1e-9;
    if (at_s < options_.start_s) continue;
    if (options_.end_s && at_s > *options_.end_s) {
      reader_.reset();  // every later message is later still: the parts are in time order
      file_ = files_.size();
      break;
    }
    auto topic = topic_of(message->channel_id);
    if (!topic) continue;
    auto sample = std::make_shared<TapSample>();
    sample->topic = topic;
    sample->receive_time = WallTime{static_cast<std::int64_t>(message->log_time)};
    sample->source_time = WallTime{static_cast<std::int64_t>(message->publish_time)};
    sample->sequence = message->sequence;
    sample->cdr.assign(message->data.begin(), message->data.end());
    pending_.push_back({TapEvent::Kind::kSample, topic, std::move(sample)});
  }
}

std::optional<TapEvent> RecordingSource::next(Duration timeout) {
  if (pending_.empty()) read_ahead();
  if (pending_.empty()) {
    finished_ = true;
    return std::nullopt;
  }
  TapEvent& event = pending_.front();
  if (event.kind == TapEvent::Kind::kSample && options_.rate > 0) {
    const auto now = std::chrono::steady_clock::now();
    const std::int64_t log_time = event.sample->receive_time.ns_since_epoch;
    if (!started_) {
      started_ = now;
      paced_from_ = log_time;
    }
    const auto due = *started_ + std::chrono::nanoseconds(static_cast<std::int64_t>(
                                     static_cast<double>(log_time - paced_from_) / options_.rate));
    if (due > now + timeout) {
      std::this_thread::sleep_for(timeout);
      return std::nullopt;
    }
    std::this_thread::sleep_until(due);
  }
  TapEvent out = std::move(event);
  pending_.pop_front();
  return out;
}

}  // namespace hubrt::hubctl
