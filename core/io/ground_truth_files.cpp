#include "core/io/ground_truth_files.hpp"

namespace sonarsim {

std::vector<std::pair<std::string, Bytes>> ground_truth_files(const std::string& prefix,
                                                              const GroundTruth& gt) {
    std::vector<std::pair<std::string, Bytes>> files;
    for (const GroundTruthField& f : ground_truth_fields()) {
        std::vector<std::size_t> shape{std::size_t(gt.bins), std::size_t(gt.beams)};
        if (f.components > 1) shape.push_back(std::size_t(f.components));
        const std::string name = prefix + "_gt_" + f.name + ".npy";
        if (f.f32)
            files.emplace_back(name,
                               encode_npy_array((gt.*f.f32).data(), (gt.*f.f32).size() * 4, "<f4", shape));
        else
            files.emplace_back(name,
                               encode_npy_array((gt.*f.i32).data(), (gt.*f.i32).size() * 4, "<i4", shape));
    }
    return files;
}

} // namespace sonarsim
