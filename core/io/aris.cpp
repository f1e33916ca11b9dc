#include "core/io/aris.hpp"

#include "core/base/errors.hpp"
#include "core/base/le_bytes.hpp"
#include "core/io/output.hpp"
#include "core/grid/sonar_grid.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <sstream>

namespace sonarsim {
namespace {

constexpr std::uint32_t kArisVersion = 0x05464444; // "DDF\x05"
constexpr size_t kHeaderBytes = 1024;

/// The ARIS modes (Sound Metrics' SystemConfiguration: FrequencyLow/High per system; ping modes and
/// beams of the file SDK's FrameFuncs.c). TheSystemType: 0 = ARIS 1800, 1 = ARIS 3000, 2 = ARIS 1200.
/// A frame is `pings` pings of 16 beams each, one CyclePeriod apart (the integration SDK's Reorder.cpp).
struct ArisMode {
    const char *name, *preset;
    int beams;
    double frequency_khz;
    std::uint32_t ping_mode, system_type, high_frequency;
    int pings;
};
constexpr ArisMode kModes[] = {{"ARIS 3000 HF", "aris3000-hf", 128, 3000, 9, 1, 1, 8},
                               {"ARIS 3000 LF", "aris3000-lf", 64, 1800, 6, 1, 0, 4},
                               {"ARIS 1800 HF", "aris1800-hf", 96, 1800, 3, 0, 1, 6},
                               {"ARIS 1800 LF", "aris1800-lf", 48, 1100, 1, 0, 0, 3},
                               {"ARIS 1200 HF", "aris1200", 48, 1200, 1, 2, 1, 3},
                               {"ARIS 1200 LF", "aris1200", 48, 700, 1, 2, 0, 3}};
constexpr double kFrequencyTolerance = 0.25; ///< relative distance from the mode's frequency allowed

/// Each system's maxima (Sound Metrics' integration SDK, SonarConfig.fs systemTypeRangeMap): SamplePeriod,
/// SampleStartDelay, PulseWidth, CyclePeriod [us], window start and end [m]. A 50 m window needs a longer
/// CyclePeriod than the 65535 the frame header's comment gives.
const ArisLimits& limits_of(const ArisMode& m) {
    static const ArisLimits k1800{"ARIS 1800", 32, 36000, 40, 80000, 25.0, 50.0};
    static const ArisLimits k3000{"ARIS 3000", 26, 18000, 24, 40000, 12.0, 20.0};
    static const ArisLimits k1200{"ARIS 1200", 40, 60000, 80, 150000, 40.0, 100.0};
    return m.system_type == 1 ? k3000 : m.system_type == 0 ? k1800 : k1200;
}

/// The system an ARIS preset fixes (TheSystemType), or -1 for any other device.
int preset_system(const std::string& device) {
    if (device.rfind("aris3000", 0) == 0) return 1;
    if (device.rfind("aris1800", 0) == 0) return 0;
    if (device.rfind("aris1200", 0) == 0) return 2;
    return -1;
}

std::string khz(double f) {
    std::ostringstream o;
    o << f;
    return o.str();
}

/// The mode of the scene's device (an ARIS preset fixes the system), beam count and frequency.
const ArisMode& aris_mode(const SonarParams& sonar, const std::string& origin) {
    // A DIDSON's recordings are DDF files of an older version whose layout Sound Metrics has not published;
    // written as an ARIS 1800 file, ARIS tools would place its beams by the ARIS 1800's lens table.
    if (sonar.device.rfind("didson", 0) == 0)
        throw InputError(origin, "sonar.device",
                         sonar.device +
                             " is a DIDSON: its own file format is not public, and as an ARIS file "
                             "its beams would be read with the ARIS 1800's angles; write --mcap "
                             "instead (it carries each beam's direction)");
    const int system = preset_system(sonar.device);
    const ArisMode* best = nullptr;
    std::string counts;
    for (auto& m : kModes) {
        if (system >= 0 && int(m.system_type) != system) continue;
        const std::string n = std::to_string(m.beams);
        if (counts.find(n) == std::string::npos) counts += (counts.empty() ? "" : " or ") + n;
        if (m.beams != sonar.beams) continue;
        const double d = std::abs(sonar.frequency_khz - m.frequency_khz);
        if (!best || d < std::abs(sonar.frequency_khz - best->frequency_khz)) best = &m;
    }
    if (!best) {
        const std::string holder =
            system < 0 ? "an ARIS file" : "an ARIS file of the " + sonar.device + " preset";
        throw InputError(origin, "sonar.beams",
                         holder + " holds " + (system < 0 ? std::string("48, 64, 96 or 128") : counts) +
                             " beams, got " + std::to_string(sonar.beams));
    }
    if (std::abs(sonar.frequency_khz / best->frequency_khz - 1) > kFrequencyTolerance)
        throw InputError(origin, "sonar.frequency_khz",
                         khz(sonar.frequency_khz) + " kHz is no ARIS mode of " + std::to_string(sonar.beams) +
                             " beams: they are the " + best->name + " mode at " + khz(best->frequency_khz) +
                             " kHz (allowed within 25 %); set sonar.frequency_khz=" +
                             khz(best->frequency_khz) + " or sonar.device=" + best->preset);
    return *best;
}

le::Bytes file_header(const ArisMode& mode, const ArisTiming& timing, size_t frames, double start_time_s) {
    le::Bytes h(kHeaderBytes, 0);
    le::put<std::uint32_t>(h, 0, kArisVersion);
    le::put<std::uint32_t>(h, 4, std::uint32_t(frames));
    const std::uint64_t frame_bytes = kHeaderBytes + std::uint64_t(mode.beams) * timing.samples;
    le::put<std::uint64_t>(h, 424, kHeaderBytes + frames * frame_bytes); // FileSize
    le::put<std::uint32_t>(h, 16, std::uint32_t(mode.beams));
    le::put<std::uint32_t>(h, 24, timing.samples);
    const std::time_t start = std::time_t(start_time_s); // the recording's date: the dataset's start
    std::tm tm{};
    gmtime_r(&start, &tm);
    std::strftime(reinterpret_cast<char*>(h.data() + 48), 32, "%Y-%m-%d %H:%M:%S UTC", &tm);
    const std::string id = "sonarsim simulated frames";
    std::copy(id.begin(), id.end(), h.begin() + 80);
    return h;
}

le::Bytes frame_header(const SceneDesc& s, const ArisMode& mode, const ArisTiming& tm,
                       const ByteMapping& mapping, const Trajectory& trajectory, size_t k) {
    le::Bytes h(kHeaderBytes, 0);
    const TrajectoryPoint& p = trajectory[k];
    // Microseconds since 1970: the dataset's start plus t.
    const auto time_us = std::uint64_t(std::llround(std::max(0.0, s.exports.start_time_s + p.t_s) * 1e6));
    le::put<std::uint32_t>(h, 0, std::uint32_t(k));
    le::put<std::uint64_t>(h, 4, time_us);
    le::put<std::uint32_t>(h, 12, kArisVersion);
    le::put<std::uint64_t>(h, 20, time_us);
    le::put<std::uint32_t>(h, 68, tm.receiver_gain_db); // ReceiverGain [dB]
    le::put<float>(h, 52, float(tm.window_start_m));
    le::put<float>(h, 56, float(tm.window_length_m));
    le::put<float>(h, 92, float(mapping.lo_db)); // UserValue1, 2: the image levels of bytes 0 and 255
    le::put<float>(h, 96, float(mapping.hi_db));
    le::put<float>(h, 224, float(s.water.temperature_c));
    const Vec3d &x = p.pose.position_m, &o = p.pose.orientation_deg;
    le::put<float>(h, 232, float(x[0])); // SonarX, Y, Z [m]
    le::put<float>(h, 236, float(x[1]));
    le::put<float>(h, 240, float(x[2]));
    le::put<float>(h, 244, float(o[2])); // SonarPan = yaw, SonarTilt = pitch, SonarRoll = roll [deg]
    le::put<float>(h, 248, float(o[1]));
    le::put<float>(h, 252, float(o[0]));
    le::put<float>(h, 420, float(1e6 / tm.sample_period_us));
    le::put<std::uint32_t>(h, 436, mode.ping_mode);
    le::put<std::uint32_t>(h, 440, mode.high_frequency);
    le::put<std::uint32_t>(h, 444, tm.pulse_width_us);
    le::put<std::uint32_t>(h, 448, tm.cycle_period_us);
    le::put<std::uint32_t>(h, 452, tm.sample_period_us);
    le::put<std::uint32_t>(h, 456, 1); // TransmitEnable
    // Frames per second, as recordings hold it: from the frame before (frame 0: to the next one).
    const double dt = k > 0                   ? p.t_s - trajectory[k - 1].t_s
                      : trajectory.size() > 1 ? trajectory[1].t_s - p.t_s
                                              : 0;
    le::put<float>(h, 460, dt > 0 ? float(1 / dt) : 0.0f);
    le::put<float>(h, 464, tm.sound_speed_m_s);
    le::put<std::uint32_t>(h, 468, tm.samples);
    le::put<std::uint32_t>(h, 472, 1); // Enable150V
    le::put<std::uint32_t>(h, 476, tm.sample_start_delay_us);
    le::put<std::uint32_t>(h, 484, mode.system_type);
    le::put<std::uint32_t>(h, 516, 1);  // ReorderedSamples: [sample][beam] already
    le::put<std::uint32_t>(h, 520, 35); // Salinity: salt
    return h;
}

} // namespace

SceneDesc on_aris_samples(const SceneDesc& s, const std::string& origin, std::string& note) {
    const ArisTiming tm = aris_timing(s, limits_of(aris_mode(s.sonar, origin)), origin);
    note.clear();
    if (bins_are_samples(s.sonar, tm)) return s;
    SceneDesc out = s;
    out.sonar = on_samples(s.sonar, tm);
    auto num = significant_text;
    note = "the range grid is the ARIS samples': " + std::to_string(tm.samples) + " bins of " +
           num(tm.sample_m * 1e3, 4) + " mm from " + num(out.sonar.range_min_m, 6) + " to " +
           num(out.sonar.range_max_m, 6) + " m (asked: " + std::to_string(s.sonar.range_bins) + " from " +
           num(s.sonar.range_min_m, 6) + " to " + num(s.sonar.range_max_m, 6) +
           " m), so the file holds the rendered samples";
    return out;
}

void check_aris(const SceneDesc& s, const std::string& origin) {
    aris_timing(s, limits_of(aris_mode(s.sonar, origin)), origin);
}

void check_aris_frame_times(const SceneDesc& s, const Trajectory& frames, const std::string& origin,
                            const std::string& times_origin) {
    const ArisMode& mode = aris_mode(s.sonar, origin);
    const ArisTiming tm = aris_timing(s, limits_of(mode), origin);
    // The vendor's validation: a frame period longer than CyclePeriod x pings per frame, at most 15 frames/s
    // (SonarConfig.fs FrameRateRange).
    const double pings_us = double(tm.cycle_period_us) * mode.pings;
    const bool by_pings = pings_us * 1e-6 > 1.0 / 15;
    for (size_t k = 1; k < frames.size(); ++k) {
        const double dt = frames[k].t_s - frames[k - 1].t_s;
        if (std::ceil(dt * 1e6 - 1e-6) > pings_us && dt >= 1.0 / 15 - 1e-9) continue;
        std::ostringstream m;
        m << "frame " << k << " comes " << dt * 1e3 << " ms after the one before, sooner than the "
          << mode.name << " mode images a frame (";
        if (by_pings)
            m << mode.pings << " pings of CyclePeriod " << tm.cycle_period_us << " us = " << pings_us * 1e-3
              << " ms";
        else
            m << "at most 15 frames/s";
        m << "), which ARIS tools reject; the fastest it allows is "
          << (by_pings ? std::floor(1e8 / pings_us - 1e-9) / 100 : 15.0) << " frames/s";
        throw InputError(times_origin, "", m.str());
    }
}

ExportReport write_aris(const std::string& path, const SceneDesc& s, const Trajectory& trajectory,
                        const FrameImageSource& image, const ByteMapping& mapping,
                        const std::string& origin) {
    const ArisMode& mode = aris_mode(s.sonar, origin);
    const ArisTiming tm = aris_timing(s, limits_of(mode), origin);
    const int beams = s.sonar.beams, samples = int(tm.samples);
    AtomicFile out(path);
    out.write(file_header(mode, tm, trajectory.size(), s.exports.start_time_s));
    le::Bytes data(size_t(beams) * size_t(samples));
    std::vector<int> device_beam(static_cast<size_t>(beams));
    const BeamTable* table = sonar_grid(s.sonar)->table();
    for (int b = 0; b < beams; ++b)
        device_beam[size_t(b)] = table ? table->device_beam[size_t(b)] : beams - 1 - b;
    ExportReport report;
    report.mapping = mapping;
    if (!tm.adjusted.empty()) report.notes.push_back(tm.adjusted);
    if (!bins_are_samples(s.sonar, tm))
        report.notes.push_back(
            "resampled: the frames' " + std::to_string(s.sonar.range_bins) +
            " range bins are not the device's " + std::to_string(tm.samples) +
            " samples, so each sample interpolates the intensity of the two bins beside it "
            "(batch --aris renders on the samples)");
    for (size_t k = 0; k < trajectory.size(); ++k) {
        const PolarImage frame = image(k);
        if (frame.beams != beams || frame.bins != s.sonar.range_bins)
            throw std::runtime_error("frame " + std::to_string(k) + " is not " +
                                     std::to_string(s.sonar.range_bins) + " x " + std::to_string(beams));
        const PolarImage img = aris_resample(frame, s.sonar, tm);
        ClipCount count;
        const std::vector<std::uint8_t> bytes = image_bytes(img, mapping, count);
        // Sample-major; ARIS beam 0 is the starboard-most, our column 0 the port-most (a table numbers each
        // beam as the device does).
        for (size_t r = 0; r < size_t(samples); ++r)
            for (size_t b = 0; b < size_t(beams); ++b)
                data[r * size_t(beams) + size_t(device_beam[b])] = bytes[r * size_t(beams) + b];
        out.write(frame_header(s, mode, tm, mapping, trajectory, k));
        out.write(data);
        report.frames.push_back(count);
        report.total += count;
    }
    out.commit();
    return report;
}

} // namespace sonarsim
