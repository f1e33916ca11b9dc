#include "core/io/ground_truth_files.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <type_traits>

namespace sonarsim {

namespace {

/// The files of `n` parts laid end to end (one part: its arrays as they are, not copied).
std::vector<std::pair<std::string, Bytes>> files_of(const std::string& prefix, const GroundTruth* parts,
                                                    std::size_t n, const std::vector<std::size_t>& cells) {
    std::vector<std::pair<std::string, Bytes>> files;
    for (const GroundTruthField& f : ground_truth_fields()) {
        std::vector<std::size_t> shape = cells;
        if (f.components > 1) shape.push_back(std::size_t(f.components));
        const std::string name = prefix + "_gt_" + f.name + ".npy";
        auto encode = [&](auto member, const char* descr) { // one part's array as it is, or all end to end
            const auto& first = parts[0].*member;
            if (n == 1) return encode_npy_array(first.data(), first.size() * 4, descr, shape);
            std::decay_t<decltype(first)> all;
            for (const GroundTruth* g = parts; g != parts + n; ++g)
                all.insert(all.end(), (g->*member).begin(), (g->*member).end());
            return encode_npy_array(all.data(), all.size() * 4, descr, shape);
        };
        files.emplace_back(name, f.f32 ? encode(f.f32, "<f4") : encode(f.i32, "<i4"));
    }
    return files;
}

} // namespace

std::vector<std::pair<std::string, Bytes>> ground_truth_files(const std::string& prefix,
                                                              const GroundTruth& gt) {
    return files_of(prefix, &gt, 1, {std::size_t(gt.bins), std::size_t(gt.beams)});
}

std::vector<std::pair<std::string, Bytes>> ground_truth_files(const std::string& prefix,
                                                              const std::vector<GroundTruth>& parts,
                                                              const std::vector<std::size_t>& cells) {
    return files_of(prefix, parts.data(), parts.size(), cells);
}

namespace {

constexpr double kLevels = 65534; ///< pixel values 1 ... 65535 span a map's range; 0 is nothing

/// A double as text that reads back to the same double.
std::string exact_text(double x) {
    char b[40];
    std::snprintf(b, sizeof b, "%.17g", x);
    return b;
}

const char* kMapLayout = "rows: range bins, the farthest at the top; columns: beams, port on the left (as "
                         "PREFIX_polar.png)";

} // namespace

std::vector<GroundTruthMap> ground_truth_maps(const SceneDesc& s) {
    return {{"range_m", &GroundTruth::range_m, "m",
             "echo-weighted mean distance from the sonar to what echoes", 0,
             2 * s.sonar.range_max_m / kLevels},
            {"elevation_deg", &GroundTruth::elevation_deg, "deg",
             "echo-weighted mean elevation of what echoes", -90, 180 / kLevels}};
}

std::vector<std::pair<std::string, Bytes>> ground_truth_map_files(const std::string& prefix,
                                                                  const GroundTruth& gt, const SceneDesc& s) {
    const int K = gt.bins, N = gt.beams;
    std::vector<std::pair<std::string, Bytes>> files;
    for (const GroundTruthMap& m : ground_truth_maps(s)) {
        std::vector<std::uint16_t> v(size_t(K) * size_t(N), 0);
        const std::vector<float>& values = gt.*m.field;
        for (int k = 0; k < K; ++k)
            for (int b = 0; b < N; ++b) {
                const size_t c = size_t(k) * size_t(N) + size_t(b);
                if (std::isnan(gt.elevation_deg[c])) continue; // nothing echoes
                const double x = values[c];
                // Within the map's span: an elevation; a distance at most the bin's range give or take a
                // multipath echo's footprint (the span is twice the window). Held at its ends should one not
                // be.
                const double q = std::clamp(std::round((x - m.offset) / m.scale), 0.0, kLevels);
                v[size_t(K - 1 - k) * size_t(N) + size_t(b)] = std::uint16_t(1 + q);
            }
        const std::string formula = m.name + " = " + exact_text(m.offset) + " + (v - 1) * " +
                                    exact_text(m.scale) + " " + m.unit +
                                    " for pixel value v; v = 0: nothing echoes";
        files.emplace_back(
            prefix + "_gt_" + m.name + ".png",
            encode_png_gray16(N, K, v,
                              {{"Title", "sonarsim ground truth: " + m.name + " (" + m.what + ")"},
                               {"Description", formula + ". " + kMapLayout},
                               {"sonarsim:offset", exact_text(m.offset)},
                               {"sonarsim:scale", exact_text(m.scale)},
                               {"sonarsim:unit", m.unit}}));
    }
    return files;
}

GroundTruthOutputs ground_truth_outputs(const std::string& prefix, const GroundTruth& gt, const SceneDesc& s,
                                        bool arrays, bool maps) {
    GroundTruthOutputs out;
    if (arrays) out.files = ground_truth_files(prefix, gt);
    if (maps) {
        for (auto& file : ground_truth_map_files(prefix, gt, s)) out.files.push_back(std::move(file));
        out.metadata = ground_truth_maps_metadata(s);
    }
    return out;
}

json ground_truth_maps_metadata(const SceneDesc& s) {
    json maps = json::array();
    for (const GroundTruthMap& m : ground_truth_maps(s))
        maps.push_back({{"suffix", "_gt_" + m.name + ".png"},
                        {"quantity", m.what},
                        {"unit", m.unit},
                        {"offset", m.offset},
                        {"scale", m.scale},
                        {"value", "offset + (v - 1) * scale for 16-bit pixel value v"},
                        {"zero", "nothing echoes"},
                        {"layout", kMapLayout}});
    return {{"ground_truth_maps", maps}};
}

} // namespace sonarsim
