#include "core/io/aris_grid.hpp"

#include "core/base/errors.hpp"
#include "core/shading/physics.hpp" // sound_speed_m_s

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace sonarsim {
namespace {

std::string num(double v, int digits = 4) {
    std::ostringstream o;
    o.precision(digits);
    o << v;
    return o.str();
}

std::string us(double v) {
    return num(v, 6) + " us";
}

} // namespace

ArisTiming aris_timing(const SceneDesc& s, std::uint32_t max_cycle_us, const std::string& origin) {
    const SonarParams& sonar = s.sonar;
    ArisTiming t;
    t.sound_speed_m_s = float(sound_speed_m_s(s.water.temperature_c, s.water.depth_m));
    const double c = double(t.sound_speed_m_s), window = sonar.range_max_m - sonar.range_min_m;
    const double bin = window / sonar.range_bins, to_us = 2e6 / c; // metres of range to us of travel

    const double sp = std::round(bin * to_us);
    if (sp < 4 || sp > 100)
        throw InputError(origin, "sonar.range_bins",
                         "ARIS samples every 4-100 us (SamplePeriod); bins of " + num(bin * 1e3) +
                             " mm are " + us(bin * to_us) + " at " + num(c, 5) +
                             " m/s: this range window allows " +
                             std::to_string(long(std::floor(window * to_us / 100.5)) + 1) + " to " +
                             std::to_string(long(std::floor(window * to_us / 3.5))) + " range bins");
    t.sample_period_us = std::uint32_t(sp);

    const double first = sonar.range_min_m + bin / 2; // the first bin's centre
    const double ssd = std::round(first * to_us);
    if (ssd < 930 || ssd > 65535)
        throw InputError(
            origin, "sonar.range_min_m",
            "ARIS starts sampling 930-65535 us after the ping (SampleStartDelay); the first bin's "
            "centre at " +
                num(first) + " m is " + us(first * to_us) + " at " + num(c, 5) +
                " m/s: the smallest range_min_m allowed is " +
                num(std::ceil((929.5 / to_us - bin / 2) * 1e3) / 1e3) + " m");
    t.sample_start_delay_us = std::uint32_t(ssd);

    t.window_start_m = ssd / to_us;
    t.sample_m = sp / to_us;
    t.samples = std::uint32_t(std::max(1.0, std::round(window / t.sample_m)));
    t.window_length_m = t.samples * t.sample_m;

    const double res = s.sensor.range_resolution_m;
    const double pw = res > 0 ? std::round(res * to_us) : sp;
    if (pw < 4 || pw > 100)
        throw InputError(origin, "sensor.range_resolution_m",
                         "an ARIS pulse is 4-100 us long (PulseWidth); 2 range_resolution_m / c is " +
                             us(res * to_us) + ": allowed " + num(3.5 / to_us) + " to " + num(100.4 / to_us) +
                             " m (or 0: one sample period)");
    t.pulse_width_us = std::uint32_t(pw);

    // The vendor SDK's sample recording: CyclePeriod 32953 = SSD 4593 + SP 14 x 2000 samples + 360 us.
    const double cycle = ssd + sp * t.samples + 360;
    if (cycle < 1802 || cycle > max_cycle_us)
        throw InputError(origin, "sonar.range_max_m",
                         "an ARIS ping cycle is 1802-" + std::to_string(max_cycle_us) +
                             " us for this system (CyclePeriod = SampleStartDelay + SamplePeriod x samples "
                             "+ 360 us); this window's is " +
                             us(cycle) + ": range_max_m from about " + num((1802 - 360) / to_us) + " to " +
                             num((max_cycle_us - 360) / to_us) + " m");
    t.cycle_period_us = std::uint32_t(cycle);
    return t;
}

PolarImage aris_resample(const PolarImage& img, const SonarParams& sonar, const ArisTiming& t) {
    PolarImage out;
    out.beams = img.beams;
    out.bins = int(t.samples);
    out.level_db.assign(size_t(out.bins) * size_t(out.beams), -std::numeric_limits<float>::infinity());
    const double bin = (sonar.range_max_m - sonar.range_min_m) / img.bins;
    for (int j = 0; j < out.bins; ++j) {
        const double r = t.window_start_m + j * t.sample_m;
        const double u = std::clamp((r - sonar.range_min_m) / bin - 0.5, 0.0, double(img.bins - 1));
        const int i0 = std::min(int(std::floor(u)), std::max(0, img.bins - 2));
        const int i1 = std::min(i0 + 1, img.bins - 1);
        const double f = u - i0;
        for (int b = 0; b < img.beams; ++b) {
            float& o = out.level_db[size_t(j) * size_t(img.beams) + size_t(b)];
            if (f <= 0)
                o = img.at(i0, b);
            else if (f >= 1)
                o = img.at(i1, b);
            else {
                const double i =
                    (1 - f) * std::pow(10.0, img.at(i0, b) / 10.0) + f * std::pow(10.0, img.at(i1, b) / 10.0);
                if (i > 0) o = float(10 * std::log10(i));
            }
        }
    }
    return out;
}

} // namespace sonarsim
