// Why a pool: Cyclone 0.10.2's dds_write serialises each sample into a fresh serdata
// (src/core/ddsi/src/ddsi_serdata_default.c, serdata_default_from_sample_cdr_common): it starts a
// block of 128 bytes (serdata_default_new, DEFAULT_NEW_SIZE) from its freelist, grows it with
// ddsrt_realloc while serialising (dds_ostream_grow in ddsi_cdrstream.c), and serdata_default_free
// puts only blocks of at most 256 bytes (MAX_SIZE_FOR_POOL) back on the freelist: a malloc and a
// realloc per write of any hub State. dds_writecdr (src/core/ddsc/src/dds_write.c ->
// dds_writecdr_impl_common -> convert_serdata) takes a serdata as it is when its type is the
// writer's sertype, and Cyclone reaches a serdata only through its `ops` (ddsi_serdata.h): so the
// blocks here are serdata of the writer's sertype with ops of our own whose free returns them to
// this pool. The bytes are Cyclone's own serialiser's (dds_stream_write_sample, exported in
// ddsi_cdrstream.h), laid out as serdata_default lays them out.
#include "serdata_pool.h"

#include <atomic>
#include <cstdio>
#include <cstring>
#include <new>

#include <dds/ddsi/ddsi_cdrstream.h>
#include <dds/ddsi/ddsi_tkmap.h>
#include <dds/ddsi/q_protocol.h>
#include <dds/ddsrt/heap.h>

#include "instance_map.h"

namespace hubrt::dds::detail {
namespace {

// A block's buffer: 4 unused bytes, the 4-byte encoding header, then the data. The data starts at
// an index that is a multiple of 8 because the stream aligns relative to its index, as Cyclone's
// own serdata does (its data member is at a multiple of 8: ddsi_cdrstream.c,
// DDSRT_STATIC_ASSERT on offsetof (struct ddsi_serdata_default, data)).
constexpr std::uint32_t kHeaderOffset = 4;
constexpr std::uint32_t kDataOffset = 8;
constexpr std::uint32_t kHeaderSize = 4;
// First size of a block's buffer (a multiple of 4, so that padding never outgrows it); a larger
// sample makes Cyclone's stream grow it in 4 KiB steps, once.
constexpr std::uint32_t kInitialCapacity = 512;

}  // namespace

struct SerdataPool::Block {
  ddsi_serdata c;  // first: what Cyclone sees (a Block* is a ddsi_serdata*)
  SerdataPool* pool;
  Block* next;             // in the pool's free list
  unsigned char* buffer;   // from ddsrt_malloc, as Cyclone's stream reallocs it
  std::uint32_t capacity;  // bytes in buffer
  std::uint32_t size;      // serialised bytes, encoding header included (ddsi_serdata_size)
};

namespace {
SerdataPool::Block* block_of(const ddsi_serdata* d) noexcept {
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-const-cast): Cyclone's ops take const serdata
  return reinterpret_cast<SerdataPool::Block*>(const_cast<ddsi_serdata*>(d));
}
}  // namespace

SerdataPool* SerdataPool::create(const ddsi_sertype* sertype, dds_entity_t writer) {
  // The pool and its blocks live by counts Cyclone's C API keeps (a serdata's refcount, the
  // writer's release), so they are made and deleted by hand, never owned by a C++ object.
  auto* pool = new SerdataPool(sertype, writer);  // NOLINT(cppcoreguidelines-owning-memory)
  pool->register_instance();
  return pool;
}

SerdataPool::SerdataPool(const ddsi_sertype* sertype, dds_entity_t writer)
    : sertype_(reinterpret_cast<ddsi_sertype_default*>(ddsi_sertype_ref(sertype))), writer_(writer) {}

