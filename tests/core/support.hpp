// Small helpers shared by the core tests: paths, linear intensity, .npy reading, Gauss-Legendre rules.
#pragma once
#include "core/data/polar_image.hpp"
#include "core/shading/shade.hpp"

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

namespace sonarsim::test {

inline std::string out_path(const std::string& name) {
    return std::string(SONARSIM_TEST_OUT) + "/" + name;
}
inline std::string data_path(const std::string& name) {
    return std::string(SONARSIM_TEST_DATA) + "/" + name;
}

/// Linear intensity 10^(dB / 10); 0 for -inf.
inline double lin(double db) {
    return std::isfinite(db) ? std::pow(10.0, db / 10.0) : 0.0;
}

/// Echo intensity E[k,i] of an L_EN image: 10^((L_EN + L_N) / 10), 0 where nothing echoes.
inline std::vector<double> echo_intensity(const PolarImage& img, double noise_level_db) {
    std::vector<double> e(img.level_db.size());
    for (size_t n = 0; n < e.size(); ++n) e[n] = lin(double(img.level_db[n]) + noise_level_db);
    return e;
}

/// Relative L1 error sum |a - ref| / sum ref of two intensity images.
inline double relative_l1(const std::vector<double>& a, const std::vector<double>& ref) {
    double num = 0, den = 0;
    for (size_t n = 0; n < ref.size(); ++n) num += std::abs(a[n] - ref[n]), den += ref[n];
    return num / den;
}

inline std::vector<std::uint8_t> read_file_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return {};
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Writes text to path through a file of this process's own and a rename, so that tests running at the
/// same time (ctest -j) that write the same file never read it half-written.
inline void write_text_atomically(const std::string& path, const std::string& text) {
    const std::string tmp = path + ".tmp" + std::to_string(::getpid());
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out << text;
        if (!out) throw std::runtime_error("cannot write " + tmp);
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) throw std::runtime_error("cannot rename " + tmp);
}

inline void write_file_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    if (!out) throw std::runtime_error("cannot write " + path);
}

/// Parses a NumPy v1/v2 .npy file of little-endian float32, C order, 2-D shape, written by encode_npy.
inline PolarImage decode_npy(const std::vector<std::uint8_t>& b) {
    static const std::uint8_t magic[6] = {0x93, 'N', 'U', 'M', 'P', 'Y'};
    if (b.size() < 10 || std::memcmp(b.data(), magic, 6) != 0) throw std::runtime_error("not an .npy file");
    const int major = b[6];
    size_t hlen = 0, hoff = 0;
    if (major == 1) {
        hlen = size_t(b[8]) | size_t(b[9]) << 8, hoff = 10;
    } else {
        if (b.size() < 12) throw std::runtime_error("truncated .npy header");
        hlen = size_t(b[8]) | size_t(b[9]) << 8 | size_t(b[10]) << 16 | size_t(b[11]) << 24, hoff = 12;
    }
    if (hoff + hlen > b.size()) throw std::runtime_error("truncated .npy header");
    const std::string h(b.begin() + long(hoff), b.begin() + long(hoff + hlen));
    if (h.find("'<f4'") == std::string::npos) throw std::runtime_error(".npy is not little-endian float32");
    if (h.find("'fortran_order': False") == std::string::npos) throw std::runtime_error(".npy not C order");
    const size_t sp = h.find("'shape': (");
    if (sp == std::string::npos) throw std::runtime_error(".npy without shape");
    PolarImage img;
    if (std::sscanf(h.c_str() + sp + 10, "%d, %d", &img.bins, &img.beams) != 2)
        throw std::runtime_error(".npy shape is not 2-D");
    const size_t n = size_t(img.bins) * size_t(img.beams), off = hoff + hlen;
    if (b.size() != off + 4 * n) throw std::runtime_error(".npy data size does not match its shape");
    img.level_db.resize(n);
    std::memcpy(img.level_db.data(), b.data() + off, 4 * n);
    return img;
}

/// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n, double precision).
struct GaussLegendre {
    std::vector<double> x, w;
    explicit GaussLegendre(int n) : x(size_t(n)), w(size_t(n)) {
        const double pi = 3.14159265358979323846;
        for (int i = 0; i < n; ++i) {
            double z = std::cos(pi * (i + 0.75) / (n + 0.5)), dp = 1;
            for (int it = 0; it < 100; ++it) {
                double p0 = 1, p1 = z;
                for (int k = 2; k <= n; ++k) {
                    const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
                    p0 = p1, p1 = p2;
                }
                dp = n * (z * p1 - p0) / (z * z - 1);
                const double dz = p1 / dp;
                z -= dz;
                if (std::abs(dz) < 1e-16) break;
            }
            x[size_t(i)] = z;
            w[size_t(i)] = 2 / ((1 - z * z) * dp * dp);
        }
    }
    /// Integral of f over [a, b].
    template <class F> double integrate(double a, double b, F&& f) const {
        const double c = 0.5 * (a + b), h = 0.5 * (b - a);
        double s = 0;
        for (size_t i = 0; i < x.size(); ++i) s += w[i] * f(c + h * x[i]);
        return s * h;
    }
};

} // namespace sonarsim::test
