#include "core/io/aris_read.hpp"

#include "core/base/errors.hpp"

#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>

namespace sonarsim {
namespace {

constexpr std::uint32_t kDdf05 = 0x05464444; // "DDF\x05"
constexpr std::size_t kHeaderBytes = 1024;   // the file header and each frame header

// Frame header offsets (vendor layout, docs/formats.md).
constexpr std::size_t kFrameIndex = 0, kFrameTime = 4, kFrameVersion = 12, kReceiverGain = 68, kSonarX = 232,
                      kPingMode = 436, kFrequencyHiLow = 440, kSamplePeriod = 452, kSoundSpeed = 464,
                      kSamplesPerBeam = 468, kSampleStartDelay = 476, kReordered = 516;

/// Bytes [offset, offset + n) of the input; the input's size.
struct Source {
    std::function<std::vector<std::uint8_t>(std::size_t offset, std::size_t n)> read;
    std::size_t size = 0;
    std::string origin;
};

template <typename T> T le(const std::vector<std::uint8_t>& b, std::size_t off) {
    T v{};
    std::memcpy(&v, b.data() + off, sizeof v); // little-endian files on a little-endian host
    return v;
}

/// Beams and samples from a frame header; checks what the frame's bytes depend on.
struct Layout {
    int beams = 0, samples = 0;
    std::size_t frame_bytes = 0;
};

Layout layout_of(const std::vector<std::uint8_t>& h, const std::string& origin, const std::string& where) {
    if (le<std::uint32_t>(h, kFrameVersion) != kDdf05)
        throw InputError(origin, where + "Version", "not an ARIS DDF_05 frame header (expected 0x05464444)");
    Layout l;
    const std::uint32_t mode = le<std::uint32_t>(h, kPingMode);
    l.beams = aris_beams_of_ping_mode(mode);
    if (l.beams == 0)
        throw InputError(origin, where + "PingMode",
                         "ping mode " + std::to_string(mode) + " is not one we know; allowed: 1, 3, 6, 9");
    const std::uint32_t samples = le<std::uint32_t>(h, kSamplesPerBeam);
    if (samples < 1 || samples > 65536)
        throw InputError(origin, where + "SamplesPerBeam",
                         std::to_string(samples) + " samples per beam; allowed: 1 to 65536");
    l.samples = int(samples);
    l.frame_bytes = kHeaderBytes + std::size_t(l.beams) * samples;
    return l;
}

Source file_source(const std::string& path) {
    auto in = std::make_shared<std::ifstream>(path, std::ios::binary);
    if (!*in) throw InputError(path, "", "cannot open the file");
    in->seekg(0, std::ios::end);
    Source s;
    s.size = std::size_t(in->tellg());
    s.origin = path;
    s.read = [in, path](std::size_t off, std::size_t n) {
        std::vector<std::uint8_t> b(n);
        in->seekg(std::streamoff(off));
        in->read(reinterpret_cast<char*>(b.data()), std::streamsize(n));
        if (std::size_t(in->gcount()) != n) throw InputError(path, "", "cannot read the file");
        return b;
    };
    return s;
}

Source memory_source(const std::vector<std::uint8_t>& bytes, const std::string& origin) {
    Source s;
    s.size = bytes.size();
    s.origin = origin;
    s.read = [&bytes](std::size_t off, std::size_t n) {
        return std::vector<std::uint8_t>(bytes.begin() + std::ptrdiff_t(off),
                                         bytes.begin() + std::ptrdiff_t(off + n));
    };
    return s;
}

/// The first frame's layout, which every frame shares (ARIS files change settings only between files).
Layout file_layout(const Source& s) {
    if (s.size < 2 * kHeaderBytes)
        throw InputError(s.origin, "", "too short for an ARIS file (a 1024-byte file header and a frame)");
    if (le<std::uint32_t>(s.read(0, 4), 0) != kDdf05)
        throw InputError(s.origin, "Version", "not an ARIS DDF_05 file (expected 0x05464444)");
    const Layout l = layout_of(s.read(kHeaderBytes, kHeaderBytes), s.origin, "frame 0: ");
    if ((s.size - kHeaderBytes) % l.frame_bytes != 0)
        throw InputError(s.origin, "frame 0: SamplesPerBeam",
                         "the file's size is not a whole number of frames of " + std::to_string(l.beams) +
                             " beams x " + std::to_string(l.samples) + " samples");
    return l;
}

std::size_t frame_count(const Source& s) {
    const Layout l = file_layout(s);
    return (s.size - kHeaderBytes) / l.frame_bytes;
}

ArisFrame frame_of(const Source& s, std::size_t k) {
    const Layout l = file_layout(s);
    const std::size_t n = (s.size - kHeaderBytes) / l.frame_bytes;
    if (k >= n)
        throw InputError(s.origin, "frame",
                         "frame " + std::to_string(k) + " asked for; the file holds " + std::to_string(n));
    const std::size_t at = kHeaderBytes + k * l.frame_bytes;
    const std::vector<std::uint8_t> h = s.read(at, kHeaderBytes);
    const std::string where = "frame " + std::to_string(k) + ": ";
    const Layout lk = layout_of(h, s.origin, where);
    if (lk.beams != l.beams || lk.samples != l.samples)
        throw InputError(s.origin, where + "PingMode",
                         "beams or samples differ from frame 0's; an ARIS file keeps them fixed");
    ArisFrame f;
    ArisFrameInfo& i = f.info;
    i.index = le<std::uint32_t>(h, kFrameIndex);
    i.time_us = le<std::uint64_t>(h, kFrameTime);
    i.ping_mode = le<std::uint32_t>(h, kPingMode);
    i.high_frequency = le<std::uint32_t>(h, kFrequencyHiLow) == 1;
    i.beams = l.beams, i.samples = l.samples;
    i.sample_period_us = le<std::uint32_t>(h, kSamplePeriod);
    i.sample_start_delay_us = le<std::uint32_t>(h, kSampleStartDelay);
    i.sound_speed_m_s = le<float>(h, kSoundSpeed);
    i.receiver_gain_db = le<std::uint32_t>(h, kReceiverGain);
    for (int c = 0; c < 3; ++c) i.position_m[c] = le<float>(h, kSonarX + 4 * std::size_t(c));
    if (!(i.sound_speed_m_s >= 1300 && i.sound_speed_m_s <= 1700))
        throw InputError(s.origin, where + "SoundSpeed",
                         "sound speed " + std::to_string(i.sound_speed_m_s) + " m/s; allowed: 1300 to 1700");
    if (!(i.sample_period_us >= 1))
        throw InputError(s.origin, where + "SamplePeriod", "a sample period of 0 us; allowed: 1 us or more");
    i.window_start_m = i.sound_speed_m_s * i.sample_start_delay_us * 1e-6 / 2;
    i.sample_length_m = i.sound_speed_m_s * i.sample_period_us * 1e-6 / 2;

    // Samples: sample-major; reordered frames hold beams in order, raw frames in firing order (ping p of
    // beams / 16 fires channels c = 0..15, beam = c x pings + p).
    const std::vector<std::uint8_t> data = s.read(at + kHeaderBytes, l.frame_bytes - kHeaderBytes);
    const bool reordered = le<std::uint32_t>(h, kReordered) != 0;
    const int pings = l.beams / 16;
    PolarImage& img = f.level_db;
    img.bins = l.samples, img.beams = l.beams;
    img.level_db.resize(data.size());
    for (int r = 0; r < l.samples; ++r)
        for (int j = 0; j < l.beams; ++j) {
            const int beam = reordered ? j : (j % 16) * pings + j / 16;
            const std::uint8_t b = data[std::size_t(r) * std::size_t(l.beams) + std::size_t(j)];
            img.level_db[std::size_t(r) * std::size_t(l.beams) + std::size_t(l.beams - 1 - beam)] =
                b == 0 ? -std::numeric_limits<float>::infinity() : float(b * 80.0 / 255.0);
        }
    return f;
}

} // namespace

int aris_beams_of_ping_mode(std::uint32_t mode) {
    switch (mode) {
    case 1:
        return 48;
    case 3:
        return 96;
    case 6:
        return 64;
    case 9:
        return 128;
    default:
        return 0;
    }
}

std::size_t aris_frame_count(const std::string& path) {
    return frame_count(file_source(path));
}

ArisFrame read_aris_frame(const std::string& path, std::size_t k) {
    return frame_of(file_source(path), k);
}

ArisFrame parse_aris_frame(const std::vector<std::uint8_t>& bytes, std::size_t k, const std::string& origin) {
    return frame_of(memory_source(bytes, origin), k);
}

std::size_t aris_frame_count(const std::vector<std::uint8_t>& bytes, const std::string& origin) {
    return frame_count(memory_source(bytes, origin));
}

} // namespace sonarsim
