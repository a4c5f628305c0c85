#include "echo_peer.h"

#include <chrono>
#include <cstring>
#include <thread>

#include <fmt/format.h>

#include "hubrt/msgs/typed.h"

#include "dock.h"
#include "raw_dds.h"

namespace hubrt::bench {

namespace {

void drain(const Peer& peer) {
  void* samples[8] = {};
  dds_sample_info_t infos[8];
  for (;;) {
    const dds_return_t n = dds_take(peer.reader, samples, infos, 8, 8);
    if (n <= 0) return;
    dds_return_loan(peer.reader, samples, n);
  }
}

}  // namespace

double round_trip(const Peer& peer, const char* action, bool* other_state_between, double* sent_at) {
  if (other_state_between != nullptr) *other_state_between = false;
  drain(peer);
  hub_msgs_msg_dds__DockCommand_ command{};
  hubrt::msgs::typed::assign(command.target_type, "dock");
  hubrt::msgs::typed::assign(command.target_name, "dock");
  hubrt::msgs::typed::assign(command.action, action);
  const double sent = mono_now();
  if (sent_at != nullptr) *sent_at = sent;
  if (dds_write(peer.writer, &command) < 0) return -1;
  for (;;) {
    dds_attach_t fired = 0;
    if (dds_waitset_wait(peer.waitset, &fired, 1, DDS_SECS(1)) <= 0) return -1;
    const double woke = mono_now();
    void* samples[8] = {};
    dds_sample_info_t infos[8];
    const dds_return_t n = dds_take(peer.reader, samples, infos, 8, 8);
    bool echoed = false;
    for (dds_return_t i = 0; i < n; ++i) {
      const auto* state = static_cast<const hub_msgs_msg_dds__DockState_*>(samples[i]);
      const bool echoes = infos[i].valid_data && std::strcmp(state->echo.action, action) == 0;
      if (!echoes && infos[i].valid_data && other_state_between != nullptr) *other_state_between = true;
      echoed = echoed || echoes;
    }
    if (n > 0) dds_return_loan(peer.reader, samples, n);
    if (echoed) return woke - sent;
  }
}

Expected<Peer> open_peer(dds_entity_t participant, std::string name, const std::string& command_topic,
                         const std::string& state_topic) {
  Peer peer;
  peer.name = std::move(name);
  auto writer = raw_writer(participant, hub_msgs_msg_dds__DockCommand__desc, command_topic);
  if (!writer) return std::move(writer).error();
  auto reader = raw_reader(participant, hub_msgs_msg_dds__DockState__desc, state_topic);
  if (!reader) return std::move(reader).error();
  auto waitset = raw_waitset(participant, *reader);
  if (!waitset) return std::move(waitset).error();
  peer.writer = *writer;
  peer.reader = *reader;
  peer.waitset = *waitset;
  if (!wait_for_readers(peer.writer, 1, 20.0)) {
    return make_error(ErrorCode::kTimeout, fmt::format("{}: nobody reads {}", peer.name, command_topic));
  }
  return peer;
}

void run_block(Peer& peer, std::size_t samples, bool record, double gap_s) {
  for (std::size_t i = 0; i < samples; ++i) {
    const double rtt = round_trip(peer, i % 2 == 0 ? "monitor" : "reset");
    if (rtt < 0) {
      ++peer.lost;
    } else if (record) {
      peer.latencies_ms.push_back(rtt * 1e3);
    }
    if (gap_s > 0) std::this_thread::sleep_for(std::chrono::duration<double>(gap_s));
  }
}

}  // namespace hubrt::bench
