#include "core/analysis/compare.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sonarsim {
namespace {

constexpr double kNegInf = -std::numeric_limits<double>::infinity();

/// Summed-area table of a K x N field, (K + 1) x (N + 1).
std::vector<double> summed(const std::vector<double>& v, int K, int N) {
    std::vector<double> s(size_t(K + 1) * size_t(N + 1), 0.0);
    for (int k = 0; k < K; ++k)
        for (int b = 0; b < N; ++b)
            s[size_t(k + 1) * size_t(N + 1) + size_t(b + 1)] =
                v[size_t(k) * size_t(N) + size_t(b)] + s[size_t(k) * size_t(N + 1) + size_t(b + 1)] +
                s[size_t(k + 1) * size_t(N + 1) + size_t(b)] - s[size_t(k) * size_t(N + 1) + size_t(b)];
    return s;
}

double box(const std::vector<double>& s, int N, int k0, int k1, int b0,
           int b1) { // rows [k0,k1), cols [b0,b1)
    auto at = [&](int k, int b) { return s[size_t(k) * size_t(N + 1) + size_t(b)]; };
    return at(k1, b1) - at(k0, b1) - at(k1, b0) + at(k0, b0);
}

double quantile(std::vector<double> v, double q) {
    if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
    const size_t i = std::min(v.size() - 1, size_t(q * double(v.size())));
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(i), v.end());
    return v[i];
}

/// Correlation coefficient of n with itself shifted by (dk, db), over pairs of used samples.
double lag_correlation(const std::vector<double>& n, const std::vector<char>& used, int K, int N, int dk,
                       int db, double mean, double var) {
    double sum = 0;
    long pairs = 0;
    for (int k = 0; k + dk < K; ++k)
        for (int b = 0; b + db < N; ++b) {
            const size_t i = size_t(k) * size_t(N) + size_t(b),
                         j = size_t(k + dk) * size_t(N) + size_t(b + db);
            if (!used[i] || !used[j]) continue;
            sum += (n[i] - mean) * (n[j] - mean);
            ++pairs;
        }
    return pairs && var > 0 ? sum / double(pairs) / var : std::numeric_limits<double>::quiet_NaN();
}

} // namespace

ImageStats image_stats(const PolarImage& img, const CompareOptions& o) {
    ImageStats st;
    const int K = img.bins, N = img.beams;
    st.bins = K, st.beams = N;
    const size_t cells = size_t(K) * size_t(N);
    if (cells == 0) return st;
    std::vector<double> I(cells, 0.0), echo(cells, 0.0);
    double peak = kNegInf;
    for (float v : img.level_db)
        if (std::isfinite(v)) peak = std::max(peak, double(v));
    long floor_samples = 0;
    for (size_t i = 0; i < cells; ++i) {
        const double l = img.level_db[i];
        if (!std::isfinite(l)) {
            ++floor_samples;
            continue;
        }
        I[i] = std::pow(10.0, (l - peak) / 10); // relative to the peak: nothing overflows
        echo[i] = 1;
    }
    st.floor_fraction = double(floor_samples) / double(cells);
    double total = 0;
    for (double v : I) total += v;
    const double mean_I = total / double(cells);
    st.mean_level_db = mean_I > 0 ? peak + 10 * std::log10(mean_I) : kNegInf;

    // Range profile.
    const int S = std::max(1, std::min(o.profile_slices, K));
    for (int s = 0; s < S; ++s) {
        const int k0 = int(long(s) * K / S), k1 = int(long(s + 1) * K / S);
        double sum = 0;
        for (size_t i = size_t(k0) * size_t(N); i < size_t(k1) * size_t(N); ++i) sum += I[i];
        const double m = sum / (double(k1 - k0) * N);
        st.range_profile_db.push_back(m > 0 && mean_I > 0 ? 10 * std::log10(m / mean_I) : kNegInf);
    }

    // Speckle against the local mean.
    const int h = std::max(1, o.local_half_window);
    const std::vector<double> sI = summed(I, K, N), sC = summed(echo, K, N);
    const double min_count = 0.25 * (2 * h + 1) * (2 * h + 1);
    std::vector<double> n(cells, 0.0);
    std::vector<char> used(cells, 0);
    std::vector<double> ns, db;
    for (int k = 0; k < K; ++k)
        for (int b = 0; b < N; ++b) {
            const size_t i = size_t(k) * size_t(N) + size_t(b);
            if (!echo[i] || !(I[i] > 0)) continue;
            const int k0 = std::max(0, k - h), k1 = std::min(K, k + h + 1), b0 = std::max(0, b - h),
                      b1 = std::min(N, b + h + 1);
            const double count = box(sC, N, k0, k1, b0, b1);
            if (count < min_count) continue;
            const double local = box(sI, N, k0, k1, b0, b1) / count;
            if (!(local > 0)) continue;
            n[i] = I[i] / local;
            used[i] = 1;
            ns.push_back(n[i]);
            db.push_back(10 * std::log10(n[i]));
        }
    st.samples_used = long(ns.size());
    const int bins_h = int(std::lround((o.histogram_hi_db - o.histogram_lo_db) / o.histogram_step_db));
    st.histogram.assign(size_t(std::max(1, bins_h)), 0.0);
    if (ns.empty()) return st;
    double m = 0, m2 = 0, a = 0, a2 = 0;
    for (double v : ns) m += v, m2 += v * v, a += std::sqrt(v), a2 += v;
    const double count = double(ns.size());
    m /= count, m2 /= count, a /= count, a2 /= count;
    const double var = std::max(0.0, m2 - m * m);
    st.contrast_intensity = std::sqrt(var) / m;
    st.contrast_amplitude = std::sqrt(std::max(0.0, a2 - a * a)) / a;
    for (size_t q = 0; q < kCompareQuantiles.size(); ++q)
        st.quantiles_db[q] = quantile(db, kCompareQuantiles[q]);
    for (int lag = 1; lag <= o.max_lag; ++lag) {
        st.grain_range.push_back(lag_correlation(n, used, K, N, lag, 0, m, var));
        st.grain_beams.push_back(lag_correlation(n, used, K, N, 0, lag, m, var));
    }
    for (double v : db) {
        const double x = (v - o.histogram_lo_db) / o.histogram_step_db;
        if (x >= 0 && x < double(st.histogram.size())) st.histogram[size_t(x)] += 1 / count;
    }
    return st;
}

