// The tests' own reader of MCAP files and CDR fields, written from the specifications (mcap.dev, OMG CDR):
// the records of a file in order, and fields read one after another.
#pragma once
#include "support.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace sonarsim::test {

/// The records of an MCAP file: opcode and content, in file order, after checking both magics.
struct Record {
    std::uint8_t op;
    size_t offset; ///< of the opcode, from the start of the file
    std::vector<std::uint8_t> content;
};

inline std::vector<Record> mcap_records(const std::vector<std::uint8_t>& b) {
    const std::uint8_t magic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
    REQUIRE(b.size() > 16);
    REQUIRE(std::memcmp(b.data(), magic, 8) == 0);
    REQUIRE(std::memcmp(b.data() + b.size() - 8, magic, 8) == 0);
    std::vector<Record> out;
    for (size_t p = 8; p < b.size() - 8;) {
        const auto len = size_t(at<std::uint64_t>(b, p + 1));
        REQUIRE(p + 9 + len <= b.size() - 8);
        out.push_back({b[p], p, {b.begin() + long(p + 9), b.begin() + long(p + 9 + len)}});
        p += 9 + len;
    }
    return out;
}

/// Reads fields in order from a byte string.
struct Reader {
    const std::vector<std::uint8_t>& b;
    size_t p = 0, origin = 0; ///< CDR aligns from `origin`
    template <typename T> T get(bool aligned = false) {
        if (aligned)
            while ((p - origin) % sizeof(T)) ++p;
        T v = at<T>(b, p);
        p += sizeof(T);
        return v;
    }
    std::string str(bool cdr = false) {
        const auto n = size_t(get<std::uint32_t>(cdr));
        std::string s(b.begin() + long(p), b.begin() + long(p + n));
        p += n;
        if (cdr) {
            REQUIRE(!s.empty());
            REQUIRE(s.back() == '\0');
            s.pop_back();
        }
        return s;
    }
};

/// A message of an MCAP file, as the data section holds it.
struct McapMessage {
    std::uint16_t channel;
    std::uint32_t sequence;
    std::uint64_t log_time_ns;
    std::vector<std::uint8_t> data;
};

/// What the data section of an MCAP file holds: the profile, schemas (name by id), channels (schema id and
/// topic by id) and every message of every chunk (uncompressed chunks only), in file order.
struct McapContents {
    std::string profile;
    std::map<std::uint16_t, std::string> schema_name;
    std::map<std::uint16_t, std::uint16_t> channel_schema;
    std::map<std::uint16_t, std::string> channel_topic;
    std::vector<McapMessage> messages;
};

inline McapContents mcap_contents(const std::vector<std::uint8_t>& b) {
    McapContents c;
    const std::vector<Record> recs = mcap_records(b);
    for (const Record& r : recs) {
        Reader in{r.content};
        if (r.op == 0x0F) break; // data end: the summary repeats the schemas and channels
        if (r.op == 0x01) c.profile = in.str();
        if (r.op == 0x03) {
            const auto id = in.get<std::uint16_t>();
            c.schema_name[id] = in.str();
        } else if (r.op == 0x04) {
            const auto id = in.get<std::uint16_t>();
            c.channel_schema[id] = in.get<std::uint16_t>();
            c.channel_topic[id] = in.str();
        } else if (r.op == 0x06) {
            in.get<std::uint64_t>(), in.get<std::uint64_t>();
            const auto size = size_t(in.get<std::uint64_t>());
            in.get<std::uint32_t>();
            REQUIRE(in.str().empty()); // uncompressed
            REQUIRE(size_t(in.get<std::uint64_t>()) == size);
            for (size_t p = in.p; p < in.p + size;) { // the chunk's records
                const auto len = size_t(at<std::uint64_t>(r.content, p + 1));
                if (r.content[p] == 0x05) {
                    Reader m{r.content, p + 9};
                    McapMessage msg;
                    msg.channel = m.get<std::uint16_t>();
                    msg.sequence = m.get<std::uint32_t>();
                    msg.log_time_ns = m.get<std::uint64_t>();
                    m.get<std::uint64_t>(); // publish time
                    msg.data.assign(r.content.begin() + long(m.p), r.content.begin() + long(p + 9 + len));
                    c.messages.push_back(std::move(msg));
                }
                p += 9 + len;
            }
        }
    }
    return c;
}

} // namespace sonarsim::test
