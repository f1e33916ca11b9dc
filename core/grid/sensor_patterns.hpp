// The sensor's beam patterns and range response (SENSORS.md 2.1, 2.2, 2.5): the two-way elevation pattern
// that weights each ray, the receive pattern that forms each beam from a finer azimuth grid, and the
// matched filter's intensity response along range. All are intensity patterns with peak 1.
#pragma once
#include "core/data/scene.hpp"
#include "core/grid/sonar_grid.hpp"

#include <memory>
#include <vector>

namespace sonarsim {

/// Widest elevation span a pattern is traced over [deg]: the front half-space of the transducer's face.
constexpr double kMaxPatternTracedDeg = 179;

/// Two-way elevation pattern B_v(e) with -3 dB full width phi3:
///   gaussian: B = exp(-4 ln 2 e^2 / phi3^2), traced out to -30 dB (|e| <= 1.579 phi3);
///   sinc:     B = (sin x / x)^2 with x = 1.39156 * 2 e / phi3 (B = 1/2 at e = phi3 / 2), traced out to its
///             second null (|e| <= 2.258 phi3: the main lobe and the first sidelobe, -13.3 dB);
///   flat:     the hard aperture sonar.elevation_fov_deg, B = 1 inside.
class ElevationWeight {
  public:
    explicit ElevationWeight(const SceneDesc& scene);
    bool flat() const { return kind_ == ElevationPattern::Flat; }
    /// B_v at elevation e [rad] (1 for flat).
    double operator()(double e_rad) const;
    /// Elevation span the rays cover [rad]: the aperture when flat, the pattern's traced support otherwise
    /// (at most kMaxPatternTracedDeg).
    double traced_fov_rad() const { return traced_rad_; }

  private:
    ElevationPattern kind_;
    double phi3_rad_, traced_rad_;
};

/// -3 dB width of the elevation pattern [deg] (sensor.elevation_beamwidth_deg, 0: sonar.elevation_fov_deg).
double elevation_beamwidth_deg(const SceneDesc& scene);
/// -3 dB width of the receive beam at broadside [deg] (sensor.azimuth_beamwidth_deg, 0: the beam spacing).
double azimuth_beamwidth_deg(const SceneDesc& scene);

/// -3 dB width of beam b's receive response [rad]: with a receive pattern (sensor.azimuth_window not none)
/// the broadside width, widened as 1 / cos of the beam's azimuth for an array (held below 10x), scaled with
/// a table beam's own width for a lens; without one, the beam's own hard-edged cell.
double receive_beamwidth_rad(const SceneDesc& scene, const SonarGrid& grid, int b);

/// Intensity pattern of a line array (64 elements, half-wavelength) with the window, |AF|^2 normalised to 1
/// at the peak, as a function of x = (angle off the beam axis) / (-3 dB full width): 1/2 at x = +-1/2.
/// Tabulated once per window out to |x| = kAzimuthPatternExtent.
class ArrayPattern {
  public:
    ArrayPattern(AzimuthWindow window, double taylor_sidelobe_db);
    double operator()(double x) const;
    /// The amplitude pattern AF (real: the window is symmetric) with the sign of the array factor and the
    /// magnitude sqrt of operator(), so that amplitude(x)^2 is exactly the intensity pattern.
    double amplitude(double x) const;
    /// The first sidelobe's level [dB], found on the table (for tests and docs).
    double first_sidelobe_db() const;
    /// The |x| beyond which the pattern stays below `floor_db` (at most kAzimuthPatternExtent).
    double extent(double floor_db) const;

  private:
    std::vector<double> table_;     ///< at x = i / kStepsPerWidth
    std::vector<signed char> sign_; ///< sign of AF at the same x
};

/// The pattern of a window (and, for taylor, its sidelobe level), made once per process and shared.
const ArrayPattern& array_pattern(AzimuthWindow window, double taylor_sidelobe_db);

/// The pattern is applied out to where it stays below kAzimuthPatternFloorDb, at most this many -3 dB widths
/// either side of a beam's axis (rect: sidelobes there are still at about -30 dB; hann: 4.6 widths).
constexpr double kAzimuthPatternExtent = 12.0;
constexpr double kAzimuthPatternFloorDb = -45.0;

/// Fine azimuth columns per beam that the receive pattern needs: enough for 4 per -3 dB width, at most 8.
/// 1 when the pattern is off.
int azimuth_subcolumns(const SceneDesc& scene);

/// Receive beam forming as a sparse matrix: output beam b = sum over fine columns j of w(j, b) E_j, with
/// w = pattern((theta_j - theta_b) / width_b) (width_b = the broadside width, over cos(theta_b) for
/// "array"). Stored per fine column j: the beams [first[j], first[j] + count[j]) and their weights.
struct AzimuthBeamforming {
    int beams = 0, sub = 1;
    std::vector<int> first, count;
    std::vector<std::size_t> offset; ///< into weight
    std::vector<double> weight;
    std::vector<double>
        amplitude; ///< with `amplitudes`: the signed sqrt of each weight (ArrayPattern::amplitude)
};
AzimuthBeamforming make_azimuth_beamforming(const SceneDesc& scene, bool amplitudes = false);

/// make_azimuth_beamforming's result for the scene, shared: made once per geometry and pattern (the sonar
/// grid, the window and its level, the -3 dB width, the beamformer) and kept for the next frames, which run
/// the sensor stage on the same geometry.
std::shared_ptr<const AzimuthBeamforming> shared_azimuth_beamforming(const SceneDesc& scene, bool amplitudes);

/// The matched filter's intensity response sampled on range bins of width dr_m: weights of bins -h..h
/// (h = (size - 1) / 2), each the kernel's integral over the bin, summing to 1. cw: (1 - |x| / dr)^2 for
/// |x| < dr (the squared triangle); chirp: sinc^2(x / dr) out to +-8 dr. A single 1 when the resolution
/// is 0.
std::vector<double> range_kernel(Pulse pulse, double resolution_m, double dr_m);

/// The matched filter's amplitude response sampled at the bin centres t dr_m (the device samples the filter's
/// output): cw the triangle 1 - |x| / dr, chirp sinc(x / dr) out to +-8 dr; scaled so that the squares sum
/// to 1 (energy kept). A single 1 when the resolution is below a bin.
std::vector<double> range_amplitude_kernel(Pulse pulse, double resolution_m, double dr_m);

} // namespace sonarsim
