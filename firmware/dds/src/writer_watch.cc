#include "hubrt/dds/writer_watch.h"

#include <algorithm>
#include <array>
#include <map>
#include <tuple>

#include <dds/dds.h>

#include "hubrt/dds/retcode.h"

namespace hubrt::dds {
namespace {

constexpr std::size_t kBatch = 64;
constexpr std::uint32_t kAlive = DDS_ANY_SAMPLE_STATE | DDS_ANY_VIEW_STATE | DDS_ALIVE_INSTANCE_STATE;
constexpr std::uint32_t kGone = DDS_ANY_SAMPLE_STATE | DDS_ANY_VIEW_STATE |
                                DDS_NOT_ALIVE_DISPOSED_INSTANCE_STATE |
                                DDS_NOT_ALIVE_NO_WRITERS_INSTANCE_STATE;

// Drops the instances of participants and writers that went away, so the readers' caches do not
// grow with every hubctl run over months of uptime.
bool purge_gone(dds_entity_t reader) noexcept {
  for (;;) {
    std::array<void*, kBatch> samples{};
    std::array<dds_sample_info_t, kBatch> infos{};
    const dds_return_t n = dds_take_mask(reader, samples.data(), infos.data(), kBatch, kBatch, kGone);
    if (n < 0) return false;
    if (n > 0) (void)dds_return_loan(reader, samples.data(), n);
    if (static_cast<std::size_t>(n) < kBatch) return true;
  }
}

// Reads (keeps in the cache) every alive instance, handing each valid sample to `visit`.
template <class Sample, class Visit>
bool read_alive(dds_entity_t reader, Visit&& visit) {
  // A builtin reader keeps one sample per instance; read them in one loan large enough for all.
  std::size_t capacity = kBatch;
  for (;;) {
    std::vector<void*> samples(capacity, nullptr);  // null entries: Cyclone loans its own memory
    std::vector<dds_sample_info_t> infos(capacity);
    const dds_return_t n = dds_read_mask(reader, samples.data(), infos.data(), capacity,
                                         static_cast<std::uint32_t>(capacity), kAlive);
    if (n < 0) return false;
    if (static_cast<std::size_t>(n) == capacity) {
      (void)dds_return_loan(reader, samples.data(), n);
      capacity *= 2;  // maybe more than fit: read again, all at once
      continue;
    }
    for (dds_return_t i = 0; i < n; ++i) {
      if (infos[i].valid_data) visit(*static_cast<const Sample*>(samples[i]));
    }
    if (n > 0) (void)dds_return_loan(reader, samples.data(), n);
    return true;
  }
}

std::string property(const dds_qos_t* qos, const char* name) {
  char* value = nullptr;
  if (qos == nullptr || !dds_qget_prop(qos, name, &value) || value == nullptr) return {};
  std::string out(value);
  dds_free(value);
  return out;
}

std::string user_data(const dds_qos_t* qos) {
  void* value = nullptr;
  std::size_t size = 0;
  if (qos == nullptr || !dds_qget_userdata(qos, &value, &size) || value == nullptr) return {};
  std::string out(static_cast<const char*>(value), size);
  dds_free(value);
  return out;
}

struct ProcessInfo {
  std::string host;
  std::string pid;
  std::string process;
  std::string user_data;
};

Expected<EntityHandle> builtin_reader(const Participant& participant, dds_entity_t topic, const char* name,
                                      void* arg, dds_on_data_available_fn callback) {
  const std::unique_ptr<dds_listener_t, decltype(&dds_delete_listener)> listener(dds_create_listener(arg),
                                                                                 &dds_delete_listener);
  dds_lset_data_available(listener.get(), callback);
  EntityHandle reader(dds_create_reader(participant.handle(), topic, nullptr, listener.get()));
  if (reader.get() < 0)
    return dds_error(reader.get(), std::string("watch writers: read discovery topic ") + name);
  return reader;
}

}  // namespace

WriterWatch::WriterWatch(Guid self, TopicFilter filter, WritersChanged changed)
    : self_(self), filter_(std::move(filter)), changed_(std::move(changed)) {}

Expected<std::unique_ptr<WriterWatch>> WriterWatch::start(const Participant& participant, TopicFilter filter,
                                                          WritersChanged changed) {
  std::unique_ptr<WriterWatch> watch(
      new WriterWatch(participant.guid(), std::move(filter), std::move(changed)));
  auto participants = builtin_reader(participant, DDS_BUILTIN_TOPIC_DCPSPARTICIPANT, "DCPSParticipant",
                                     watch.get(), &WriterWatch::on_data_available);
  if (!participants) return std::move(participants).error();
  watch->participants_ = std::move(*participants);
  auto publications = builtin_reader(participant, DDS_BUILTIN_TOPIC_DCPSPUBLICATION, "DCPSPublication",
                                     watch.get(), &WriterWatch::on_data_available);
  if (!publications) return std::move(publications).error();
  watch->publications_ = std::move(*publications);
  watch->ready_ = true;
  // A new builtin reader is filled with everything discovered so far, possibly before its
  // listener could report it: read it once here.
  watch->refresh();
  return watch;
}

WriterWatch::~WriterWatch() {
  ready_ = false;
  publications_.reset();
  participants_.reset();
}

void WriterWatch::on_data_available(dds_entity_t /*reader*/, void* arg) noexcept {
  auto* watch = static_cast<WriterWatch*>(arg);
  if (watch->ready_) watch->refresh();
}

std::vector<WatchedWriter> WriterWatch::current() const {
  const std::lock_guard lock(current_mutex_);
  return current_;
}

std::vector<WatchedParticipant> WriterWatch::participants() const {
  const std::lock_guard lock(current_mutex_);
  return participants_current_;
}

void WriterWatch::refresh() noexcept {
  try {
    const std::lock_guard lock(refresh_mutex_);
    if (!purge_gone(participants_.get()) || !purge_gone(publications_.get())) return;  // being deleted
    std::map<Guid, ProcessInfo> processes;
    std::vector<WatchedParticipant> others;
    const bool read_participants = read_alive<dds_builtintopic_participant_t>(
        participants_.get(), [&](const dds_builtintopic_participant_t& p) {
          const Guid key = Guid::from(p.key);
          ProcessInfo& info = processes[key] =
              ProcessInfo{property(p.qos, "__Hostname"), property(p.qos, "__Pid"),
                          property(p.qos, "__ProcessName"), user_data(p.qos)};
          if (key != self_) others.push_back(WatchedParticipant{key, info.user_data});
        });
    if (!read_participants) return;
    std::sort(others.begin(), others.end(),
              [](const WatchedParticipant& a, const WatchedParticipant& b) { return a.key < b.key; });
    {
      const std::lock_guard current_lock(current_mutex_);
      std::uint64_t added = 0;
      for (const WatchedParticipant& other : others) {
        const bool known = std::binary_search(
            participants_current_.begin(), participants_current_.end(), other,
            [](const WatchedParticipant& a, const WatchedParticipant& b) { return a.key < b.key; });
        if (!known) ++added;
      }
      participants_current_ = std::move(others);
      if (added > 0) participants_discovered_.fetch_add(added, std::memory_order_release);
    }
    std::vector<WatchedWriter> writers;
    const bool read_publications = read_alive<dds_builtintopic_endpoint_t>(
        publications_.get(), [&](const dds_builtintopic_endpoint_t& e) {
          const Guid participant = Guid::from(e.participant_key);
          if (participant == self_ || e.topic_name == nullptr || !filter_(e.topic_name)) return;
          WatchedWriter writer;
          writer.topic_name = e.topic_name;
          writer.key = Guid::from(e.key);
          writer.participant_key = participant;
          if (const auto it = processes.find(participant); it != processes.end()) {
            writer.host = it->second.host;
            writer.pid = it->second.pid;
            writer.process = it->second.process;
            writer.user_data = it->second.user_data;
          }
          writers.push_back(std::move(writer));
        });
    if (!read_publications) return;
    std::sort(writers.begin(), writers.end(), [](const WatchedWriter& a, const WatchedWriter& b) {
      return std::tie(a.participant_key, a.topic_name, a.key) <
             std::tie(b.participant_key, b.topic_name, b.key);
    });
    {
      const std::lock_guard current_lock(current_mutex_);
      if (reported_ && writers == current_) return;
      current_ = writers;
      reported_ = true;
    }
    changed_(writers);
  } catch (const std::exception&) {
    // Out of memory on a Cyclone thread: keep the last list (the next discovery event retries)
    // rather than terminate the hub.
  }
}

}  // namespace hubrt::dds
