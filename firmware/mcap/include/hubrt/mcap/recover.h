// Making a whole file out of a cut-off one: every message of its whole chunks (and whole records
// outside chunks), written anew with their schemas and channels, chunk indexes and a summary.
// What `hubctl record --recover FILE` does for a recording whose writer died.
#pragma once

#include <cstdint>
#include <string>

#include "hubrt/base/status.h"
#include "hubrt/mcap/linear_reader.h"
#include "hubrt/mcap/writer.h"

namespace hubrt::mcap {

struct Recovered {
  std::uint64_t messages = 0;
  std::uint64_t chunks_read = 0;  // whole chunks of the input
  std::uint64_t bytes_kept = 0;   // of the input: up to the end of its last whole record
  std::uint64_t bytes_dropped = 0;
  ReadStop stop;  // where and why reading the input stopped
};

// Reads `input` as far as it is whole and writes what it holds to `output` (which must not exist;
// WriterOptions as given, the Header's profile and library carried over). Channel and schema ids
// may change; messages keep their order, times, sequence numbers and bytes.
// Errors: those of LinearReader::open for the input and of Writer for the output (the partial
// output is removed).
Expected<Recovered> recover(const std::string& input, const std::string& output, WriterOptions options = {});

}  // namespace hubrt::mcap
