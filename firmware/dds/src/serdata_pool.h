// A writer's pool of serialised samples, handed to Cyclone with dds_writecdr() so that a write in
// steady state allocates nothing (Cyclone 0.10's own dds_write allocates twice per sample over
// 256 serialised bytes: see serdata_pool.cc).
#pragma once

#include <cstddef>
#include <cstdint>
#include <mutex>

#include <dds/dds.h>
#include <dds/ddsi/ddsi_serdata.h>
#include <dds/ddsi/ddsi_serdata_default.h>
#include <dds/ddsi/ddsi_tkmap.h>

namespace hubrt::dds::detail {

// Serialises samples of one keyless type, XCDR1, into blocks it keeps and reuses, as serdata of
// the writer's own sertype (so that dds_writecdr takes them as they are: dds_write.c,
// convert_serdata). Cyclone holds a serdata as long as it needs it (writer history until
// acknowledged, transmit queue, a local reader's history) and gives it back through its ops'
// free; the pool then keeps it for the next write.
//
// Lifetime: create() returns the pool with one owner reference; release() drops it. The pool
// deletes itself once released and every serdata it handed out has come back (a local reader may
// hold the last State beyond the writer's life).
// Thread-safety: serialize() from one thread at a time (the writer's); the serdatas' free runs on
// any Cyclone thread (mutex).
class SerdataPool {
 public:
  // Precondition: `sertype` is Cyclone's default sertype of a keyless topic type
  // (ddsi_sertype_default, as dds_create_topic makes one) whose writers write XCDR1. Takes a
  // reference on it (ddsi_sertype_ref). Allocates.
  // Registers the topic's one instance in Cyclone's key-to-instance map through a serdata of the
  // pool (see register_instance in serdata_pool.cc) and holds it for the writer's life.
  static SerdataPool* create(const ddsi_sertype* sertype, dds_entity_t writer);
  SerdataPool(const SerdataPool&) = delete;
  SerdataPool& operator=(const SerdataPool&) = delete;

  // Drops the owner's reference and the instance registration (while `writer` still exists, i.e.
  // before it is deleted). The pointer must not be used afterwards.
  void release() noexcept;

  // A serdata (kind SDK_DATA, one reference: the caller's, which dds_writecdr consumes) holding
  // `sample` serialised exactly as Cyclone's dds_write would (dds_stream_write_sample, the same
  // 4-byte encoding header and padding), or nullptr when the sample does not serialise (e.g. an
  // enum out of range). Allocates only when every block is in use by Cyclone (a new one) or when
  // a sample is larger than its block has ever been (Cyclone's stream grows it by realloc, in 4 KiB
  // steps: ddsi_cdrstream.c, dds_ostream_grow); the pool keeps both.
  ddsi_serdata* serialize(const void* sample) noexcept;

  // Blocks made so far (handed out or free); for tests and benchmarks.
  [[nodiscard]] std::size_t blocks() const noexcept;

  // The writer's sertype (UntypedWriter::write_serialized makes serdata of it).
  [[nodiscard]] const ddsi_sertype* sertype() const noexcept { return &sertype_->c; }

  // One serialised sample and its buffer (serdata_pool.cc); public for the ops' helpers only.
  struct Block;

 private:
  SerdataPool(const ddsi_sertype* sertype, dds_entity_t writer);
  ~SerdataPool();

  void register_instance() noexcept;
  void unregister_instance() noexcept;

  Block* take_free_block() noexcept;
  ddsi_serdata* serialize_key() noexcept;  // an empty key serdata of ours (kind SDK_KEY)
  void give_back(Block* block) noexcept;

  // The serdata ops of every block of every pool (a serdata finds its ops through its own `ops`,
  // not through its sertype's: ddsi_serdata.h). One table for the process, because Cyclone's
  // key-to-instance map takes two serdata for the same instance only when their ops are the same
  // (ddsi_tkmap.c, dds_tk_equals): two writers of one topic write one instance.
  static const ddsi_serdata_ops& pooled_ops() noexcept;
  static bool op_untyped_to_sample(const ddsi_sertype* type, const ddsi_serdata* d, void* sample,
                                   void** bufptr, void* buflim);
  static std::uint32_t op_get_size(const ddsi_serdata* d);
  static bool op_eqkey(const ddsi_serdata* a, const ddsi_serdata* b);
  static void op_free(ddsi_serdata* d);
  static void op_to_ser(const ddsi_serdata* d, std::size_t off, std::size_t sz, void* buf);
  static ddsi_serdata* op_to_ser_ref(const ddsi_serdata* d, std::size_t off, std::size_t sz,
                                     ddsrt_iovec_t* ref);
  static void op_to_ser_unref(ddsi_serdata* d, const ddsrt_iovec_t* ref);
  static bool op_to_sample(const ddsi_serdata* d, void* sample, void** bufptr, void* buflim);
  static ddsi_serdata* op_to_untyped(const ddsi_serdata* d);
  static std::size_t op_print(const ddsi_sertype* type, const ddsi_serdata* d, char* buf, std::size_t size);
  static void op_get_keyhash(const ddsi_serdata* d, ddsi_keyhash* buf, bool force_md5);

  ddsi_sertype_default* sertype_;  // referenced (ddsi_sertype_ref) for the pool's life
  dds_entity_t writer_;
  struct ddsi_tkmap_instance* instance_ = nullptr;  // our reference to the registered instance

  mutable std::mutex mutex_;
  Block* free_ = nullptr;        // guarded by mutex_
  std::size_t blocks_ = 0;       // guarded by mutex_
  std::size_t outstanding_ = 0;  // handed out, not yet back; guarded by mutex_
  bool released_ = false;        // guarded by mutex_
};

}  // namespace hubrt::dds::detail
