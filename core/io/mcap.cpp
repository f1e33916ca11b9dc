#include "core/io/mcap.hpp"

#include "core/base/le_bytes.hpp"

#include <algorithm>
#include <zlib.h>

namespace sonarsim {
namespace {

constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', 0x30, '\r', '\n'};
enum Op : std::uint8_t {
    kHeader = 0x01,
    kFooter = 0x02,
    kSchema = 0x03,
    kChannel = 0x04,
    kMessage = 0x05,
    kChunk = 0x06,
    kMessageIndex = 0x07,
    kChunkIndex = 0x08,
    kStatistics = 0x0B,
    kSummaryOffset = 0x0E,
    kDataEnd = 0x0F
};

void append_string(le::Bytes& b, const std::string& s) {
    le::append<std::uint32_t>(b, std::uint32_t(s.size()));
    le::append_bytes(b, s);
}

/// <opcode><uint64 length><content>
le::Bytes framed(std::uint8_t op, const le::Bytes& content) {
    le::Bytes r{op};
    le::append<std::uint64_t>(r, content.size());
    r.insert(r.end(), content.begin(), content.end());
    return r;
}

} // namespace

std::uint32_t crc32(const void* data, size_t n, std::uint32_t crc) {
    // zlib's: a null buffer would give its initial value (0), not crc
    return n ? std::uint32_t(::crc32_z(crc, static_cast<const Bytef*>(data), n)) : crc;
}

McapWriter::McapWriter(const std::string& path, const std::string& profile, const std::string& library)
    : file_(path) {
    file_.write(kMagic, sizeof kMagic);
    le::Bytes h;
    append_string(h, profile);
    append_string(h, library);
    record(kHeader, h);
}

void McapWriter::record(std::uint8_t op, const Bytes& content) {
    file_.write(framed(op, content));
}

std::uint16_t McapWriter::add_schema(const std::string& name, const std::string& encoding,
                                     const std::string& data) {
    const auto id = std::uint16_t(schemas_.size() + 1);
    le::Bytes s;
    le::append<std::uint16_t>(s, id);
    append_string(s, name);
    append_string(s, encoding);
    append_string(s, data); // uint32 length-prefixed bytes
    record(kSchema, s);
    schemas_.push_back(std::move(s));
    return id;
}

std::uint16_t McapWriter::add_channel(std::uint16_t schema_id, const std::string& topic,
                                      const std::string& encoding,
                                      const std::map<std::string, std::string>& metadata) {
    const auto id = std::uint16_t(channels_.size());
    le::Bytes c;
    le::append<std::uint16_t>(c, id);
    le::append<std::uint16_t>(c, schema_id);
    append_string(c, topic);
    append_string(c, encoding);
    le::Bytes map;
    for (auto& [k, v] : metadata) append_string(map, k), append_string(map, v);
    le::append<std::uint32_t>(c, std::uint32_t(map.size()));
    c.insert(c.end(), map.begin(), map.end());
    record(kChannel, c);
    channels_.push_back(std::move(c));
    channel_counts_[id] = 0;
    return id;
}

void McapWriter::add_message(std::uint16_t channel, std::uint32_t sequence, std::uint64_t time_ns,
                             const Bytes& data) {
    le::Bytes m;
    le::append<std::uint16_t>(m, channel);
    le::append<std::uint32_t>(m, sequence);
    le::append<std::uint64_t>(m, time_ns);
    le::append<std::uint64_t>(m, time_ns);
    m.insert(m.end(), data.begin(), data.end());
    const le::Bytes records = framed(kMessage, m);

    le::Bytes chunk;
    le::append<std::uint64_t>(chunk, time_ns);
    le::append<std::uint64_t>(chunk, time_ns);
    le::append<std::uint64_t>(chunk, records.size());
    le::append<std::uint32_t>(chunk, crc32(records.data(), records.size()));
    append_string(chunk, ""); // no compression
    le::append<std::uint64_t>(chunk, records.size());
    ChunkInfo info{time_ns, file_.size(), 0, 0, 0, records.size(), channel};
    chunk.insert(chunk.end(), records.begin(), records.end());
    record(kChunk, chunk);
    info.length = file_.size() - info.start;

    le::Bytes index; // the chunk's one message at offset 0 of its records
    le::append<std::uint16_t>(index, channel);
    le::append<std::uint32_t>(index, 16);
    le::append<std::uint64_t>(index, time_ns);
    le::append<std::uint64_t>(index, 0);
    info.index_start = file_.size();
    record(kMessageIndex, index);
    info.index_length = file_.size() - info.index_start;
    chunks_.push_back(info);
    ++channel_counts_[channel];
}

void McapWriter::finish() {
    record(kDataEnd, le::Bytes(4, 0)); // data section CRC: not computed
    struct Group {
        std::uint8_t op;
        std::uint64_t start, length;
    };
    std::vector<Group> groups;
    const std::uint64_t summary_start = file_.size();
    auto group = [&](std::uint8_t op, const std::vector<le::Bytes>& contents) {
        if (contents.empty()) return;
        const std::uint64_t start = file_.size();
        for (auto& c : contents) record(op, c);
        groups.push_back({op, start, file_.size() - start});
    };
    group(kSchema, schemas_);
    group(kChannel, channels_);

    std::uint64_t t0 = 0, t1 = 0;
    if (!chunks_.empty()) {
        t0 = chunks_.front().time_ns, t1 = t0;
        for (auto& c : chunks_) t0 = std::min(t0, c.time_ns), t1 = std::max(t1, c.time_ns);
    }
    le::Bytes stats;
    le::append<std::uint64_t>(stats, chunks_.size()); // messages: one per chunk
    le::append<std::uint16_t>(stats, std::uint16_t(schemas_.size()));
    le::append<std::uint32_t>(stats, std::uint32_t(channels_.size()));
    le::append<std::uint32_t>(stats, 0); // attachments
    le::append<std::uint32_t>(stats, 0); // metadata
    le::append<std::uint32_t>(stats, std::uint32_t(chunks_.size()));
    le::append<std::uint64_t>(stats, t0);
    le::append<std::uint64_t>(stats, t1);
    le::append<std::uint32_t>(stats, std::uint32_t(channel_counts_.size() * 10));
    for (auto& [id, n] : channel_counts_)
        le::append<std::uint16_t>(stats, id), le::append<std::uint64_t>(stats, n);
    group(kStatistics, {stats});

    std::vector<le::Bytes> indexes;
    for (auto& c : chunks_) {
        le::Bytes x;
        le::append<std::uint64_t>(x, c.time_ns);
        le::append<std::uint64_t>(x, c.time_ns);
        le::append<std::uint64_t>(x, c.start);
        le::append<std::uint64_t>(x, c.length);
        le::append<std::uint32_t>(x, 10); // map: one channel -> its message index's offset
        le::append<std::uint16_t>(x, c.channel);
        le::append<std::uint64_t>(x, c.index_start);
        le::append<std::uint64_t>(x, c.index_length);
        append_string(x, "");
        le::append<std::uint64_t>(x, c.records_size);
        le::append<std::uint64_t>(x, c.records_size);
        indexes.push_back(std::move(x));
    }
    group(kChunkIndex, indexes);

    const std::uint64_t offsets_start = file_.size();
    for (auto& g : groups) {
        le::Bytes o{g.op};
        le::append<std::uint64_t>(o, g.start);
        le::append<std::uint64_t>(o, g.length);
        record(kSummaryOffset, o);
    }
    le::Bytes footer;
    le::append<std::uint64_t>(footer, summary_start);
    le::append<std::uint64_t>(footer, offsets_start);
    le::append<std::uint32_t>(footer, 0); // summary CRC: not computed
    record(kFooter, footer);
    file_.write(kMagic, sizeof kMagic);
    file_.commit();
}

} // namespace sonarsim
