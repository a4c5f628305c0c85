#include "hubrt/dds/writer_watch.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <map>
#include <tuple>

#include <dds/dds.h>

#include "builtin_reader.h"
#include "sertype_probe.h"

namespace hubrt::dds {
namespace {

constexpr std::uint32_t kAlive = DDS_ANY_SAMPLE_STATE | DDS_ANY_VIEW_STATE | DDS_ALIVE_INSTANCE_STATE;
constexpr std::uint32_t kNewAlive = DDS_NOT_READ_SAMPLE_STATE | DDS_ANY_VIEW_STATE | DDS_ALIVE_INSTANCE_STATE;
constexpr std::uint32_t kGone = DDS_ANY_SAMPLE_STATE | DDS_ANY_VIEW_STATE |
                                DDS_NOT_ALIVE_DISPOSED_INSTANCE_STATE |
                                DDS_NOT_ALIVE_NO_WRITERS_INSTANCE_STATE;

// Every read and take below lends Cyclone's own sample memory (the first buffer entry null), and
// the buffer handed over must hold as many entries as the largest loan the reader ever made:
// Cyclone 0.10.2 (src/core/ddsc/src/dds_read.c, dds_read_impl) keeps one loan per reader and,
// when it is at least as large as the request, fills in one pointer per sample of the whole loan
// ("ddsi_sertype_realloc_samples (buf, ..., rd->m_loan, rd->m_loan_size, rd->m_loan_size)"), not
// `maxs` of them. So a reader's buffer size only grows (`capacity`, one per reader): once a
// station had more than 64 writers, a buffer of 64 after a loan of 128 was written past its end
// (32 hubs on one host corrupted every hub's heap).
using LoanBuffer = std::vector<void*>;

// Drops the instances of participants and writers that went away, so the readers' caches do not
// grow with every hubctl run over months of uptime. Returns how many, or -1 when the reader is gone.
int purge_gone(dds_entity_t reader, std::size_t capacity) {
  int gone = 0;
  for (;;) {
    LoanBuffer samples(capacity, nullptr);
    std::vector<dds_sample_info_t> infos(capacity);
    const dds_return_t n = dds_take_mask(reader, samples.data(), infos.data(), capacity,
                                         static_cast<std::uint32_t>(capacity), kGone);
    if (n < 0) return -1;
    if (n > 0) (void)dds_return_loan(reader, samples.data(), n);
    gone += n;
    if (static_cast<std::size_t>(n) < capacity) return gone;
  }
}

// Reads the samples not read before (they count as read from then on) and counts those for which
// `counts` holds, or -1 when the reader is gone.
template <class Sample, class Counts>
int read_new(dds_entity_t reader, std::size_t capacity, Counts&& counts) {
  int counted = 0;
  for (;;) {
    LoanBuffer samples(capacity, nullptr);
    std::vector<dds_sample_info_t> infos(capacity);
    const dds_return_t n = dds_read_mask(reader, samples.data(), infos.data(), capacity,
                                         static_cast<std::uint32_t>(capacity), kNewAlive);
    if (n < 0) return -1;
    for (dds_return_t i = 0; i < n; ++i) {
      if (infos[i].valid_data && counts(*static_cast<const Sample*>(samples[i]))) ++counted;
    }
    if (n > 0) (void)dds_return_loan(reader, samples.data(), n);
    if (static_cast<std::size_t>(n) < capacity) return counted;
  }
}

// Reads (keeps in the cache) every alive instance, handing each valid sample to `visit`.
template <class Sample, class Visit>
bool read_alive(dds_entity_t reader, std::size_t& capacity, Visit&& visit) {
  // A builtin reader keeps one sample per instance; read them in one loan large enough for all.
  for (;;) {
    LoanBuffer samples(capacity, nullptr);  // null entries: Cyclone loans its own memory
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

}  // namespace

WriterWatch::WriterWatch(Guid self, TopicFilter filter, WritersChanged changed)
    : self_(self), filter_(std::move(filter)), changed_(std::move(changed)) {}

Expected<std::unique_ptr<WriterWatch>> WriterWatch::start(const Participant& participant, TopicFilter filter,
                                                          WritersChanged changed) {
  std::unique_ptr<WriterWatch> watch(
      new WriterWatch(participant.guid(), std::move(filter), std::move(changed)));
  auto participants =
      detail::listening_builtin_reader(participant, DDS_BUILTIN_TOPIC_DCPSPARTICIPANT, "DCPSParticipant",
                                       "watch writers", watch.get(), &WriterWatch::on_data_available);
  if (!participants) return std::move(participants).error();
  watch->participants_ = std::move(*participants);
  auto publications =
      detail::listening_builtin_reader(participant, DDS_BUILTIN_TOPIC_DCPSPUBLICATION, "DCPSPublication",
                                       "watch writers", watch.get(), &WriterWatch::on_data_available);
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
    const int gone_participants = purge_gone(participants_.get(), participants_capacity_);
    const int gone_writers = purge_gone(publications_.get(), publications_capacity_);
    const int new_participants =
        read_new<dds_builtintopic_participant_t>(participants_.get(), participants_capacity_,
                                                 [](const dds_builtintopic_participant_t&) { return true; });
    const int new_watched = read_new<dds_builtintopic_endpoint_t>(
        publications_.get(), publications_capacity_, [this](const dds_builtintopic_endpoint_t& e) {
          return Guid::from(e.participant_key) != self_ && e.topic_name != nullptr && filter_(e.topic_name) &&
                 !detail::is_sertype_probe(e.qos);
        });
    if (gone_participants < 0 || gone_writers < 0 || new_participants < 0 || new_watched < 0)
      return;  // being deleted
    // Each discovery event used to re-read every writer and participant on the domain: with N
    // hubs on a host each hub did that N * (writers per hub) times while they started, O(N^2)
    // sample copies per hub (Cyclone copies a builtin sample's QoS into each loan), which on 2
    // cores stretched 64 hubs' discovery to tens of seconds. The participants are re-read when
    // one came or went (the start-up check counts them, and knows a twin by its USER_DATA
    // before its writers appear); the writers only when a watched writer came, a writer went, or
    // a participant came or went while watched writers exist (its process details).
    const bool participants_changed = gone_participants > 0 || new_participants > 0;
    bool writers_unchanged = false;
    {
      const std::lock_guard current_lock(current_mutex_);
      const bool process_changed = !current_.empty() && participants_changed;
      writers_unchanged = reported_ && new_watched == 0 && gone_writers == 0 && !process_changed;
    }
    if (writers_unchanged && !participants_changed) return;
    std::map<Guid, ProcessInfo> processes;
    std::vector<WatchedParticipant> others;
    const bool read_participants = read_alive<dds_builtintopic_participant_t>(
        participants_.get(), participants_capacity_, [&](const dds_builtintopic_participant_t& p) {
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
      if (added > 0) {
        const auto at = std::chrono::duration_cast<std::chrono::nanoseconds>(
            std::chrono::steady_clock::now().time_since_epoch());
        last_discovered_ns_.store(at.count(), std::memory_order_release);
        participants_discovered_.fetch_add(added, std::memory_order_release);
      }
    }
    if (writers_unchanged) return;
    std::vector<WatchedWriter> writers;
    const bool read_publications = read_alive<dds_builtintopic_endpoint_t>(
        publications_.get(), publications_capacity_, [&](const dds_builtintopic_endpoint_t& e) {
          const Guid participant = Guid::from(e.participant_key);
          if (participant == self_ || e.topic_name == nullptr || !filter_(e.topic_name) ||
              detail::is_sertype_probe(e.qos))
            return;
          WatchedWriter writer;
          writer.topic_name = e.topic_name;
          if (e.type_name != nullptr) writer.type_name = e.type_name;
          writer.qos = read_offered_qos(e.qos);
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
