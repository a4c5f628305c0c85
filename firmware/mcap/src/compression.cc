#include "hubrt/mcap/compression.h"

#include <zstd.h>

#include <fmt/format.h>
#include <lz4frame.h>

namespace hubrt::mcap {

std::string_view compression_name(Compression compression) noexcept {
  switch (compression) {
    case Compression::kZstd:
      return "zstd";
    case Compression::kLz4:
      return "lz4";
    case Compression::kNone:
      break;
  }
  return "";
}

std::optional<Compression> compression_from_name(std::string_view name) noexcept {
  if (name.empty()) return Compression::kNone;
  if (name == "zstd") return Compression::kZstd;
  if (name == "lz4") return Compression::kLz4;
  return std::nullopt;
}

struct Compressor::Contexts {
  ZSTD_CCtx* zstd = nullptr;
  ~Contexts() { ZSTD_freeCCtx(zstd); }
};

Compressor::Compressor(Compression compression)
    : compression_(compression), contexts_(std::make_unique<Contexts>()) {}
Compressor::~Compressor() = default;
Compressor::Compressor(Compressor&&) noexcept = default;
Compressor& Compressor::operator=(Compressor&&) noexcept = default;

Expected<void> Compressor::compress(Bytes in, std::vector<std::uint8_t>& out) {
  switch (compression_) {
    case Compression::kNone:
      out.assign(in.begin(), in.end());
      return {};
    case Compression::kZstd: {
      if (contexts_->zstd == nullptr) contexts_->zstd = ZSTD_createCCtx();
      if (contexts_->zstd == nullptr) return make_error(ErrorCode::kInternal, "zstd: no compression context");
      out.resize(ZSTD_compressBound(in.size()));
      // Level 3, zstd's default: about 4x on hub States at a few hundred MB/s per core.
      const std::size_t n = ZSTD_compressCCtx(contexts_->zstd, out.data(), out.size(), in.data(), in.size(),
                                              ZSTD_CLEVEL_DEFAULT);
      if (ZSTD_isError(n) != 0U)
        return make_error(ErrorCode::kInternal, fmt::format("zstd: {}", ZSTD_getErrorName(n)));
      out.resize(n);
      return {};
    }
    case Compression::kLz4: {
      LZ4F_preferences_t preferences{};
      preferences.frameInfo.contentSize = in.size();  // lets a reader check the size up front
      out.resize(LZ4F_compressFrameBound(in.size(), &preferences));
      const std::size_t n = LZ4F_compressFrame(out.data(), out.size(), in.data(), in.size(), &preferences);
      if (LZ4F_isError(n) != 0U)
        return make_error(ErrorCode::kInternal, fmt::format("lz4: {}", LZ4F_getErrorName(n)));
      out.resize(n);
      return {};
    }
  }
  return make_error(ErrorCode::kInternal, "unknown compression");
}

namespace {

Expected<void> decompress_zstd(Bytes in, std::vector<std::uint8_t>& out) {
  const std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> context(ZSTD_createDCtx(), &ZSTD_freeDCtx);
  if (!context) return make_error(ErrorCode::kInternal, "zstd: no decompression context");
  // A frame may ask for a window of up to 2^27 bytes by default (ZSTD_WINDOWLOG_LIMIT_DEFAULT):
  // more than any chunk needs; a hostile frame cannot make zstd allocate beyond that.
  const std::size_t n = ZSTD_decompressDCtx(context.get(), out.data(), out.size(), in.data(), in.size());
  if (ZSTD_isError(n) != 0U)
    return make_error(ErrorCode::kProtocol, fmt::format("zstd: {}", ZSTD_getErrorName(n)));
  if (n != out.size()) {
    return make_error(ErrorCode::kProtocol,
                      fmt::format("zstd: {} byte(s) decompressed, the chunk says {}", n, out.size()));
  }
  return {};
}

Expected<void> decompress_lz4(Bytes in, std::vector<std::uint8_t>& out) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION)) != 0U)
    return make_error(ErrorCode::kInternal, "lz4: no decompression context");
  const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> context(
      raw, &LZ4F_freeDecompressionContext);
  std::size_t in_pos = 0;
  std::size_t out_pos = 0;
  std::size_t hint = 1;
  // Each call consumes input and fills output as far as it can; 0 means the frame ended.
  while (hint != 0 && in_pos < in.size()) {
    std::size_t out_size = out.size() - out_pos;
    std::size_t in_size = in.size() - in_pos;
    hint = LZ4F_decompress(context.get(), out.data() + out_pos, &out_size, in.data() + in_pos, &in_size,
                           nullptr);
    if (LZ4F_isError(hint) != 0U)
      return make_error(ErrorCode::kProtocol, fmt::format("lz4: {}", LZ4F_getErrorName(hint)));
    in_pos += in_size;
    out_pos += out_size;
    if (in_size == 0 && out_size == 0) break;  // no progress: output full with more to come
  }
  if (hint != 0)
    return make_error(ErrorCode::kProtocol, "lz4: the frame is cut short or larger than the chunk says");
  if (out_pos != out.size()) {
    return make_error(ErrorCode::kProtocol,
                      fmt::format("lz4: {} byte(s) decompressed, the chunk says {}", out_pos, out.size()));
  }
  return {};
}

}  // namespace

Expected<void> decompress(Compression compression, Bytes in, std::uint64_t uncompressed_size,
                          std::uint64_t max_size, std::vector<std::uint8_t>& out) {
  if (uncompressed_size > max_size) {
    return make_error(ErrorCode::kOutOfRange,
                      fmt::format("a chunk of {} bytes uncompressed, more than the {} allowed",
                                  uncompressed_size, max_size));
  }
  if (compression == Compression::kNone) {
    if (in.size() != uncompressed_size) {
      return make_error(
          ErrorCode::kProtocol,
          fmt::format("an uncompressed chunk of {} byte(s) says it has {}", in.size(), uncompressed_size));
    }
    out.assign(in.begin(), in.end());
    return {};
  }
  out.assign(static_cast<std::size_t>(uncompressed_size), 0);
  return compression == Compression::kZstd ? decompress_zstd(in, out) : decompress_lz4(in, out);
}

}  // namespace hubrt::mcap
