// The range grid of an ARIS recording: the water's sound speed, whole-microsecond SamplePeriod and
// SampleStartDelay within the vendor's documented ranges (file SDK, FrameHeader.h), and our range bins
// resampled onto the device's samples.
#pragma once
#include "core/display/polar_image.hpp"
#include "core/scene/scene.hpp"

#include <cstdint>
#include <string>

namespace sonarsim {

/// Range geometry of an ARIS frame: sample j at range window_start_m + j * sample_m, where
/// window_start_m = SampleStartDelay c / 2 and sample_m = SamplePeriod c / 2 (c = SoundSpeed, the
/// water's, as the float the header holds).
struct ArisTiming {
    std::uint32_t sample_period_us = 0, sample_start_delay_us = 0, samples = 0;
    std::uint32_t pulse_width_us = 0, cycle_period_us = 0;
    float sound_speed_m_s = 0;
    double window_start_m = 0, sample_m = 0, window_length_m = 0; ///< window_length_m = samples x sample_m
};

/// The grid of the scene's range window: SamplePeriod the whole us nearest 2 bin / c (4-100 us, else
/// InputError naming sonar.range_bins); SampleStartDelay the whole us of the first bin's centre (930-65535
/// us, else sonar.range_min_m); as many samples as cover the window; PulseWidth 2 sensor.range_resolution_m
/// / c, or one sample period when that is 0 (4-100 us, else sensor.range_resolution_m); CyclePeriod
/// SSD + SP samples + 360 us (1802 us up to `max_cycle_us`, else sonar.range_max_m).
ArisTiming aris_timing(const SceneDesc& scene, std::uint32_t max_cycle_us, const std::string& origin);

/// The image on the device's samples: per beam, the intensity 10^(L/10) interpolated linearly between
/// the centres of the bins either side of each sample's range (the nearest bin's level beyond the first
/// and last centre); -inf where neither echoes.
PolarImage aris_resample(const PolarImage& image, const SonarParams& sonar, const ArisTiming& timing);

} // namespace sonarsim
