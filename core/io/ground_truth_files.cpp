#include "core/io/ground_truth_files.hpp"

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

} // namespace sonarsim
