#include "hubrt/dds/writer.h"

#include <chrono>
#include <string>

#include "hubrt/dds/retcode.h"
#include "hubrt/dds/sample.h"

#include "listener.h"
#include "matched_count.h"
#include "serdata_pool.h"
#include "sertype_probe.h"

namespace hubrt::dds {

// Runs on Cyclone's discovery thread, under the writer's observer lock (dds_writer.c,
// dds_writer_status_cb -> status_cb_publication_matched in Cyclone 0.10): must not block.
// update_publication_matched() counts an added reader in total_count_change and a lost one only
// in current_count (and current_count_change, negative); the listener resets the *_change fields
// after each call (dds_lset_publication_matched: reset_on_invoke), so total_count_change is
// the number of readers added since the last call.
void UntypedWriter::on_publication_matched(dds_entity_t /*writer*/,
                                           const dds_publication_matched_status_t status,
                                           void* arg) noexcept {
  auto* matches = static_cast<MatchWatch*>(arg);
  matches->current_readers.store(status.current_count);
  if (status.total_count_change == 0) return;  // a reader went away
  matches->new_readers.fetch_add(status.total_count_change);
  if (matches->callback) matches->callback();
}

Expected<UntypedWriter> UntypedWriter::create(const Participant& participant, const UntypedTopic& topic,
                                              const Qos& qos, ReaderMatchedCallback on_reader_matched) {
  auto matches = std::make_unique<MatchWatch>();
  matches->callback = std::move(on_reader_matched);
  const detail::ListenerPtr listener(dds_create_listener(matches.get()));
  dds_lset_publication_matched(listener.get(), &UntypedWriter::on_publication_matched);
  // Cyclone copies the listener, so ours can go when this returns.
  const dds_entity_t handle =
      dds_create_writer(participant.handle(), topic.handle(), qos.get(), listener.get());
  if (handle < 0) {
    return dds_error(
        handle, "create writer on '" + topic.dds_name() + "' in domain " + std::to_string(topic.domain_id()));
  }
  UntypedWriter writer(std::move(matches), EntityHandle(handle), topic.dds_name(), &topic.descriptor());
  // A keyless topic has one instance. Registering it now keeps Cyclone's instance entry alive
  // for the writer's lifetime; otherwise, while no reader holds it, every write() creates and
  // garbage-collects it again (measured: about 3 heap allocations per write). The write pool
  // registers it through its own serdata (serdata_pool.cc, register_instance); without a pool,
  // dds_register_instance does.
  if (topic.descriptor().m_nkeys == 0) {
    // The write pool needs the topic's sertype (the writer's own: every hubrt QoS writes XCDR1,
    // which Cyclone derives no other sertype for, ddsi_sertype_default.c
    // sertype_default_derive_sertype). Without it the writer falls back to dds_write.
    if (const ddsi_sertype* sertype =
            detail::probe_topic_sertype(participant.handle(), topic.handle(), topic.descriptor())) {
      writer.pool_.reset(detail::SerdataPool::create(sertype, writer.handle()));
      return writer;
    }
    const UntypedSample any_sample(topic.descriptor());
    dds_instance_handle_t instance = 0;
    const dds_return_t rc = dds_register_instance(writer.handle(), &instance, any_sample.data());
    if (rc < 0) return dds_error(rc, "register the instance of keyless topic '" + topic.dds_name() + "'");
  }
  return writer;
}

// The block's bytes in place (the pool's to_ser_ref), before Cyclone holds the serdata.
void UntypedWriter::show_hook(ddsi_serdata* serdata, WallTime source_time) noexcept {
  if (hook_ == nullptr) return;
  const std::uint32_t size = ddsi_serdata_size(serdata);
  ddsrt_iovec_t ref;
  ddsi_serdata* held = ddsi_serdata_to_ser_ref(serdata, 0, size, &ref);
  hook_->on_sample({static_cast<const std::uint8_t*>(ref.iov_base), static_cast<std::size_t>(ref.iov_len)},
                   source_time);
  ddsi_serdata_to_ser_unref(held, &ref);
}

void UntypedWriter::PoolRelease::operator()(detail::SerdataPool* pool) const noexcept {
  pool->release();
}

Status UntypedWriter::write(const void* sample) noexcept {
  if (pool_ == nullptr || sample == nullptr) return to_status(dds_write(handle_.get(), sample));
  ddsi_serdata* serdata = pool_->serialize(sample);
  if (serdata == nullptr) return to_status(DDS_RETCODE_BAD_PARAMETER);  // as dds_write's from_sample
  show_hook(serdata, WallTime{});
  const dds_return_t rc = dds_writecdr(handle_.get(), serdata);
  // dds_writecdr consumes the serdata's reference once it has locked the writer; when it cannot
  // (a deleted or wrong handle: dds_write.c, dds_writer_lock) it returns with the reference ours.
  if (rc == DDS_RETCODE_BAD_PARAMETER || rc == DDS_RETCODE_ALREADY_DELETED ||
      rc == DDS_RETCODE_ILLEGAL_OPERATION) {
    ddsi_serdata_unref(serdata);
  }
  return to_status(rc);
}

Status UntypedWriter::write(const void* sample, WallTime source_time) noexcept {
  if (source_time.ns_since_epoch < 0 || sample == nullptr) return to_status(DDS_RETCODE_BAD_PARAMETER);
  if (pool_ == nullptr) return to_status(dds_write_ts(handle_.get(), sample, source_time.ns_since_epoch));
  ddsi_serdata* serdata = pool_->serialize(sample);
  if (serdata == nullptr) return to_status(DDS_RETCODE_BAD_PARAMETER);
  // What dds_writecdr sets before dds_writecdr_impl, with our time in place of dds_time().
  serdata->statusinfo = 0;
  serdata->timestamp.v = source_time.ns_since_epoch;
  show_hook(serdata, source_time);
  const dds_return_t rc = dds_forwardcdr(handle_.get(), serdata);
  if (rc == DDS_RETCODE_BAD_PARAMETER || rc == DDS_RETCODE_ALREADY_DELETED ||
      rc == DDS_RETCODE_ILLEGAL_OPERATION) {
    ddsi_serdata_unref(serdata);
  }
  return to_status(rc);
}

Status UntypedWriter::write_serialized(std::span<const std::uint8_t> serialized) noexcept {
  if (pool_ == nullptr) return Status(ErrorCode::kFailedPrecondition);
  ddsrt_iovec_t iov;
  iov.iov_base = const_cast<std::uint8_t*>(serialized.data());  // read only (from_ser_iov copies)
  iov.iov_len = static_cast<ddsrt_iov_len_t>(serialized.size());
  ddsi_serdata* serdata = ddsi_serdata_from_ser_iov(pool_->sertype(), SDK_DATA, 1, &iov, serialized.size());
  if (serdata == nullptr) return Status(ErrorCode::kInvalidArgument);
  const dds_return_t rc = dds_writecdr(handle_.get(), serdata);
  if (rc == DDS_RETCODE_BAD_PARAMETER || rc == DDS_RETCODE_ALREADY_DELETED ||
      rc == DDS_RETCODE_ILLEGAL_OPERATION) {
    ddsi_serdata_unref(serdata);  // as in write(): not consumed when the writer could not be locked
  }
  return to_status(rc);
}

std::size_t UntypedWriter::pooled_blocks() const noexcept {
  return pool_ == nullptr ? 0 : pool_->blocks();
}

Result<std::uint32_t> UntypedWriter::matched_readers() const noexcept {
  return detail::matched_count(handle_.get(), detail::EndpointKind::kWriter);
}

Expected<void> UntypedWriter::wait_for_readers(std::uint32_t count, Duration timeout) const {
  return detail::wait_for_matched(handle_.get(), detail::EndpointKind::kWriter, count, timeout,
                                  "wait for readers of writer on '" + topic_name_ + "'");
}

Status UntypedWriter::announce() const {
  if (descriptor_->m_nkeys != 0) return Status(ErrorCode::kFailedPrecondition);
  dds_qos_t* qos = dds_create_qos();
  bool disposes = true;
  const dds_return_t got = dds_get_qos(handle_.get(), qos);
  if (got == DDS_RETCODE_OK) (void)dds_qget_writer_data_lifecycle(qos, &disposes);
  dds_delete_qos(qos);
  if (got != DDS_RETCODE_OK) return to_status(got);
  if (disposes) return Status(ErrorCode::kFailedPrecondition);
  // Keyless: every sample is the one instance, so a zeroed one names it.
  const UntypedSample any_sample(*descriptor_);
  return to_status(dds_unregister_instance(handle_.get(), any_sample.data()));
}

Expected<void> UntypedWriter::wait_for_acks(Duration timeout) const {
  // dds.h: dds_wait_for_acks "blocks the calling thread until either all data written by the
  // publisher or writer is acknowledged by all matched reliable reader entities, or else the
  // duration specified by the timeout parameter elapses" (DDS_RETCODE_TIMEOUT).
  const dds_return_t rc = dds_wait_for_acks(handle_.get(), timeout.count());
  if (rc == DDS_RETCODE_TIMEOUT) {
    const Result<std::uint32_t> matched = matched_readers();
    return make_error(
        ErrorCode::kTimeout,
        "wait for acknowledgements on '" + topic_name_ + "': not every one of the " +
            std::to_string(matched.is_ok() ? matched.value() : 0) +
            " matched reader(s) acknowledged within " +
            std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(timeout).count()) + " ms");
  }
  if (rc < 0) return dds_error(rc, "wait for acknowledgements on '" + topic_name_ + "'");
  return {};
}

}  // namespace hubrt::dds
