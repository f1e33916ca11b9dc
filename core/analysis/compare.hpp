// `sonarsim compare`: the numbers practitioners judge a sonar image's realism by, for one image and for a
// pair (a simulated frame against a real recording, or two simulations). Every statistic is of the linear
// intensity I = 10^(L/10) of the level image (dB), so that a gain or TVG offset shared by the whole image
// changes none of them but the mean levels; samples at -inf (nothing above the floor) are the floor.
//
// Speckle is measured against the local mean Ibar (a box of (2 h + 1)^2 samples around each, floor samples
// left out): n = I / Ibar. Closed forms for fully developed speckle (exponential intensity): contrast of n 1,
// of sqrt(n) sqrt(4/pi - 1) = 0.523, dB quantiles 10 log10(-ln(1 - q)).
#pragma once
#include "core/data/polar_image.hpp"

#include <array>
#include <vector>

namespace sonarsim {

struct CompareOptions {
    int local_half_window = 7; ///< h: the local mean over (2h+1) x (2h+1) samples
    int profile_slices = 20;   ///< the range profile's slices of the window
    int max_lag = 4;           ///< autocorrelation lags along range and across beams
    double histogram_lo_db = -30, histogram_hi_db = 15, histogram_step_db = 0.5; ///< of 10 log10 n
};

struct ImageStats {
    int bins = 0, beams = 0;
    double floor_fraction = 0;            ///< samples at the floor (-inf)
    double mean_level_db = 0;             ///< 10 log10 of the mean intensity, floor samples as 0
    std::vector<double> range_profile_db; ///< per slice of the range window: its mean I over the image's, dB
    double contrast_intensity = 0;        ///< std(n) / mean(n)
    double contrast_amplitude = 0;        ///< std(sqrt n) / mean(sqrt n)
    std::array<double, 5> quantiles_db{}; ///< 10 log10 n at 5, 25, 50, 75, 95 %
    std::vector<double> grain_range;      ///< correlation coefficient of n at lags 1..max_lag along range
    std::vector<double> grain_beams;      ///< ... and across beams
    std::vector<double> histogram;        ///< fraction of samples per bin of 10 log10 n (sums to <= 1)
    long samples_used = 0;                ///< samples with a local mean (the speckle statistics' sample)
};
inline constexpr std::array<double, 5> kCompareQuantiles{0.05, 0.25, 0.5, 0.75, 0.95};

ImageStats image_stats(const PolarImage& image, const CompareOptions& options = {});

struct PairStats {
    double profile_rms_db = 0;      ///< rms difference of the range profiles (slices finite in both)
    double histogram_distance = 0;  ///< total variation: half the sum of |p_a - p_b| (0 same, 1 disjoint)
    double contrast_difference = 0; ///< contrast_intensity b - a
    bool aligned = false;           ///< same bins and beams: the per-sample numbers below are defined
    double correlation = 0;         ///< Pearson correlation of the dB images over samples finite in both
    double highlight_overlap = 0;   ///< intersection over union of the samples above each image's 90th pct
    double shadow_overlap = 0;      ///< ... of the samples at the floor or below each image's 10th pct
};

PairStats compare_stats(const PolarImage& a, const ImageStats& sa, const PolarImage& b, const ImageStats& sb,
                        const CompareOptions& options = {});

} // namespace sonarsim
