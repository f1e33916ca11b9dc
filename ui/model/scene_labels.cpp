#include "ui/model/scene_labels.hpp"

#include "core/scene/scene_io.hpp"

#include <cstdio>
#include <filesystem>

namespace sonarsim::ui {
namespace {

std::string shape_text(const ObjectDesc& o, bool full_path) {
    if (o.box_m) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "box %g x %g x %g m", (*o.box_m)[0], (*o.box_m)[1], (*o.box_m)[2]);
        return buf;
    }
    return full_path ? o.mesh : std::filesystem::path(o.mesh).filename().string();
}

} // namespace

bool is_paper_fig9_scene(const SceneDesc& s) {
    static const Vec3d prism = *default_scene().objects.at(0).box_m;
    return s.seafloor && s.objects.size() == 1 && s.objects[0].box_m && *s.objects[0].box_m == prism;
}

std::string object_label(const SceneDesc& s, size_t i) {
    if (i >= s.objects.size()) return "object " + std::to_string(i);
    const ObjectDesc& o = s.objects[i];
    return "object " + std::to_string(i) + ": " + (o.name.empty() ? shape_text(o, false) : o.name);
}

std::string object_tooltip(const SceneDesc& s, size_t i) {
    if (i >= s.objects.size()) return {};
    const ObjectDesc& o = s.objects[i];
    return (o.name.empty() ? "" : o.name + "\n") + shape_text(o, true);
}

} // namespace sonarsim::ui
