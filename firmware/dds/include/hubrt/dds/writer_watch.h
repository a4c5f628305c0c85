// Keeps an up-to-date list of the other participants' writers on a chosen set of topics, with
// what DDS says about the process behind each (host, pid, process name, USER_DATA), read from
// Cyclone's builtin discovery topics DCPSPublication and DCPSParticipant. hubd uses it to notice
// a second hub publishing its States (assembly/twin_watch.h).
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/dds/entity.h"
#include "hubrt/dds/guid.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/qos.h"

namespace hubrt::dds {

// One writer of a watched topic that belongs to another participant.
struct WatchedWriter {
  std::string topic_name;  // DDS name, e.g. "rt/dock_ecu/dock/state"
  std::string type_name;   // DDS name, e.g. "hub_msgs::msg::dds_::DockState_"
  OfferedQos qos;          // what the writer offers (reliability, durability, history, ...)
  Guid key;
  Guid participant_key;
  // Cyclone publishes these as properties of every participant's QoS ("__Hostname", "__Pid",
  // "__ProcessName"; src/core/ddsi/src/q_init.c, "participant location properties", and
  // DDS_BUILTIN_TOPIC_PARTICIPANT_PROPERTY_* in dds/ddsi/q_protocol.h). Empty when the other
  // side did not send them (another DDS implementation) or its participant is not known yet.
  std::string host;
  std::string pid;
  std::string process;
  std::string user_data;  // the participant's USER_DATA QoS, verbatim
  bool operator==(const WatchedWriter&) const = default;
};

// Another participant as its SPDP announcement described it: known before any of its endpoints
// (SEDP follows SPDP), which lets hubd recognise a twin hub by the identity in its USER_DATA as
// soon as the participant is discovered.
struct WatchedParticipant {
  Guid key;
  std::string user_data;  // its USER_DATA QoS, verbatim
  bool operator==(const WatchedParticipant&) const = default;
};

// Says whether a DDS topic name is watched. Called on Cyclone's threads: pure, no blocking.
using TopicFilter = std::function<bool(std::string_view dds_topic_name)>;
// Receives the whole current list each time it changes (sorted by participant, then topic).
// Called on a Cyclone thread, or on the thread calling start() for the first list; never twice at
// once. Must not block or delete the watch.
using WritersChanged = std::function<void(const std::vector<WatchedWriter>&)>;

class WriterWatch {
 public:
  // Creates listening readers of DCPSPublication and DCPSParticipant on `participant` (which
  // must outlive the watch) and reports the writers known so far at once through `changed`.
  // Writers of `participant` itself are never reported.
  // Errors: Cyclone's refusal as "watch writers: read discovery topic DCPS...: DDS_RETCODE_...".
  // Thread-safety: the watch may be queried from any thread; destroy it from one thread.
  static Expected<std::unique_ptr<WriterWatch>> start(const Participant& participant, TopicFilter filter,
                                                      WritersChanged changed);
  // Deletes the readers; Cyclone's dds_delete waits for listener calls in progress
  // (src/core/ddsc/src/dds_entity.c: m_cb_pending_count), so no callback runs after it returns.
  ~WriterWatch();
  WriterWatch(const WriterWatch&) = delete;
  WriterWatch& operator=(const WriterWatch&) = delete;

  // The list as last reported. Allocates: not for the cycle.
  [[nodiscard]] std::vector<WatchedWriter> current() const;
  // Every other participant alive as of the last discovery event (sorted by key), and how many
  // participants were newly discovered since start (it only grows). Allocates: not for the cycle.
  [[nodiscard]] std::vector<WatchedParticipant> participants() const;
  [[nodiscard]] std::uint64_t participants_discovered() const noexcept {
    return participants_discovered_.load(std::memory_order_acquire);
  }
  // When participants_discovered() last grew: std::chrono::steady_clock's time since its epoch,
  // taken on Cyclone's thread as the watch learnt of the participant (zero before any). Lets a
  // caller that looks only now and then count a discovery from when it happened.
  [[nodiscard]] std::chrono::nanoseconds last_discovered_at() const noexcept {
    return std::chrono::nanoseconds(last_discovered_ns_.load(std::memory_order_acquire));
  }

 private:
  WriterWatch(Guid self, TopicFilter filter, WritersChanged changed);
  static void on_data_available(dds_entity_t reader, void* arg) noexcept;
  // Re-reads both builtin readers and reports the list when it changed.
  void refresh() noexcept;

  Guid self_;
  TopicFilter filter_;
  WritersChanged changed_;
  std::mutex refresh_mutex_;  // one refresh at a time (two listeners may fire at once)
  // Entries of the sample buffers handed to each reader: never fewer than its largest loan so far
  // (writer_watch.cc, LoanBuffer). Guarded by refresh_mutex_.
  std::size_t participants_capacity_ = 64;
  std::size_t publications_capacity_ = 64;
  mutable std::mutex current_mutex_;
  std::vector<WatchedWriter> current_;
  std::vector<WatchedParticipant> participants_current_;
  std::atomic<std::uint64_t> participants_discovered_{0};
  std::atomic<std::int64_t> last_discovered_ns_{0};  // stored before participants_discovered_ grows
  bool reported_ = false;
  std::atomic<bool> ready_{false};  // both readers exist: callbacks before that are ignored
  EntityHandle participants_;
  EntityHandle publications_;  // declared last: deleted first, while the other still exists
};

}  // namespace hubrt::dds