// Every write looks its serdata's instance up in the domain's key-to-instance map
// (dds_write.c, deliver_data_any -> ddsi_tkmap_lookup_instance_ref), which creates the entry
// (allocating) when nobody holds it and drops it again after the write when no reader or history
// holds it. dds_register_instance would hold one, but for a serdata of the sertype's own ops,
// which the map does not take as the same instance as ours (ddsi_tkmap.c, dds_tk_equals compares
// ops). So the pool holds the entry itself, found through one of its own serdata, as
// dds_register_instance does (dds_instance.c: the thread made awake around the map calls).
void SerdataPool::register_instance() noexcept {
  ddsi_serdata* key = serialize_key();
  if (key == nullptr) return;
  instance_ = hubrt_dds_instance_ref(&sertype_->c, key);
  ddsi_serdata_unref(key);
}

void SerdataPool::unregister_instance() noexcept {
  // Only while the writer exists: once its participant is deleted the domain may be gone, and
  // its map with it (which then freed the entry).
  if (instance_ == nullptr || dds_get_parent(writer_) <= 0) return;
  hubrt_dds_instance_unref(&sertype_->c, instance_);
  instance_ = nullptr;
}

SerdataPool::~SerdataPool() {
  while (free_ != nullptr) {
    Block* block = free_;
    free_ = block->next;
    ddsrt_free(block->buffer);
    delete block;  // NOLINT(cppcoreguidelines-owning-memory): see create()
  }
  ddsi_sertype_unref(&sertype_->c);
}

void SerdataPool::release() noexcept {
  unregister_instance();
  bool last = false;
  {
    const std::lock_guard lock(mutex_);
    released_ = true;
    last = outstanding_ == 0;
  }
  if (last) delete this;  // NOLINT(cppcoreguidelines-owning-memory): see create()
}

std::size_t SerdataPool::blocks() const noexcept {
  const std::lock_guard lock(mutex_);
  return blocks_;
}

SerdataPool::Block* SerdataPool::take_free_block() noexcept {
  const std::lock_guard lock(mutex_);
  Block* block = free_;
  if (block != nullptr) {
    free_ = block->next;
  } else {
    block = new (std::nothrow) Block{};  // NOLINT(cppcoreguidelines-owning-memory): see create()
    if (block == nullptr) return nullptr;
    block->buffer = static_cast<unsigned char*>(ddsrt_malloc(kInitialCapacity));
    if (block->buffer == nullptr) {
      delete block;  // NOLINT(cppcoreguidelines-owning-memory): see create()
      return nullptr;
    }
    block->capacity = kInitialCapacity;
    block->pool = this;
    ++blocks_;
  }
  ++outstanding_;
  return block;
}

void SerdataPool::give_back(Block* block) noexcept {
  bool last = false;
  {
    const std::lock_guard lock(mutex_);
    block->next = free_;
    free_ = block;
    --outstanding_;
    last = released_ && outstanding_ == 0;
  }
  if (last) delete this;  // NOLINT(cppcoreguidelines-owning-memory): see create()
}

ddsi_serdata* SerdataPool::serialize_key() noexcept {
  Block* block = take_free_block();
  if (block == nullptr) return nullptr;
  ddsi_serdata_init(&block->c, &sertype_->c, SDK_KEY);
  block->c.ops = &pooled_ops();
  block->c.hash = sertype_->c.serdata_basehash;
  const std::uint16_t identifier =
      ddsi_sertype_get_native_enc_identifier(CDR_ENC_VERSION_1, sertype_->encoding_format);
  std::memcpy(block->buffer + kHeaderOffset, &identifier, sizeof identifier);
  block->buffer[kHeaderOffset + 2] = 0;
  block->buffer[kHeaderOffset + 3] = 0;
  block->size = kHeaderSize;
  return &block->c;
}

