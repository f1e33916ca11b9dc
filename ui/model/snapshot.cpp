#include "ui/model/snapshot.hpp"

#include "core/io/ground_truth_files.hpp"
#include "core/scene/scene_io.hpp"

#include <ctime>
#include <filesystem>

namespace sonarsim::ui {

std::string default_snapshot_prefix(const std::string& dir) {
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    localtime_r(&now, &tm);
    char stamp[32];
    std::strftime(stamp, sizeof stamp, "sonarsim_%Y%m%d_%H%M%S", &tm);
    const std::filesystem::path base = std::filesystem::path(dir.empty() ? "." : dir) / stamp;
    std::string prefix = base.string();
    std::error_code ec;
    for (int n = 2; std::filesystem::exists(prefix + ".npy", ec); ++n)
        prefix = base.string() + "_" + std::to_string(n);
    return prefix;
}

std::string snapshot_scene_text(const SceneDesc& scene) {
    return scene_to_json(scene).dump(2) + "\n";
}

std::vector<std::string> write_snapshot(const std::string& prefix, const SceneDesc& scene, const Frame& frame,
                                        const Bytes& view3d_png, const GroundTruth* ground_truth,
                                        const Bytes& annotated_png) {
    std::vector<std::pair<std::string, Bytes>> extra;
    GroundTruthOutputs gt;
    if (ground_truth) gt = ground_truth_outputs(prefix, *ground_truth, scene, true, true);
    for (auto& file : gt.files) extra.push_back(std::move(file));
    if (!view3d_png.empty()) extra.emplace_back(prefix + "_3d.png", view3d_png);
    if (!annotated_png.empty()) extra.emplace_back(prefix + "_annotated.png", annotated_png);
    extra.emplace_back(prefix + "_scene.json", to_bytes(snapshot_scene_text(scene)));
    std::vector<std::string> paths = render_output_paths(prefix, scene);
    for (auto& e : extra) paths.push_back(e.first);
    write_render_files(prefix, scene, frame, std::move(extra), gt.metadata);
    return paths;
}

} // namespace sonarsim::ui
