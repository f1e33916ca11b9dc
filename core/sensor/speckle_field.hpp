// Speckle with the device's grain (docs/model.md, "The sensor"): a circular complex Gaussian field drawn per
// sample of the ideal image, keyed by the world point the sample stands for, formed coherently through the
// receive pattern's amplitude across azimuth and the matched filter's amplitude response along range, then
// |.|^2. Neighbouring beams share speckle in proportion to their overlap, range bins in proportion to the
// pulse length, and the mean is the intensity path's (sum of P I, then the range kernel) exactly.
#pragma once
#include "core/data/pose.hpp"
#include "core/data/scene.hpp"
#include "core/sensor/keyed_variates.hpp"
#include "core/sensor/sensor.hpp"
#include "core/shading/accumulate.hpp"

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace sonarsim {

/// Keys of world points: a point is quantised on a grid of 2^q metres, the largest power of two at or below
/// half of `cell_m` (so the grid is the same at all ranges within an octave and a scatterer keeps its key
/// while the sonar moves over it); the key hashes the seed, q and the grid cell (keyed_variates.hpp).
class WorldKeyGrid {
  public:
    WorldKeyGrid(std::uint64_t seed, double cell_m);
    /// The keys of n points.
    void keys(int n, const keyed::RaisedPoints& p, std::uint32_t* key) const {
        keyed::world_cell_keys(n, p, inv_q_per_m_, row_seed_, key);
    }

  private:
    std::uint32_t row_seed_;
    double inv_q_per_m_;
};

/// Where the sonar looks from: the world point at range r along a direction of the fan (`ahead`, unit,
/// horizontal in the sonar frame) raised by the elevation e [rad] (NaN: 0) towards `up` is
/// origin + r sin(e) up + r cos(e) ahead.
struct SonarFrame {
    explicit SonarFrame(const SceneDesc& s);
    glm::dvec3 origin, up;
    glm::dmat3 R;
    glm::dvec3 ahead(double azimuth_rad) const; ///< R (cos a, sin a, 0)
    /// sin and cos of an elevation angle |e| <= pi/2 (Taylor to e^9 and e^10: errors below 2e-4 and 5e-7 at
    /// pi/2, 1e-8 within 0.5 rad): only used to place a key, where any fixed function of e does.
    static double key_sin(double e) {
        const double e2 = e * e;
        return e *
               (1 - e2 * (1.0 / 6) * (1 - e2 * (1.0 / 20) * (1 - e2 * (1.0 / 42) * (1 - e2 * (1.0 / 72)))));
    }
    static double key_cos(double e) {
        const double e2 = e * e;
        return 1 - e2 * 0.5 *
                       (1 - e2 * (1.0 / 12) *
                                (1 - e2 * (1.0 / 30) * (1 - e2 * (1.0 / 56) * (1 - e2 * (1.0 / 90)))));
    }
    /// A row of cells at range r raised by their beam's elevation: cell j's rise r sin(e) along `up` and
    /// reach r cos(e) along its direction, e = elevation_rad[j / per_beam] (NaN: 0), a beam's cells sharing
    /// it.
    void raise(double r_m, int cells, int per_beam, const float* elevation_rad, double* rise_m,
               double* reach_m) const;
    /// The points origin + rise up + reach ahead of n cells (directions ahead_x, ahead_y, ahead_z).
    keyed::RaisedPoints points(const double* rise_m, const double* reach_m, const double* ahead_x,
                               const double* ahead_y, const double* ahead_z) const {
        return {
            {origin.x, origin.y, origin.z}, {up.x, up.y, up.z}, rise_m, reach_m, ahead_x, ahead_y, ahead_z};
    }
};

/// The speckled intensity per (range bin, beam) [bin * beams + beam], relative to 10^(peak_db / 10), from the
/// levels L_EN [dB] of `src` per (range bin, source column) (J = beams x sub columns, the fine ones when the
/// receive pattern is formed from them; peak_db their largest): the field sqrt(I) z, I = 10^(L_EN / 10),
/// z ~ CN(0, 1) keyed by the sample's world point (range, column azimuth, the beam's mean elevation in
/// `inputs`, quantised to half the sample spacing), summed over the columns with the receive pattern's
/// amplitude (when the window is on), convolved along range with the matched filter's amplitude response,
/// then |.|^2. The field and the beams are carried in single precision relative to the strongest sample of
/// each 8 range bins (a sample more than 759 dB below that one counts as 0).
/// `block_peaks`: speckle_block_peaks(src) when the caller has it already (none: form_speckle finds them).
std::vector<double> form_speckle(const PolarImage& src, double peak_db, const SensorInputs& inputs,
                                 const SceneDesc& scene, const std::vector<float>* block_peaks = nullptr);

/// The largest level [dB] of each block of range bins whose field form_speckle carries relative to one
/// amplitude (-inf where nothing echoes), found in parallel; their largest is the image's.
std::vector<float> speckle_block_peaks(const PolarImage& src);

/// The largest of n levels [dB] (-inf when there is none; NaN is passed over).
float max_level(std::size_t n, const float* level_db);

/// Each row of `rows` (K rows of `width` values) replaced by the h-weighted sum of its neighbours along
/// range: out_k = sum_t h[t + half] x_(k - t).
void convolve_range(std::vector<double>& rows, int K, int width, const std::vector<double>& h);

} // namespace sonarsim
