#include "ui/model/scene_files.hpp"

#include "core/base/file_io.hpp"
#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"

#include <optional>
#include <set>

namespace sonarsim::ui {

bool looks_like_scene_file(const std::string& path) {
    const std::optional<std::string> text = try_read_file_bytes(path, kMaxSceneFileBytes);
    if (!text) return false;
    const json j = json::parse(*text, nullptr, false);
    if (j.is_discarded() || !j.is_object()) return false;
    // The sections of core's parameter table (sonar, water, sensor, ...), objects and the seafloor.
    static const std::set<std::string> sections = [] {
        std::set<std::string> s = {"seafloor", "objects"};
        for (const ParamSpec& p : scene_params()) s.insert(p.key.substr(0, p.key.find('.')));
        return s;
    }();
    for (auto it = j.begin(); it != j.end(); ++it)
        if (!sections.count(it.key())) return false;
    return true;
}

} // namespace sonarsim::ui
