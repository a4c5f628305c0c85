#include "raw_dds.h"

#include <charconv>
#include <cstdlib>
#include <ctime>
#include <string_view>
#include <thread>

#include <fmt/format.h>

namespace hubrt::bench {
namespace {

Error refused(dds_return_t rc, const std::string& what) {
  return make_error(ErrorCode::kIo, fmt::format("{}: {}", what, dds_strretcode(rc)));
}

Expected<dds_entity_t> raw_topic(dds_entity_t participant, const dds_topic_descriptor_t& descriptor,
                                 const std::string& dds_name) {
  dds_qos_t* qos = raw_qos();
  const dds_entity_t topic = dds_create_topic(participant, &descriptor, dds_name.c_str(), qos, nullptr);
  dds_delete_qos(qos);
  if (topic < 0) return refused(topic, fmt::format("create topic {}", dds_name));
  return topic;
}

}  // namespace

std::uint32_t domain_from_environment() noexcept {
  const char* text = std::getenv("ROS_DOMAIN_ID");  // NOLINT(concurrency-mt-unsafe): read at start
  if (text == nullptr) return 0;
  std::uint32_t id = 0;
  const std::string_view view(text);
  std::from_chars(view.data(), view.data() + view.size(), id);
  return id;
}

Expected<dds_entity_t> raw_participant(std::uint32_t domain) {
  const dds_entity_t participant = dds_create_participant(domain, nullptr, nullptr);
  if (participant < 0) return refused(participant, fmt::format("create participant in domain {}", domain));
  return participant;
}

dds_qos_t* raw_qos() {
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
  dds_qset_durability(qos, DDS_DURABILITY_VOLATILE);
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 10);
  const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(qos, 1, &xcdr1);
  return qos;
}

Expected<dds_entity_t> raw_reader(dds_entity_t participant, const dds_topic_descriptor_t& descriptor,
                                  const std::string& dds_name) {
  auto topic = raw_topic(participant, descriptor, dds_name);
  if (!topic) return topic;
  dds_qos_t* qos = raw_qos();
  const dds_entity_t reader = dds_create_reader(participant, *topic, qos, nullptr);
  dds_delete_qos(qos);
  if (reader < 0) return refused(reader, fmt::format("create reader on {}", dds_name));
  return reader;
}

Expected<dds_entity_t> raw_writer(dds_entity_t participant, const dds_topic_descriptor_t& descriptor,
                                  const std::string& dds_name) {
  auto topic = raw_topic(participant, descriptor, dds_name);
  if (!topic) return topic;
  dds_qos_t* qos = raw_qos();
  const dds_entity_t writer = dds_create_writer(participant, *topic, qos, nullptr);
  dds_delete_qos(qos);
  if (writer < 0) return refused(writer, fmt::format("create writer on {}", dds_name));
  return writer;
}

Expected<dds_entity_t> raw_waitset(dds_entity_t participant, dds_entity_t reader) {
  const dds_entity_t condition = dds_create_readcondition(reader, DDS_ANY_STATE);
  if (condition < 0) return refused(condition, "create read condition");
  const dds_entity_t waitset = dds_create_waitset(participant);
  if (waitset < 0) return refused(waitset, "create waitset");
  if (const dds_return_t rc = dds_waitset_attach(waitset, condition, reader); rc < 0)
    return refused(rc, "attach read condition");
  return waitset;
}

bool wait_for_readers(dds_entity_t writer, std::uint32_t count, double timeout_s) {
  const double deadline = mono_now() + timeout_s;
  while (mono_now() < deadline) {
    dds_publication_matched_status_t status{};
    if (dds_get_publication_matched_status(writer, &status) >= 0 && status.current_count >= count)
      return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return false;
}

double mono_now() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

}  // namespace hubrt::bench
