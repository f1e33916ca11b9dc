// The range grid of an ARIS recording: the water's sound speed, whole-microsecond SamplePeriod and
// SampleStartDelay within the vendor's documented ranges (file SDK, FrameHeader.h), and our range bins
// resampled onto the device's samples.
#pragma once
#include "core/data/polar_image.hpp"
#include "core/data/scene.hpp"

#include <cstdint>
#include <string>

namespace sonarsim {

/// What one ARIS system allows of the acoustic settings (Sound Metrics' integration SDK, SonarConfig.fs: the
/// engineering command list's ranges, each system's maxima). The minima are every system's: SamplePeriod 4
/// us, SampleStartDelay 930 us, PulseWidth 4 us, CyclePeriod 1802 us, 128 samples per beam.
struct ArisLimits {
    const char* system; ///< "ARIS 3000"
    std::uint32_t sample_period_max_us, sample_start_delay_max_us, pulse_width_max_us, cycle_period_max_us;
    double window_start_max_m, window_end_max_m;
};
constexpr std::uint32_t kArisMaxSamples = 4096;
/// An ARIS receiver's gain in whole dB, 0 to this (ARIS Integration SDK: ReceiverGain 0-24 dB).
constexpr std::uint32_t kArisMaxReceiverGainDb = 24;

/// Range geometry of an ARIS frame: sample j at range window_start_m + j * sample_m, where
/// window_start_m = SampleStartDelay c / 2 and sample_m = SamplePeriod c / 2 (c = SoundSpeed, the
/// water's, as the float the header holds).
struct ArisTiming {
    std::uint32_t sample_period_us = 0, sample_start_delay_us = 0, samples = 0;
    std::uint32_t pulse_width_us = 0, cycle_period_us = 0;
    std::uint32_t receiver_gain_db = 0; ///< ReceiverGain: sensor.gain_db, the nearest whole dB in 0-24
    float sound_speed_m_s = 0;
    double window_start_m = 0, sample_m = 0, window_length_m = 0; ///< window_length_m = samples x sample_m
    /// What the grid chose that the scene did not ask for, as the nearest legal setting; empty when nothing.
    std::string adjusted;
};

/// The grid of the scene's range window within `limits` (else an InputError naming the key and the limit):
/// SamplePeriod the whole us nearest 2 bin / c (sonar.range_bins); SampleStartDelay the whole us of the first
/// bin's centre, its window start within the system's (sonar.range_min_m); as many samples as cover the
/// window, one fewer when the last would end past the system's window end (`adjusted` says so), 128-4096
/// (sonar.range_bins); PulseWidth 2 sensor.range_resolution_m / c, or one sample period when that is 0
/// (sensor.range_resolution_m); CyclePeriod SSD + SP samples + 360 us (sonar.range_max_m); ReceiverGain
/// sensor.gain_db, the nearest whole dB in 0-24 (`adjusted` says so when that differs).
ArisTiming aris_timing(const SceneDesc& scene, const ArisLimits& limits, const std::string& origin);

/// `v` to `digits` significant digits, as the ARIS writer's messages quote values.
std::string significant_text(double v, int digits);

/// True when the sonar's range bins are the device's samples of `timing`: one bin per sample, each centred
/// on its sample's range (to 1e-6 of a sample).
bool bins_are_samples(const SonarParams& sonar, const ArisTiming& timing);

/// The sonar with its range window and bins on the samples of `timing`: range_bins = SamplesPerBeam, bin j
/// centred on sample j's range (range_min_m half a sample before the first, range_max_m half a sample past
/// the last). aris_timing of the result gives `timing` again.
SonarParams on_samples(SonarParams sonar, const ArisTiming& timing);

/// The image on the device's samples: the image itself when its bins are the samples (bins_are_samples);
/// otherwise per beam, the intensity 10^(L/10) interpolated linearly between
/// the centres of the bins either side of each sample's range (the nearest bin's level beyond the first
/// and last centre); -inf where neither echoes.
PolarImage aris_resample(const PolarImage& image, const SonarParams& sonar, const ArisTiming& timing);

} // namespace sonarsim
