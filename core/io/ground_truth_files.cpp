#include "core/io/ground_truth_files.hpp"

#include <type_traits>

namespace sonarsim {

std::vector<std::pair<std::string, Bytes>> ground_truth_files(const std::string& prefix,
                                                              const GroundTruth& gt) {
    return ground_truth_files(prefix, {gt}, {std::size_t(gt.bins), std::size_t(gt.beams)});
}

std::vector<std::pair<std::string, Bytes>> ground_truth_files(const std::string& prefix,
                                                              const std::vector<GroundTruth>& parts,
                                                              const std::vector<std::size_t>& cells) {
    std::vector<std::pair<std::string, Bytes>> files;
    for (const GroundTruthField& f : ground_truth_fields()) {
        std::vector<std::size_t> shape = cells;
        if (f.components > 1) shape.push_back(std::size_t(f.components));
        const std::string name = prefix + "_gt_" + f.name + ".npy";
        auto joined = [&](auto member) { // one part's array as it is, or all parts' end to end
            using T = typename std::decay_t<decltype(parts[0].*member)>::value_type;
            if (parts.size() == 1) return parts[0].*member;
            std::vector<T> all;
            for (const GroundTruth& g : parts) all.insert(all.end(), (g.*member).begin(), (g.*member).end());
            return all;
        };
        if (f.f32) {
            const std::vector<float> v = joined(f.f32);
            files.emplace_back(name, encode_npy_array(v.data(), v.size() * 4, "<f4", shape));
        } else {
            const std::vector<std::int32_t> v = joined(f.i32);
            files.emplace_back(name, encode_npy_array(v.data(), v.size() * 4, "<i4", shape));
        }
    }
    return files;
}

} // namespace sonarsim
