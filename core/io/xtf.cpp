#include "core/io/xtf.hpp"

#include "core/base/le_bytes.hpp"
#include "core/data/pose.hpp"
#include "core/shading/physics.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <string>

namespace sonarsim {
namespace {

constexpr size_t kFileHeaderBytes = 1024, kChanInfoOffset = 256, kChanInfoBytes = 128;
constexpr size_t kPingHeaderBytes = 256, kChanHeaderBytes = 64;

/// A fixed-width text field: `text` cut to `width` bytes, NUL-padded.
void put_text(le::Bytes& b, size_t offset, const std::string& text, size_t width) {
    if (b.size() < offset + width) b.resize(offset + width);
    std::copy_n(text.begin(), std::min(text.size(), width), b.begin() + long(offset));
}

le::Bytes file_header(const SceneDesc& s, const ByteMapping& m) {
    le::Bytes h(kFileHeaderBytes, 0);
    le::put<std::uint8_t>(h, 0, 0x7B); // FileFormat
    le::put<std::uint8_t>(h, 1, 1);    // SystemType
    put_text(h, 2, "sonarsim", 8);
    put_text(h, 10, "1", 8);
    put_text(h, 18, s.sonar.device == "none" ? "sidescan" : s.sonar.device, 16);
    le::put<std::uint16_t>(h, 34, 0); // SonarType: none of Triton's enumerated systems
    char note[64];
    std::snprintf(note, sizeof note, "samples: byte = 255 (L - %.1f) / %.1f, L in dB (sonarsim)", m.lo_db,
                  m.hi_db - m.lo_db);
    put_text(h, 36, note, 64);
    le::put<std::uint16_t>(h, 164, 0); // NavUnits: metres
    le::put<std::uint16_t>(h, 166, 2); // NumberOfSonarChannels
    for (int ch = 0; ch < 2; ++ch) {
        const size_t c = kChanInfoOffset + size_t(ch) * kChanInfoBytes;
        le::put<std::uint8_t>(h, c + 0, std::uint8_t(ch + 1)); // TypeOfChannel: 1 port, 2 starboard
        le::put<std::uint8_t>(h, c + 1, std::uint8_t(ch));     // SubChannelNumber
        le::put<std::uint16_t>(h, c + 4, 1);                   // UniPolar
        le::put<std::uint16_t>(h, c + 6, 1);                   // BytesPerSample
        le::put<std::uint32_t>(h, c + 8, std::uint32_t(s.sonar.range_bins)); // Reserved (NumSamples)
        put_text(h, c + 12, ch == 0 ? "port" : "starboard", 16);
        le::put<float>(h, c + 32, float(s.sonar.frequency_khz));     // Frequency [kHz]
        le::put<float>(h, c + 36, float(s.sonar.azimuth_fov_deg));   // HorizBeamAngle
        le::put<float>(h, c + 40, float(s.sidescan.depression_deg)); // TiltAngle
        le::put<float>(h, c + 44, float(s.sonar.elevation_fov_deg)); // BeamWidth
        le::put<std::uint16_t>(h, c + 72, 1);                        // BeamsPerArray
        le::put<std::uint8_t>(h, c + 74, 8);                         // SampleFormat: byte
    }
    return h;
}

/// One ping's sonar record: its header, then per channel its header and samples.
void append_ping(le::Bytes& out, const SceneDesc& s, const PingSeries& p, int i, const ByteMapping& m,
                 double c) {
    const Ping& ping = p.schedule[size_t(i)];
    const size_t n = size_t(p.bins);
    const size_t record = kPingHeaderBytes + 2 * (kChanHeaderBytes + n);
    le::Bytes h(kPingHeaderBytes, 0);
    le::put<std::uint16_t>(h, 0, 0xFACE); // MagicNumber
    le::put<std::uint8_t>(h, 2, 0);       // HeaderType: sonar
    le::put<std::uint16_t>(h, 4, 2);      // NumChansToFollow
    le::put<std::uint32_t>(h, 10, std::uint32_t(record));
    const double t = std::max(0.0, s.exports.start_time_s + ping.time_s);
    const std::time_t whole = std::time_t(std::floor(t));
    std::tm tm{};
    gmtime_r(&whole, &tm);
    le::put<std::uint16_t>(h, 14, std::uint16_t(tm.tm_year + 1900));
    le::put<std::uint8_t>(h, 16, std::uint8_t(tm.tm_mon + 1));
    le::put<std::uint8_t>(h, 17, std::uint8_t(tm.tm_mday));
    le::put<std::uint8_t>(h, 18, std::uint8_t(tm.tm_hour));
    le::put<std::uint8_t>(h, 19, std::uint8_t(tm.tm_min));
    le::put<std::uint8_t>(h, 20, std::uint8_t(tm.tm_sec));
    le::put<std::uint8_t>(h, 21, std::uint8_t(std::min(99.0, std::floor((t - double(whole)) * 100))));
    le::put<std::uint16_t>(h, 22, std::uint16_t(tm.tm_yday + 1)); // JulianDay
    le::put<std::uint32_t>(h, 28, std::uint32_t(i));              // PingNumber
    le::put<float>(h, 32, float(c / 2));                          // SoundVelocity: one way, halved
    le::put<float>(h, 64, float(s.water.temperature_c));
    le::put<float>(h, 72, float(c)); // ComputedSoundVelocity
    const auto& pos = ping.vehicle.position_m;
    for (size_t at : {size_t(128), size_t(160)}) { // Ship and Sensor Y (north), X (east)
        le::put<double>(h, at, pos[1]);
        le::put<double>(h, at + 8, pos[0]);
    }
    le::put<float>(h, 152, float(std::hypot(s.sonar.velocity_mps[0], s.sonar.velocity_mps[1]) / 0.514444));
    const double altitude = p.first_return_m[size_t(i)];
    le::put<float>(h, 192, float(s.water.depth_m));
    le::put<float>(h, 196, float(std::isfinite(altitude) ? altitude : 0.0));
    const auto& o = ping.vehicle.orientation_deg;
    le::put<float>(h, 204, float(o[1])); // SensorPitch
    le::put<float>(h, 208, float(o[0])); // SensorRoll
    double heading = std::fmod(90 - o[2], 360.0);
    if (heading < 0) heading += 360;
    le::put<float>(h, 212, float(heading)); // SensorHeading: clockwise from north (y)
    out.insert(out.end(), h.begin(), h.end());
    const double r_max = s.sonar.range_max_m, r_min = p.grid->range_min_m;
    for (int ch = 0; ch < 2; ++ch) {
        le::Bytes ch_header(kChanHeaderBytes, 0);
        le::put<std::uint16_t>(ch_header, 0, std::uint16_t(ch)); // ChannelNumber
        le::put<float>(ch_header, 4, float(r_max));              // SlantRange
        le::put<float>(ch_header, 8,
                       float(std::isfinite(altitude) && altitude < r_max
                                 ? std::sqrt(r_max * r_max - altitude * altitude)
                                 : r_max));                            // GroundRange
        le::put<float>(ch_header, 12, float(2 * r_min / c));           // TimeDelay
        le::put<float>(ch_header, 16, float(2 * (r_max - r_min) / c)); // TimeDuration
        le::put<float>(ch_header, 20, float(p.ping_interval_s));       // SecondsPerPing
        le::put<std::uint16_t>(ch_header, 26, std::uint16_t(std::lround(s.sonar.frequency_khz)));
        le::put<std::uint32_t>(ch_header, 42, std::uint32_t(n)); // NumSamples
        out.insert(out.end(), ch_header.begin(), ch_header.end());
        // Port's samples far first, starboard's near first: the specification reverses the sample order of
        // odd-numbered (port) sonar channels so that a waterfall shows them as they lie (Rev. 41, 2.3.1).
        const float* profile = p.profile(i, ch);
        for (size_t k = 0; k < n; ++k) out.push_back(level_byte(profile[ch == 0 ? n - 1 - k : k], m));
    }
}

} // namespace

Bytes encode_xtf(const SceneDesc& s, const PingSeries& p, const ByteMapping& m) {
    const double c = sound_speed_m_s(s.water.temperature_c, s.water.depth_m);
    le::Bytes out = file_header(s, m);
    out.reserve(out.size() + size_t(p.pings) * (kPingHeaderBytes + 2 * (kChanHeaderBytes + size_t(p.bins))));
    for (int i = 0; i < p.pings; ++i) append_ping(out, s, p, i, m, c);
    return out;
}

} // namespace sonarsim
