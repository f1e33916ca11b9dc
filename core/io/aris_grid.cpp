#include "core/io/aris_grid.hpp"

#include "core/base/errors.hpp"
#include "core/grid/sonar_grid.hpp"
#include "core/shading/physics.hpp" // sound_speed_m_s

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace sonarsim {
std::string significant_text(double v, int digits) {
    std::ostringstream o;
    o.precision(digits);
    o << v;
    return o.str();
}

namespace {

std::string num(double v, int digits = 4) {
    return significant_text(v, digits);
}

std::string us(double v) {
    return num(v, 6) + " us";
}

} // namespace

ArisTiming aris_timing(const SceneDesc& s, const ArisLimits& lim, const std::string& origin) {
    const SonarParams& sonar = s.sonar;
    ArisTiming t;
    t.sound_speed_m_s = float(sound_speed_m_s(s.water.temperature_c, s.water.depth_m));
    const double c = double(t.sound_speed_m_s), window = range_window_m(sonar);
    const double bin = range_bin_m(sonar), to_us = 2e6 / c; // metres of range to us of travel
    const std::string sys = lim.system;

    const double sp = std::round(bin * to_us), sp_max = lim.sample_period_max_us;
    if (sp < 4 || sp > sp_max)
        throw InputError(origin, "sonar.range_bins",
                         "an " + sys + " samples every 4-" + num(sp_max) + " us (SamplePeriod); bins of " +
                             num(bin * 1e3) + " mm are " + us(bin * to_us) + " at " + num(c, 5) +
                             " m/s: this range window allows " +
                             std::to_string(long(std::floor(window * to_us / (sp_max + 0.5))) + 1) + " to " +
                             std::to_string(long(std::floor(window * to_us / 3.5))) + " range bins");
    t.sample_period_us = std::uint32_t(sp);

    const double first = sonar_grid(sonar)->bin_centre_m(0);
    const double ssd = std::round(first * to_us);
    const double ssd_max =
        std::min(double(lim.sample_start_delay_max_us), std::floor(lim.window_start_max_m * to_us));
    if (ssd < 930 || ssd > ssd_max)
        throw InputError(origin, "sonar.range_min_m",
                         "an " + sys + " starts sampling 930-" + num(ssd_max, 6) +
                             " us after the ping (SampleStartDelay, a window start of at most " +
                             num(lim.window_start_max_m) + " m); the first bin's centre at " + num(first) +
                             " m is " + us(first * to_us) + " at " + num(c, 5) + " m/s: range_min_m from " +
                             num(std::ceil((929.5 / to_us - bin / 2) * 1e3) / 1e3) + " to " +
                             num(std::floor((ssd_max / to_us - bin / 2) * 1e3) / 1e3) + " m");
    t.sample_start_delay_us = std::uint32_t(ssd);

    t.window_start_m = ssd / to_us;
    t.sample_m = sp / to_us;
    t.samples = std::uint32_t(std::max(1.0, std::round(window / t.sample_m)));
    if (t.window_start_m + t.samples * t.sample_m > lim.window_end_max_m + 1e-9) {
        // The last sample ends past the system's window: one fewer when that is enough (the nearest legal
        // window), else the window is too long for the system.
        if (t.window_start_m + (t.samples - 1.0) * t.sample_m > lim.window_end_max_m + 1e-9)
            throw InputError(origin, "sonar.range_max_m",
                             "an " + sys + "'s window ends at most " + num(lim.window_end_max_m) +
                                 " m from the sonar; this one ends at " +
                                 num(t.window_start_m + t.samples * t.sample_m) + " m");
        --t.samples;
        t.adjusted = "the window ends at " + num(t.window_start_m + t.samples * t.sample_m, 6) +
                     " m, one sample (" + num(t.sample_m * 1e3) + " mm) short of range_max_m, within the " +
                     sys + "'s " + num(lim.window_end_max_m) + " m";
    }
    if (t.samples < 128 || t.samples > kArisMaxSamples)
        throw InputError(origin, "sonar.range_bins",
                         "an ARIS frame holds 128-" + std::to_string(kArisMaxSamples) +
                             " samples per beam; this window at SamplePeriod " + us(sp) + " needs " +
                             std::to_string(t.samples));
    t.window_length_m = t.samples * t.sample_m;

    const double res = s.sensor.range_resolution_m, pw_max = lim.pulse_width_max_us;
    const double pw = res > 0 ? std::round(res * to_us) : sp;
    if (pw < 4 || pw > pw_max)
        throw InputError(origin, "sensor.range_resolution_m",
                         "an " + sys + " pulse is 4-" + num(pw_max) +
                             " us long (PulseWidth); 2 range_resolution_m / c is " +
                             us(res > 0 ? res * to_us : sp) + ": allowed " + num(3.5 / to_us) + " to " +
                             num((pw_max + 0.4) / to_us) + " m (or 0: one sample period)");
    t.pulse_width_us = std::uint32_t(pw);

    // The vendor SDK's sample recording: CyclePeriod 32953 = SSD 4593 + SP 14 x 2000 samples + 360 us.
    const double cycle = ssd + sp * t.samples + 360, cycle_max = lim.cycle_period_max_us;
    if (cycle < 1802 || cycle > cycle_max)
        throw InputError(origin, "sonar.range_max_m",
                         "an " + sys + "'s ping cycle is 1802-" + num(cycle_max, 6) +
                             " us (CyclePeriod = SampleStartDelay + SamplePeriod x samples + 360 us); this "
                             "window's is " +
                             us(cycle) + ": range_max_m from about " + num((1802 - 360) / to_us) + " to " +
                             num((cycle_max - 360) / to_us) + " m");
    t.cycle_period_us = std::uint32_t(cycle);

    // ReceiverGain: the sensor's gain, in the whole dB (0-24) a system's receiver takes.
    const double gain = s.sensor.gain_db;
    const double legal = std::clamp(std::round(gain), 0.0, double(kArisMaxReceiverGainDb));
    t.receiver_gain_db = std::uint32_t(legal);
    if (legal != gain)
        t.adjusted += std::string(t.adjusted.empty() ? "" : "; ") + "ReceiverGain " + num(legal) +
                      " dB, the nearest an ARIS receiver takes (whole dB, 0-" +
                      std::to_string(kArisMaxReceiverGainDb) + ") to sensor.gain_db " + num(gain) +
                      " dB; the samples keep the image's levels";
    return t;
}

bool bins_are_samples(const SonarParams& sonar, const ArisTiming& t) {
    const std::shared_ptr<const SonarGrid> grid = sonar_grid(sonar);
    const double tol = 1e-6 * t.sample_m;
    return sonar.range_bins == int(t.samples) && std::abs(grid->bin_m - t.sample_m) * t.samples <= tol &&
           std::abs(grid->bin_centre_m(0) - t.window_start_m) <= tol;
}

SonarParams on_samples(SonarParams sonar, const ArisTiming& t) {
    const double near_m = t.window_start_m - t.sample_m / 2;
    sonar.range_min_m = near_m;
    sonar.range_max_m = near_m + t.samples * t.sample_m;
    sonar.range_bins = int(t.samples);
    return sonar;
}

PolarImage aris_resample(const PolarImage& img, const SonarParams& sonar, const ArisTiming& t) {
    if (img.bins == sonar.range_bins && bins_are_samples(sonar, t)) return img;
    PolarImage out;
    out.beams = img.beams;
    out.bins = int(t.samples);
    out.level_db.assign(size_t(out.bins) * size_t(out.beams), -std::numeric_limits<float>::infinity());
    SonarParams of_image = sonar; // the image's own bins
    of_image.range_bins = img.bins;
    const std::shared_ptr<const SonarGrid> grid = sonar_grid(of_image);
    for (int j = 0; j < out.bins; ++j) {
        const double r = t.window_start_m + j * t.sample_m;
        const double u = std::clamp(grid->bin_position(r) - 0.5, 0.0, double(img.bins - 1));
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
