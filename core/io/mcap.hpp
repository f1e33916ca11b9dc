// A minimal MCAP writer (mcap.dev specification, major version 0): header, schemas and channels, each
// message in its own uncompressed chunk followed by its message index, then the summary (schemas, channels,
// statistics, chunk indexes), the summary offsets and the footer. Written streaming and atomically.
#pragma once
#include "core/io/output.hpp"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace sonarsim {

/// CRC-32 (ISO-HDLC, as zlib computes it) of `n` bytes, continuing from `crc` (0 to start).
std::uint32_t crc32(const void* data, size_t n, std::uint32_t crc = 0);

class McapWriter {
  public:
    /// Starts `path` (a temporary until finish()) with the magic and a Header record.
    McapWriter(const std::string& path, const std::string& profile, const std::string& library);
    /// Returns the schema id (1, 2, ...).
    std::uint16_t add_schema(const std::string& name, const std::string& encoding, const std::string& data);
    /// Returns the channel id (0, 1, ...).
    std::uint16_t add_channel(std::uint16_t schema_id, const std::string& topic, const std::string& encoding,
                              const std::map<std::string, std::string>& metadata);
    /// One message, times in ns; publish time = log time.
    void add_message(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time_ns,
                     const Bytes& data);
    /// Writes the data end, summary, summary offsets, footer and magic, then renames the file into place.
    void finish();

  private:
    struct ChunkInfo {
        std::uint64_t time_ns, start, length, index_start, index_length, records_size;
        std::uint16_t channel;
    };
    void record(std::uint8_t op, const Bytes& content);
    AtomicFile file_;
    std::vector<Bytes> schemas_, channels_; ///< their record contents, repeated in the summary
    std::vector<ChunkInfo> chunks_;
    std::map<std::uint16_t, std::uint64_t> channel_counts_;
};

} // namespace sonarsim
