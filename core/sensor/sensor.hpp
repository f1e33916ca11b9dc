// The sensor stage: from the ideal echo image (what the sampler converges, L_EN per range bin and beam) to
// what a device shows. In order (SENSORS.md 2.8): the receive beam pattern across azimuth, the matched
// filter along range, speckle (with speckle on, the three formed together as a complex field:
// speckle_field.hpp), additive noise, then time-varying gain and receiver gain. Each effect is off
// unless the scene turns it on (sensor.*), and the ideal sensor passes the image through untouched.
#pragma once
#include "core/data/polar_image.hpp"
#include "core/data/scene.hpp"
#include "core/shading/accumulate.hpp"

#include <cstdint>

namespace sonarsim {

/// True when every effect of the sensor stage is off: each row of the parameter table with an ideal value
/// holds it (the elevation pattern, acting in the trace, aside).
bool sensor_is_ideal(const SceneDesc& scene);

/// The device's image [dB]: L_EN after the receive pattern, range response, speckle and noise, plus TVG
/// and gain. `inputs` are needed when needs_sensor_inputs(scene). Intensities are carried in double
/// precision relative to the image's peak, so nothing within 3000 dB of it underflows (the speckle field:
/// single precision within 759 dB of the strongest sample of its 8 range bins, form_speckle).
PolarImage apply_sensor(const PolarImage& ideal, const SensorInputs* inputs, const SceneDesc& scene,
                        double alpha_db_per_m);

/// Time-varying gain at range r [dB]: N log10(r / 1 m) + 2 alpha r for the law N log R (0 when off).
double tvg_db(Tvg law, double range_m, double alpha_db_per_m);

/// splitmix64's finaliser: a 64-bit mix.
inline std::uint64_t mix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

} // namespace sonarsim
