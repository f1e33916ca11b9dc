#include "core/io/ping360_log.hpp"

#include "core/base/errors.hpp"
#include "core/base/le_bytes.hpp"
#include "core/scene/params.hpp"
#include "core/shading/physics.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>

namespace sonarsim {
namespace {

constexpr double kTickS = 25e-9; ///< the sample period's unit
constexpr int kMinSamples = 200, kMaxSamples = 1200, kMinTicks = 80, kMaxTicks = 40000;

int log_samples(const SceneDesc& s) {
    return std::clamp(s.sonar.range_bins, kMinSamples, kMaxSamples);
}

double sample_ticks(const SceneDesc& s) {
    const double c = sound_speed_m_s(s.water.temperature_c, s.water.depth_m);
    return 2 * s.sonar.range_max_m / (log_samples(s) * c * kTickS);
}

// Big-endian QDataStream fields.
void be_u32(le::Bytes& b, std::uint32_t v) {
    for (int k = 3; k >= 0; --k) b.push_back(std::uint8_t(v >> (8 * k)));
}
void qstring(le::Bytes& b, const std::string& ascii) {
    be_u32(b, std::uint32_t(2 * ascii.size()));
    for (char ch : ascii) b.push_back(0), b.push_back(std::uint8_t(ch));
}
void qbytes(le::Bytes& b, const le::Bytes& data) {
    be_u32(b, std::uint32_t(data.size()));
    b.insert(b.end(), data.begin(), data.end());
}

/// One ping-protocol message: "BR", payload length, id, source and destination ids, payload, checksum.
le::Bytes ping_message(std::uint16_t id, const le::Bytes& payload) {
    le::Bytes m = {'B', 'R'};
    le::append<std::uint16_t>(m, std::uint16_t(payload.size()));
    le::append<std::uint16_t>(m, id);
    le::append<std::uint8_t>(m, 0); // source device id
    le::append<std::uint8_t>(m, 0); // destination
    m.insert(m.end(), payload.begin(), payload.end());
    std::uint16_t sum = 0;
    for (std::uint8_t byte : m) sum = std::uint16_t(sum + byte);
    le::append<std::uint16_t>(m, sum);
    return m;
}

/// "hh:mm:ss.zzz" of UNIX time t.
std::string time_of_day(double t) {
    const std::time_t whole = std::time_t(std::floor(t));
    std::tm tm{};
    gmtime_r(&whole, &tm);
    char buf[48]; // room for any int the compiler cannot rule out; the fields are 2, 2, 2 and 3 digits
    std::snprintf(buf, sizeof buf, "%02d:%02d:%02d.%03d", tm.tm_hour, tm.tm_min, tm.tm_sec,
                  std::clamp(int(std::floor((t - double(whole)) * 1000)), 0, 999));
    return buf;
}

} // namespace

std::string ping360_log_problem(const SceneDesc& s) {
    if (!(s.sonar.frequency_khz >= 500 && s.sonar.frequency_khz <= 1000))
        return "sonar.frequency_khz " + number_text(s.sonar.frequency_khz) +
               " kHz is outside the Ping360 protocol's 500-1000 kHz";
    const double ticks = sample_ticks(s);
    if (!(std::lround(ticks) >= kMinTicks && std::lround(ticks) <= kMaxTicks))
        return "sonar.range_max_m " + number_text(s.sonar.range_max_m) + " m over " +
               std::to_string(log_samples(s)) + " samples needs a sample period of " + number_text(ticks) +
               " ticks of 25 ns; the protocol allows 80-40000";
    return "";
}

Bytes encode_ping360_log(const SceneDesc& s, const PingSeries& p, const ByteMapping& m,
                         const std::string& origin) {
    if (const std::string problem = ping360_log_problem(s); !problem.empty())
        throw InputError(origin, problem.substr(0, problem.find(' ')), problem);
    const double c = sound_speed_m_s(s.water.temperature_c, s.water.depth_m);
    const int n = log_samples(s);
    const auto ticks = std::uint16_t(std::lround(sample_ticks(s)));
    const double period_us = ticks * kTickS * 1e6;
    const auto tx_us = std::uint16_t(std::lround(std::clamp(
        8000 * s.sonar.range_max_m / c, std::max(5.0, 2.5 * period_us), std::min(500.0, 64 * period_us))));
    le::Bytes out;
    qstring(out, "PingViewer sensor log file");
    be_u32(out, 1); // log structure version
    for (const char* info : {"sonarsim", "simulated", "sonarsim", "sonarsim", "1"}) qstring(out, info);
    be_u32(out, 1); // sensor family: Ping
    be_u32(out, 2); // sensor type: Ping360
    // The samples' ranges under the protocol: sample j at (j + 1/2) of n along [0, r_max).
    const double sample_m = s.sonar.range_max_m / n;
    for (int i = 0; i < p.pings; ++i) {
        const Ping& g = p.schedule[size_t(i)];
        le::Bytes payload;
        le::append<std::uint8_t>(payload, 1); // mode: Ping360
        le::append<std::uint8_t>(payload, 1); // gain setting: normal
        double grad = std::fmod(-g.head_deg / 0.9, 400.0);
        if (grad < 0) grad += 400;
        le::append<std::uint16_t>(payload, std::uint16_t(std::lround(grad) % 400));
        le::append<std::uint16_t>(payload, tx_us);
        le::append<std::uint16_t>(payload, ticks);
        le::append<std::uint16_t>(payload, std::uint16_t(std::lround(s.sonar.frequency_khz)));
        le::append<std::uint16_t>(payload, std::uint16_t(n));
        le::append<std::uint16_t>(payload, std::uint16_t(n)); // the data array's length
        const float* profile = p.profile(i, 0);
        for (int j = 0; j < n; ++j) {
            const double r = (j + 0.5) * sample_m, u = p.grid->bin_position(r);
            const float level = u >= 0 && u < p.bins ? profile[int(u)] : -INFINITY;
            payload.push_back(level_byte(level, m));
        }
        qstring(out, time_of_day(std::max(0.0, s.exports.start_time_s + g.time_s)));
        qbytes(out, ping_message(2300, payload));
    }
    return out;
}

} // namespace sonarsim
