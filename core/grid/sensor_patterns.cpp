#include "core/grid/sensor_patterns.hpp"

#include "core/data/pose.hpp"
#include "core/base/recent_shared.hpp"
#include "core/grid/sonar_grid.hpp"

#include <algorithm>
#include <memory>
#include <cmath>
#include <numeric>

namespace sonarsim {
namespace {

constexpr int kStepsPerWidth = 256;
constexpr int kArrayElements = 64;
constexpr double kSincHalfPower = 1.39156;       ///< x where sin x / x = 1 / sqrt 2
constexpr double kGaussianTracedWidths = 1.5786; ///< |e| / phi3 where the gaussian is at -30 dB
constexpr double kSincTracedWidths = 2.2575;     ///< |e| / phi3 at the second null of sinc^2

/// Element weights of the window over kArrayElements elements.
std::vector<double> window_weights(AzimuthWindow window, double taylor_sidelobe_db) {
    const int M = kArrayElements;
    std::vector<double> w(size_t(M), 1.0);
    if (window == AzimuthWindow::Hann) {
        for (int k = 0; k < M; ++k) w[size_t(k)] = 0.5 - 0.5 * std::cos(2 * kPi * (k + 1) / (M + 1));
    } else if (window == AzimuthWindow::Taylor) {
        // Taylor (1955) as in Carrara et al.: A = acosh(10^(SLL/20)) / pi, nbar >= 2 A^2 + 1/2.
        const double A = std::acosh(std::pow(10.0, -taylor_sidelobe_db / 20)) / kPi;
        const int nbar = std::max(4, int(std::ceil(2 * A * A + 0.5)));
        const double sigma2 = nbar * nbar / (A * A + (nbar - 0.5) * (nbar - 0.5));
        std::vector<double> F(size_t(nbar), 0.0);
        for (int m = 1; m < nbar; ++m) {
            double num = 1, den = 1;
            for (int n = 1; n < nbar; ++n) {
                num *= 1 - m * m / (sigma2 * (A * A + (n - 0.5) * (n - 0.5)));
                if (n != m) den *= 1 - double(m * m) / double(n * n);
            }
            F[size_t(m)] = (m % 2 ? 0.5 : -0.5) * num / den;
        }
        for (int k = 0; k < M; ++k) {
            const double xi = (k - 0.5 * M + 0.5) / M;
            double v = 1;
            for (int m = 1; m < nbar; ++m) v += 2 * F[size_t(m)] * std::cos(2 * kPi * m * xi);
            w[size_t(k)] = v;
        }
    }
    return w;
}

/// AF(psi) of the weighted array (real, the weights being symmetric), 1 at psi = 0.
double array_factor(const std::vector<double>& w, double psi) {
    const double mid = 0.5 * (double(w.size()) - 1);
    double sum = 0, norm = 0;
    for (size_t k = 0; k < w.size(); ++k) sum += w[k] * std::cos((double(k) - mid) * psi), norm += w[k];
    return sum / norm;
}

/// |AF(psi)|^2, 1 at psi = 0.
double array_intensity(const std::vector<double>& w, double psi) {
    const double af = array_factor(w, psi);
    return af * af;
}

} // namespace

ElevationWeight::ElevationWeight(const SceneDesc& s)
    : kind_(s.sensor.elevation_pattern), phi3_rad_(deg2rad(elevation_beamwidth_deg(s))) {
    // A pattern's support stops at the transducer's face: what lies behind it (beyond 89.5 deg off the
    // axis) is baffled, so a wide side-scan beam is traced over the front half-space only.
    traced_rad_ =
        kind_ == ElevationPattern::Flat
            ? deg2rad(s.sonar.elevation_fov_deg)
            : std::min(deg2rad(kMaxPatternTracedDeg),
                       2 * (kind_ == ElevationPattern::Gaussian ? kGaussianTracedWidths : kSincTracedWidths) *
                           phi3_rad_);
}

double ElevationWeight::operator()(double e) const {
    if (kind_ == ElevationPattern::Flat) return 1.0;
    const double u = e / phi3_rad_;
    if (kind_ == ElevationPattern::Gaussian) return std::exp(-4 * std::log(2.0) * u * u);
    const double x = kSincHalfPower * 2 * u;
    if (std::abs(x) < 1e-8) return 1.0;
    const double s = std::sin(x) / x;
    return s * s;
}

double elevation_beamwidth_deg(const SceneDesc& s) {
    return s.sensor.elevation_beamwidth_deg > 0 ? s.sensor.elevation_beamwidth_deg
                                                : s.sonar.elevation_fov_deg;
}

double azimuth_beamwidth_deg(const SceneDesc& s) {
    return s.sensor.azimuth_beamwidth_deg > 0 ? s.sensor.azimuth_beamwidth_deg
                                              : s.sonar.azimuth_fov_deg / s.sonar.beams;
}

double receive_beamwidth_rad(const SceneDesc& s, const SonarGrid& grid, int b) {
    if (s.sensor.azimuth_window == AzimuthWindow::None) return grid.beam_width_rad(b);
    const double bw = deg2rad(azimuth_beamwidth_deg(s));
    // A flat array steered to theta_b: the beam widens as 1 / cos theta_b (held below 10x, at 84 deg).
    // A lens beam from a table: its -3 dB width scales with its own width (the preset gives the mean).
    return s.sensor.beamformer == Beamformer::Array ? bw / std::max(0.1, std::cos(grid.beam_azimuth_rad(b)))
           : grid.table()                           ? bw * grid.beam_width_rad(b) / grid.spacing_rad
                                                    : bw;
}

ArrayPattern::ArrayPattern(AzimuthWindow window, double taylor_sidelobe_db) {
    const std::vector<double> w = window_weights(window, taylor_sidelobe_db);
    // psi3: where |AF|^2 first falls to 1/2 (stepping, then bisection).
    double lo = 0, hi = 1e-3;
    while (array_intensity(w, hi) > 0.5) lo = hi, hi *= 1.25;
    for (int i = 0; i < 100; ++i) {
        const double mid = 0.5 * (lo + hi);
        (array_intensity(w, mid) > 0.5 ? lo : hi) = mid;
    }
    const double psi3 = 0.5 * (lo + hi);
    const int n = int(kAzimuthPatternExtent * kStepsPerWidth) + 2;
    table_.resize(size_t(n)), sign_.resize(size_t(n));
    for (int i = 0; i < n; ++i) {
        const double af = array_factor(w, 2 * psi3 * i / kStepsPerWidth);
        table_[size_t(i)] = af * af, sign_[size_t(i)] = af < 0 ? -1 : 1;
    }
}

const ArrayPattern& array_pattern(AzimuthWindow window, double taylor_sidelobe_db) {
    // A few hundred thousand cosines per table: built once per (window, level) in the process, not on
    // every run of the sensor stage. Entries are never removed, so references stay valid.
    static std::mutex m;
    static std::vector<std::pair<std::pair<AzimuthWindow, double>, std::unique_ptr<const ArrayPattern>>> made;
    const double level = window == AzimuthWindow::Taylor ? taylor_sidelobe_db : 0;
    std::lock_guard<std::mutex> lock(m);
    for (auto& [key, pattern] : made)
        if (key.first == window && key.second == level) return *pattern;
    made.emplace_back(std::pair{window, level}, std::make_unique<const ArrayPattern>(window, level));
    return *made.back().second;
}

double ArrayPattern::operator()(double x) const {
    const double t = std::abs(x) * kStepsPerWidth;
    const size_t i = size_t(t);
    if (i + 1 >= table_.size()) return 0.0;
    const double f = t - double(i);
    return table_[i] * (1 - f) + table_[i + 1] * f;
}

double ArrayPattern::amplitude(double x) const {
    const double t = std::abs(x) * kStepsPerWidth;
    const size_t i = std::min(size_t(t + 0.5), sign_.size() - 1); // the nearest sample's sign
    return sign_[i] * std::sqrt((*this)(x));
}

double ArrayPattern::first_sidelobe_db() const {
    size_t i = 1;
    while (i + 1 < table_.size() && table_[i + 1] <= table_[i]) ++i; // down the main lobe to the null
    while (i + 1 < table_.size() && table_[i + 1] >= table_[i]) ++i; // up to the first sidelobe
    return 10 * std::log10(table_[i]);
}

double ArrayPattern::extent(double floor_db) const {
    const double floor = std::pow(10.0, floor_db / 10);
    size_t i = table_.size() - 1;
    while (i > 0 && table_[i] < floor) --i;
    return std::min(kAzimuthPatternExtent, double(i + 1) / kStepsPerWidth);
}

int azimuth_subcolumns(const SceneDesc& s) {
    if (s.sensor.azimuth_window == AzimuthWindow::None) return 1;
    const std::shared_ptr<const SonarGrid> grid_ptr =
        sonar_grid(s.sonar); // held: the registry keeps only what someone holds
    const SonarGrid& grid = *grid_ptr;
    double spacing = 0; // the widest beam's [deg]: every beam gets four columns per -3 dB width
    for (int b = 0; b < grid.beams; ++b) spacing = std::max(spacing, grid.beam_width_deg(b));
    return std::clamp(int(std::ceil(4 * spacing / azimuth_beamwidth_deg(s) - 1e-9)), 1, 8);
}

AzimuthBeamforming make_azimuth_beamforming(const SceneDesc& s, bool amplitudes) {
    AzimuthBeamforming f;
    const std::shared_ptr<const SonarGrid> grid_ptr =
        sonar_grid(s.sonar); // held: the registry keeps only what someone holds
    const SonarGrid& grid = *grid_ptr;
    const int N = grid.beams, S = azimuth_subcolumns(s);
    f.beams = N, f.sub = S;
    const ArrayPattern& pattern = array_pattern(s.sensor.azimuth_window, s.sensor.taylor_sidelobe_db);
    std::vector<double> centre(static_cast<size_t>(N)), width(static_cast<size_t>(N));
    double widest = 0;
    for (int b = 0; b < N; ++b) {
        centre[size_t(b)] = grid.beam_azimuth_rad(b);
        width[size_t(b)] = receive_beamwidth_rad(s, grid, b);
        widest = std::max(widest, width[size_t(b)]);
    }
    const double extent = pattern.extent(kAzimuthPatternFloorDb);
    const int reach = int(std::ceil(extent * widest / grid.narrowest_beam_rad())) + 1;
    const int J = N * S;
    f.first.resize(size_t(J)), f.count.resize(size_t(J)), f.offset.resize(size_t(J) + 1);
    for (int j = 0; j < J; ++j) {
        const double tj = grid.column_azimuth_rad(j, S);
        const int bc = j / S, b0 = std::max(0, bc - reach), b1 = std::min(N - 1, bc + reach);
        int first = -1, last = -2;
        for (int b = b0; b <= b1; ++b)
            if (std::abs(tj - centre[size_t(b)]) <= extent * width[size_t(b)]) {
                if (first < 0) first = b;
                last = b;
            }
        f.offset[size_t(j)] = f.weight.size();
        f.first[size_t(j)] = std::max(first, 0), f.count[size_t(j)] = last - first + 1;
        for (int b = first; b <= last; ++b) {
            const double x = (tj - centre[size_t(b)]) / width[size_t(b)];
            f.weight.push_back(pattern(x));
            if (amplitudes) f.amplitude.push_back(pattern.amplitude(x));
        }
    }
    f.offset[size_t(J)] = f.weight.size();
    return f;
}

std::shared_ptr<const AzimuthBeamforming> shared_azimuth_beamforming(const SceneDesc& s, bool amplitudes) {
    // Everything make_azimuth_beamforming reads: the grid (held in the key, so that the pointer stays its
    // own), the window and its level, the broadside -3 dB width and the beamformer.
    struct Key {
        std::shared_ptr<const SonarGrid> grid;
        AzimuthWindow window;
        double taylor_db, width_deg;
        Beamformer beamformer;
        bool amplitudes;
        bool operator==(const Key& o) const {
            return grid == o.grid && window == o.window && taylor_db == o.taylor_db &&
                   width_deg == o.width_deg && beamformer == o.beamformer && amplitudes == o.amplitudes;
        }
    };
    static RecentShared<Key, AzimuthBeamforming, 4> kept; // a few simulators may alternate
    const Key key{sonar_grid(s.sonar),      s.sensor.azimuth_window, s.sensor.taylor_sidelobe_db,
                  azimuth_beamwidth_deg(s), s.sensor.beamformer,     amplitudes};
    return kept.get(key, [&] {
        return std::make_shared<const AzimuthBeamforming>(make_azimuth_beamforming(s, amplitudes));
    });
}

std::vector<double> range_amplitude_kernel(Pulse pulse, double res_m, double dr_m) {
    if (!(res_m > 0)) return {1.0};
    const double extent = pulse == Pulse::Cw ? res_m : 8 * res_m;
    const int h = int(std::floor(extent / dr_m)); // bin centres within `extent` of 0
    std::vector<double> g(size_t(2 * h + 1));
    double energy = 0;
    for (int t = -h; t <= h; ++t) {
        const double u = std::abs(t) * dr_m / res_m;
        const double a = pulse == Pulse::Cw ? std::max(0.0, 1 - u)
                         : u < 1e-9         ? 1.0
                                            : std::sin(kPi * u) / (kPi * u);
        g[size_t(t + h)] = a, energy += a * a;
    }
    for (double& x : g) x /= std::sqrt(energy);
    return g;
}

std::vector<double> range_kernel(Pulse pulse, double res_m, double dr_m) {
    if (!(res_m > 0)) return {1.0};
    const double extent = pulse == Pulse::Cw ? res_m : 8 * res_m;
    const int h = int(std::ceil(extent / dr_m + 0.5)); // bins reaching within `extent` of 0
    auto k = [&](double x) {
        const double u = std::abs(x) / res_m;
        if (pulse == Pulse::Cw) return u < 1 ? (1 - u) * (1 - u) : 0.0;
        if (u > 8) return 0.0;
        if (u < 1e-9) return 1.0;
        const double s = std::sin(kPi * u) / (kPi * u);
        return s * s;
    };
    constexpr int kSub = 64; // midpoint rule inside each bin
    std::vector<double> w(size_t(2 * h + 1), 0.0);
    for (int t = -h; t <= h; ++t) {
        double sum = 0;
        for (int i = 0; i < kSub; ++i) sum += k((t - 0.5 + (i + 0.5) / kSub) * dr_m);
        w[size_t(t + h)] = sum / kSub;
    }
    const double total = std::accumulate(w.begin(), w.end(), 0.0);
    for (double& x : w) x /= total;
    return w;
}

} // namespace sonarsim
