#include "core/io/ping360_log_read.hpp"

#include "core/base/errors.hpp"

namespace sonarsim {
namespace {

class Cursor {
  public:
    Cursor(const std::vector<std::uint8_t>& b, std::string path) : b_(b), path_(std::move(path)) {}
    bool done() const { return at_ >= b_.size(); }
    std::uint32_t be32(const char* field) {
        need(4, field);
        std::uint32_t v = 0;
        for (int k = 0; k < 4; ++k) v = (v << 8) | b_[at_++];
        return v;
    }
    std::vector<std::uint8_t> array(const char* field) {
        const std::uint32_t n = be32(field);
        if (n == 0xFFFFFFFFu) return {}; // a null string
        need(n, field);
        std::vector<std::uint8_t> out(b_.begin() + long(at_), b_.begin() + long(at_ + n));
        at_ += n;
        return out;
    }
    /// A QString (UTF-16 big-endian) of ASCII text.
    std::string text(const char* field) {
        const auto raw = array(field);
        if (raw.size() % 2) throw InputError(path_, field, "a UTF-16 string of an odd number of bytes");
        std::string s;
        for (size_t i = 0; i < raw.size(); i += 2) s += char(raw[i] ? '?' : raw[i + 1]);
        return s;
    }
    const std::string& path() const { return path_; }

  private:
    void need(size_t n, const char* field) const {
        if (at_ + n > b_.size()) throw InputError(path_, field, "the file ends inside this field");
    }
    const std::vector<std::uint8_t>& b_;
    std::string path_;
    size_t at_ = 0;
};

int le16(const std::vector<std::uint8_t>& m, size_t at) {
    return int(m[at]) | int(m[at + 1]) << 8;
}

} // namespace

Ping360Log read_ping360_log(const std::vector<std::uint8_t>& bytes, const std::string& path) {
    Cursor c(bytes, path);
    Ping360Log log;
    log.header = c.text("header");
    if (log.header != "PingViewer sensor log file")
        throw InputError(path, "header", "not a Ping Viewer sensor log (header \"" + log.header + "\")");
    log.version = int(c.be32("version"));
    for (const char* f : {"hash", "date", "tag", "os name", "os version"})
        log.build_info.push_back(c.text(f));
    log.sensor_family = int(c.be32("sensor family"));
    log.sensor_type = int(c.be32("sensor type"));
    while (!c.done()) {
        Ping360DeviceData d;
        d.timestamp = c.text("timestamp");
        const auto m = c.array("message");
        if (m.size() < 10 || m[0] != 'B' || m[1] != 'R')
            throw InputError(path, "message", "a record's message does not start with \"BR\"");
        const size_t payload = size_t(le16(m, 2));
        if (m.size() != 8 + payload + 2)
            throw InputError(path, "payload_length", "does not match the message's size");
        int sum = 0;
        for (size_t i = 0; i < 8 + payload; ++i) sum += m[i];
        if ((sum & 0xFFFF) != le16(m, 8 + payload))
            throw InputError(path, "checksum", "does not match the message's bytes");
        if (le16(m, 4) != 2300) continue;
        if (payload < 14) throw InputError(path, "device_data", "shorter than its fixed fields");
        const size_t p = 8;
        d.mode = m[p], d.gain_setting = m[p + 1];
        d.angle_grad = le16(m, p + 2);
        d.transmit_duration_us = le16(m, p + 4);
        d.sample_period_ticks = le16(m, p + 6);
        d.transmit_frequency_khz = le16(m, p + 8);
        d.number_of_samples = le16(m, p + 10);
        const size_t n = size_t(le16(m, p + 12));
        if (14 + n != payload) throw InputError(path, "data", "its length does not fill the payload");
        d.data.assign(m.begin() + long(p + 14), m.begin() + long(p + 14 + n));
        log.pings.push_back(std::move(d));
    }
    return log;
}

} // namespace sonarsim
