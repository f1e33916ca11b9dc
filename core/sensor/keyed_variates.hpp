// Counter-based random variates for the sensor stage, a row of cells at a time: each variate is a pure
// function of a 32-bit key (a hash of the seed and what it belongs to: a scatterer's world cell, a pixel), so
// the same key gives the same number in any order, on any thread. The loops are plain and branch-free so the
// compiler vectorises them (SSE2, or AVX2 or AVX-512 where the CPU has it: all give the same bits, no FMA
// being used).
#pragma once
#include <cstdint>

namespace sonarsim::keyed {

/// A 32-bit integer hash (the "lowbias32" mix of C. Wellons): every input bit affects every output bit.
inline std::uint32_t mix32(std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

/// 32 bits of a 64-bit seed.
inline std::uint32_t fold(std::uint64_t seed) {
    return mix32(std::uint32_t(seed) ^ mix32(std::uint32_t(seed >> 32)));
}

/// World points p_i = origin + rise_m[i] up + reach_m[i] (ahead_x, ahead_y, ahead_z)[i] [m]: cells of the
/// fan at their range and elevation (up, ahead_i: unit vectors).
struct RaisedPoints {
    double origin_m[3], up[3];
    const double *rise_m, *reach_m, *ahead_x, *ahead_y, *ahead_z;
};

/// Keys of the n points p_i quantised on a grid of 1 / inv_cell_per_m metres: key[i] = hash(seed,
/// floor(x inv_cell), floor(y inv_cell), floor(z inv_cell)), each cell index taken modulo 2^32 (exact while
/// |coordinate| * inv_cell < 2^51).
void world_cell_keys(int n, const RaisedPoints& p, double inv_cell_per_m, std::uint32_t seed,
                     std::uint32_t* key);

/// A unit-power circular complex Gaussian variate per key: power[i] ~ Exp(1), and cos and sin of a phase
/// uniform on the circle (in single precision; 24-bit uniforms: power at most 17.3).
void exp_phasors(int n, const std::uint32_t* key, float* power, float* cos_phase, float* sin_phase);

/// A Gamma(shape, 1) / shape variate (mean 1, variance 1 / shape) per key: Marsaglia and Tsang (2000), a
/// rejected draw retried with the next draws of its key; for shape < 1, Gamma(shape + 1) U^(1 / shape).
void gamma_unit_mean(int n, const std::uint32_t* key, double shape, double* out);

} // namespace sonarsim::keyed