ddsi_serdata* SerdataPool::serialize(const void* sample) noexcept {
  Block* block = take_free_block();
  if (block == nullptr) return nullptr;
  ddsi_serdata_init(&block->c, &sertype_->c, SDK_DATA);  // one reference, timestamps unset
  block->c.ops = &pooled_ops();
  // A keyless topic has one instance: Cyclone's own serdata carries the type's base hash
  // (ddsi_serdata_default.c, fix_serdata_default_nokey), which finds the registered instance.
  block->c.hash = sertype_->c.serdata_basehash;

  dds_ostream_t os{};
  os.m_buffer = block->buffer;
  os.m_size = block->capacity;
  os.m_index = kDataOffset;
  os.m_xcdr_version = CDR_ENC_VERSION_1;
  const bool ok = dds_stream_write_sample(&os, sample, sertype_);
  block->buffer = os.m_buffer;  // the stream may have grown it (ddsrt_realloc)
  block->capacity = os.m_size;
  block->size = kHeaderSize;
  if (!ok) {
    ddsi_serdata_unref(&block->c);  // back to the pool through op_free
    return nullptr;
  }
  // DDSI wants the payload padded to 4 bytes, the pad count in the options' last 2 bits
  // (ddsi_cdrstream.c, dds_ostream_add_to_serdata_default); capacity is a multiple of 4, so the
  // padding fits.
  const std::uint32_t length = os.m_index - kDataOffset;
  const std::uint32_t pad = (4 - length % 4) % 4;
  std::memset(block->buffer + os.m_index, 0, pad);
  const std::uint16_t identifier =
      ddsi_sertype_get_native_enc_identifier(CDR_ENC_VERSION_1, sertype_->encoding_format);
  std::memcpy(block->buffer + kHeaderOffset, &identifier, sizeof identifier);
  block->buffer[kHeaderOffset + 2] = 0;  // options, big-endian: padding count
  block->buffer[kHeaderOffset + 3] = static_cast<unsigned char>(pad);
  block->size = kHeaderSize + length + pad;
  return &block->c;
}

const ddsi_serdata_ops& SerdataPool::pooled_ops() noexcept {
  static const ddsi_serdata_ops ops = [] {
    // Creating serdata (from_ser, from_keyhash, from_sample, from_iox_buffer) goes through the
    // sertype, so those stay Cyclone's XCDR1 keyless ones.
    ddsi_serdata_ops table = ddsi_serdata_ops_cdr_nokey;
    table.eqkey = &op_eqkey;
    table.get_size = &op_get_size;
    table.to_ser = &op_to_ser;
    table.to_ser_ref = &op_to_ser_ref;
    table.to_ser_unref = &op_to_ser_unref;
    table.to_sample = &op_to_sample;
    table.to_untyped = &op_to_untyped;
    table.untyped_to_sample = &op_untyped_to_sample;
    table.free = &op_free;
    table.print = &op_print;
    table.get_keyhash = &op_get_keyhash;
    return table;
  }();
  return ops;
}

std::uint32_t SerdataPool::op_get_size(const ddsi_serdata* d) {
  return block_of(d)->size;
}

// Keyless: every sample is the same instance (serdata_default_eqkey_nokey).
bool SerdataPool::op_eqkey(const ddsi_serdata* /*a*/, const ddsi_serdata* /*b*/) {
  return true;
}

void SerdataPool::op_free(ddsi_serdata* d) {
  // The last reference is gone: ddsi_serdata_unref took the count to 0 with a full barrier, but
  // when a thread of Debian's uninstrumented libddsc was the last, ThreadSanitizer saw none of it.
  // This acquire load orders every earlier unref (ours in hubrt code, on the same atomic) before
  // the block is reused or its pool freed, as the reference-count idiom needs, and lets TSan see
  // it (StationTapTest: the tap's unref, then Cyclone's gc thread freeing the pool, was reported).
  static_cast<void>(std::atomic_ref<std::uint32_t>(d->refc.v).load(std::memory_order_acquire));
  Block* block = block_of(d);
  block->pool->give_back(block);
}