PairStats compare_stats(const PolarImage& a, const ImageStats& sa, const PolarImage& b, const ImageStats& sb,
                        const CompareOptions&) {
    PairStats p;
    double sq = 0;
    int slices = 0;
    for (size_t s = 0; s < std::min(sa.range_profile_db.size(), sb.range_profile_db.size()); ++s)
        if (std::isfinite(sa.range_profile_db[s]) && std::isfinite(sb.range_profile_db[s])) {
            const double d = sa.range_profile_db[s] - sb.range_profile_db[s];
            sq += d * d, ++slices;
        }
    p.profile_rms_db = slices ? std::sqrt(sq / slices) : std::numeric_limits<double>::quiet_NaN();
    double tv = 0;
    for (size_t i = 0; i < std::max(sa.histogram.size(), sb.histogram.size()); ++i)
        tv += std::abs((i < sa.histogram.size() ? sa.histogram[i] : 0) -
                       (i < sb.histogram.size() ? sb.histogram[i] : 0));
    p.histogram_distance = 0.5 * tv;
    p.contrast_difference = sb.contrast_intensity - sa.contrast_intensity;
    p.aligned = a.bins == b.bins && a.beams == b.beams && a.bins > 0 && a.beams > 0;
    if (!p.aligned) return p;

    const size_t cells = a.level_db.size();
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    long n = 0;
    std::vector<double> fa, fb;
    for (size_t i = 0; i < cells; ++i) {
        const double x = a.level_db[i], y = b.level_db[i];
        if (std::isfinite(x)) fa.push_back(x);
        if (std::isfinite(y)) fb.push_back(y);
        if (!std::isfinite(x) || !std::isfinite(y)) continue;
        sx += x, sy += y, sxx += x * x, syy += y * y, sxy += x * y, ++n;
    }
    if (n > 1) {
        const double cov = sxy / n - sx / n * sy / n, vx = sxx / n - sx / n * sx / n,
                     vy = syy / n - sy / n * sy / n;
        p.correlation =
            vx > 0 && vy > 0 ? cov / std::sqrt(vx * vy) : std::numeric_limits<double>::quiet_NaN();
    }
    const double hi_a = quantile(fa, 0.9), hi_b = quantile(fb, 0.9), lo_a = quantile(fa, 0.1),
                 lo_b = quantile(fb, 0.1);
    long hi_and = 0, hi_or = 0, lo_and = 0, lo_or = 0;
    for (size_t i = 0; i < cells; ++i) {
        const double x = a.level_db[i], y = b.level_db[i];
        const bool ha = std::isfinite(x) && x >= hi_a, hb = std::isfinite(y) && y >= hi_b;
        const bool la = !std::isfinite(x) || x <= lo_a, lb = !std::isfinite(y) || y <= lo_b;
        hi_and += ha && hb, hi_or += ha || hb, lo_and += la && lb, lo_or += la || lb;
    }
    p.highlight_overlap = hi_or ? double(hi_and) / double(hi_or) : 0;
    p.shadow_overlap = lo_or ? double(lo_and) / double(lo_or) : 0;
    return p;
}

} // namespace sonarsim
