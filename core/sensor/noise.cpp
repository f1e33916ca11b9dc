// Noise: |sqrt(I) + n|^2, n a circular complex Gaussian of power 1 in L_EN units (the noise level L_N),
// keyed by the seed, the pose (and a ping's own draw) and the cell: stable while nothing moves, redrawn
// when the sonar moves.
#include "core/sensor/row_effects.hpp"

#include "core/base/fast_math.hpp"
#include "core/sensor/keyed_variates.hpp"
#include "core/sensor/sensor.hpp"

#include <cmath>

namespace sonarsim {
namespace {

/// A key for everything that decides where the sonar looks from (and which ping it is): noise stays put
/// while nothing moves.
std::uint64_t pose_key(const SceneDesc& s) {
    std::uint64_t h = mix64(std::uint64_t(s.sensor.seed) ^ 0x6e6f697365ULL); // "noise"
    for (double v : s.sonar.pose.position_m) h = mix64(h ^ fast::bits_of(v));
    for (double v : s.sonar.pose.orientation_deg) h = mix64(h ^ fast::bits_of(v));
    if (s.sensor.noise_draw) h = mix64(h ^ s.sensor.noise_draw); // a ping's own draw (an image has none)
    return h;
}

/// |sqrt(v) + n|^2 for a row of intensities v, n = sigma sqrt(E) e^(i phi) circular complex Gaussian of power
/// sigma^2 keyed by the row's key and the beam (key, power, cos_phase, sin_phase: scratch of n values).
SONARSIM_SIMD_CLONES void add_noise(int n, std::uint32_t row_key, double noise_power, std::uint32_t* key,
                                    float* power, float* cos_phase, float* sin_phase, double* v) {
    for (int b = 0; b < n; ++b) key[b] = keyed::mix32(row_key + std::uint32_t(b));
    keyed::exp_phasors(n, key, power, cos_phase, sin_phase); // the sine unused
    const double sigma = std::sqrt(noise_power);
    for (int b = 0; b < n; ++b) {
        const double E = power[b];
        v[b] = v[b] + noise_power * E + 2 * sigma * std::sqrt(v[b] * E) * double(cos_phase[b]);
    }
}

class Noise final : public RowEffect {
  public:
    explicit Noise(const RowContext& c)
        : power_(std::pow(10.0, -c.peak_db / 10)), // L_EN of noise is 0 dB
          seed_(pose_key(c.scene)), beams_(c.grid.beams) {}

    void apply(int bin, double, double* v) const override {
        struct Scratch {
            std::vector<std::uint32_t> key;
            std::vector<float> power, cos_phase, sin_phase;
        };
        thread_local Scratch w; // a leaf task's: nothing else runs on this thread while it is in use
        w.key.resize(size_t(beams_));
        for (auto* a : {&w.power, &w.cos_phase, &w.sin_phase}) a->resize(size_t(beams_));
        const std::uint32_t row_key = keyed::fold(mix64(seed_ ^ std::uint64_t(bin)));
        add_noise(beams_, row_key, power_, w.key.data(), w.power.data(), w.cos_phase.data(),
                  w.sin_phase.data(), v);
    }

  private:
    double power_;
    std::uint64_t seed_;
    int beams_;
};

} // namespace

std::unique_ptr<const RowEffect> make_noise(const RowContext& c) {
    if (!c.scene.sensor.noise || !(std::pow(10.0, -c.peak_db / 10) > 0)) return nullptr; // none, or below
    return std::make_unique<Noise>(c);                                                   // double's range
}

} // namespace sonarsim
