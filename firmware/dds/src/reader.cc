#include "hubrt/dds/reader.h"

#include <dds/ddsi/ddsi_serdata.h>

#include "hubrt/dds/retcode.h"

#include "listener.h"
#include "matched_count.h"

namespace hubrt::dds {
namespace {

// Runs on a Cyclone thread; the callback's contract (no blocking, no throwing) is documented at
// DataAvailableCallback. noexcept turns a broken contract into a clear terminate.
void invoke_data_available(dds_entity_t /*reader*/, void* arg) noexcept {
  (*static_cast<DataAvailableCallback*>(arg))();
}

}  // namespace

Expected<UntypedReader> UntypedReader::create(const Participant& participant, const UntypedTopic& topic,
                                              const Qos& qos, DataAvailableCallback on_data_available) {
  std::unique_ptr<DataAvailableCallback> callback;
  detail::ListenerPtr listener;
  if (on_data_available) {
    callback = std::make_unique<DataAvailableCallback>(std::move(on_data_available));
    listener.reset(dds_create_listener(callback.get()));
    dds_lset_data_available(listener.get(), &invoke_data_available);
  }
  // Cyclone copies the listener, so ours can go when this returns.
  const dds_entity_t handle =
      dds_create_reader(participant.handle(), topic.handle(), qos.get(), listener.get());
  if (handle < 0) {
    return dds_error(
        handle, "create reader on '" + topic.dds_name() + "' in domain " + std::to_string(topic.domain_id()));
  }
  return UntypedReader(std::move(callback), EntityHandle(handle), topic.dds_name(), topic.descriptor());
}

Result<bool> UntypedReader::take_next(void* sample, SampleInfo* info) noexcept {
  if (hook_ != nullptr) return take_next_shown(sample, info);
  for (;;) {
    // A non-null buf[0] makes Cyclone deserialise into the caller's sample, reusing its buffers,
    // instead of loaning one of its own.
    void* buffers[1] = {sample};
    dds_sample_info_t sample_info;
    const dds_return_t n = dds_take(handle_.get(), buffers, &sample_info, 1, 1);
    if (n < 0) return to_status(n);
    if (n == 0) return false;
    if (!sample_info.valid_data) continue;
    if (info != nullptr) {
      info->source_time = WallTime{sample_info.source_timestamp};
      info->publication_handle = sample_info.publication_handle;
    }
    return true;
  }
}

// take_next with the hook: dds_takecdr hands over the received serdata (a reference, no copy), the
// hook sees its bytes (ddsi_serdata_to_ser_ref: in place), ddsi_serdata_to_sample deserialises it
// into the caller's sample reusing its buffers — what dds_take does with a non-null buf[0] (Cyclone
// 0.10.2 dds_rhc_default.c, take_w_qminv -> ddsi_serdata_to_sample) — and the reference goes back.
Result<bool> UntypedReader::take_next_shown(void* sample, SampleInfo* info) noexcept {
  for (;;) {
    struct ddsi_serdata* serdata = nullptr;
    dds_sample_info_t sample_info;
    const dds_return_t n = dds_takecdr(handle_.get(), &serdata, 1, &sample_info, DDS_ANY_STATE);
    if (n < 0) return to_status(n);
    if (n == 0) return false;
    if (!sample_info.valid_data || serdata == nullptr) {
      if (serdata != nullptr) ddsi_serdata_unref(serdata);
      continue;
    }
    const std::uint32_t size = ddsi_serdata_size(serdata);
    ddsrt_iovec_t ref;
    struct ddsi_serdata* held = ddsi_serdata_to_ser_ref(serdata, 0, size, &ref);
    hook_->on_sample({static_cast<const std::uint8_t*>(ref.iov_base), static_cast<std::size_t>(ref.iov_len)},
                     WallTime{sample_info.source_timestamp});
    ddsi_serdata_to_ser_unref(held, &ref);
    const bool read = ddsi_serdata_to_sample(serdata, sample, nullptr, nullptr);
    ddsi_serdata_unref(serdata);
    if (!read) return Status(ErrorCode::kInvalidArgument);
    if (info != nullptr) {
      info->source_time = WallTime{sample_info.source_timestamp};
      info->publication_handle = sample_info.publication_handle;
    }
    return true;
  }
}

Result<bool> UntypedReader::take_serialized(std::vector<std::uint8_t>& out, SampleInfo* info) {
  for (;;) {
    struct ddsi_serdata* serdata = nullptr;
    dds_sample_info_t sample_info;
    const dds_return_t n = dds_takecdr(handle_.get(), &serdata, 1, &sample_info, DDS_ANY_STATE);
    if (n < 0) return to_status(n);
    if (n == 0) return false;
    // Ours now: one reference, whatever happens below.
    const std::unique_ptr<ddsi_serdata, decltype(&ddsi_serdata_unref)> owned(serdata, &ddsi_serdata_unref);
    if (!sample_info.valid_data || serdata == nullptr) continue;
    const std::uint32_t size = ddsi_serdata_size(serdata);
    out.resize(size);
    ddsi_serdata_to_ser(serdata, 0, size, out.data());
    if (info != nullptr) {
      info->source_time = WallTime{sample_info.source_timestamp};
      info->publication_handle = sample_info.publication_handle;
    }
    return true;
  }
}

Result<std::uint32_t> UntypedReader::matched_writers() const noexcept {
  return detail::matched_count(handle_.get(), detail::EndpointKind::kReader);
}

Expected<void> UntypedReader::wait_for_writers(std::uint32_t count, Duration timeout) const {
  return detail::wait_for_matched(handle_.get(), detail::EndpointKind::kReader, count, timeout,
                                  "wait for writers of reader on '" + topic_name_ + "'");
}

}  // namespace hubrt::dds