// 0 <= off < off + sz <= alignup4(size): the header and data are contiguous in the buffer.
void SerdataPool::op_to_ser(const ddsi_serdata* d, std::size_t off, std::size_t sz, void* buf) {
  std::memcpy(buf, block_of(d)->buffer + kHeaderOffset + off, sz);
}

ddsi_serdata* SerdataPool::op_to_ser_ref(const ddsi_serdata* d, std::size_t off, std::size_t sz,
                                         ddsrt_iovec_t* ref) {
  ref->iov_base = block_of(d)->buffer + kHeaderOffset + off;
  ref->iov_len = static_cast<ddsrt_iov_len_t>(sz);
  return ddsi_serdata_ref(d);
}

void SerdataPool::op_to_ser_unref(ddsi_serdata* d, const ddsrt_iovec_t* /*ref*/) {
  ddsi_serdata_unref(d);
}

namespace {
dds_istream_t istream_of(const SerdataPool::Block& block) noexcept {
  dds_istream_t is{};
  dds_istream_init(&is, kDataOffset + block.size - kHeaderSize, block.buffer, CDR_ENC_VERSION_1);
  is.m_index = kDataOffset;
  return is;
}
}  // namespace

// For a reader in this process of the same sertype (Cyclone hands it this serdata): Cyclone's
// own deserialiser, as serdata_default_to_sample_cdr. Like it, no caller-provided buffer.
bool SerdataPool::op_to_sample(const ddsi_serdata* d, void* sample, void** bufptr, void* /*buflim*/) {
  if (bufptr != nullptr) return false;
  if (d->kind != SDK_DATA) return true;  // a keyless type's key has no fields to fill
  const Block& block = *block_of(d);
  dds_istream_t is = istream_of(block);
  dds_stream_read_sample(&is, sample, block.pool->sertype_);
  return true;
}

// The instance's key for Cyclone's key-to-instance map, as serdata_default_to_untyped makes it (no
// type, kind key, the sample's hash) but of our ops, so that the map finds the instance again
// for every serdata of ours. A keyless type's key is empty.
ddsi_serdata* SerdataPool::op_to_untyped(const ddsi_serdata* d) {
  SerdataPool& pool = *block_of(d)->pool;
  ddsi_serdata* key = pool.serialize_key();
  if (key == nullptr) return nullptr;
  key->type = nullptr;
  key->hash = d->hash;
  return key;
}

// A keyless type's untyped key fills nothing (serdata_default_untyped_to_sample_cdr_nokey).
bool SerdataPool::op_untyped_to_sample(const ddsi_sertype* /*type*/, const ddsi_serdata* /*d*/,
                                       void* /*sample*/, void** /*bufptr*/, void* /*buflim*/) {
  return true;
}

std::size_t SerdataPool::op_print(const ddsi_sertype* /*type*/, const ddsi_serdata* d, char* buf,
                                  std::size_t size) {
  if (d->kind != SDK_DATA) return static_cast<std::size_t>(std::snprintf(buf, size, "{}"));
  const Block& block = *block_of(d);
  dds_istream_t is = istream_of(block);
  return dds_stream_print_sample(&is, block.pool->sertype_, buf, size);
}

// A keyless type's key is empty: its keyhash is 16 zero bytes, or the MD5 of nothing when MD5 is
// forced (serdata_default_get_keyhash with a key of size 0).
void SerdataPool::op_get_keyhash(const ddsi_serdata* /*d*/, ddsi_keyhash* buf, bool force_md5) {
  static constexpr unsigned char kMd5OfNothing[16] = {0xd4, 0x1d, 0x8c, 0xd9, 0x8f, 0x00, 0xb2, 0x04,
                                                      0xe9, 0x80, 0x09, 0x98, 0xec, 0xf8, 0x42, 0x7e};
  if (force_md5) {
    std::memcpy(buf->value, kMd5OfNothing, sizeof kMd5OfNothing);
  } else {
    std::memset(buf->value, 0, sizeof buf->value);
  }
}

}  // namespace hubrt::dds::detail
