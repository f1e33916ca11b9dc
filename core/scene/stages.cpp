// What an edit invalidates, from the table alone: each row's stage (Place under adaptive placement for the
// rows that steer the sampler, a mirror appearing or disappearing re-traces), and the earliest stage at
// which two scenes differ.
#include "core/scene/params.hpp"

#include <algorithm>
#include <cmath>

namespace sonarsim {

Stage ValueSpec::effective_stage(const SceneDesc& scene) const {
    return steers_sampler && scene.sampling.placement == RayPlacement::Adaptive
               ? std::min(stage, Stage::Place)
               : stage;
}

Stage MaterialSpec::stage_of_change(double before, double after, const SceneDesc& scene) const {
    return optional && std::isfinite(before) != std::isfinite(after) ? Stage::Trace : effective_stage(scene);
}

Stage changed_stage(const SceneDesc& a, const SceneDesc& b) {
    Stage st = Stage::None;
    auto mark = [&](Stage s) { st = std::min(st, s); };
    for (auto& p : scene_params())
        if (p.get(a) != p.get(b)) mark(p.effective_stage(b));
    auto material_stage = [&](const Material& x, const Material& y) {
        for (auto& p : material_params())
            if (p.get(x) != p.get(y)) mark(p.stage_of_change(x.*p.field, y.*p.field, b));
    };
    material_stage(a.water.surface_material, b.water.surface_material);
    if (a.objects.size() != b.objects.size()) {
        mark(Stage::Geometry);
    } else {
        for (size_t i = 0; i < a.objects.size(); ++i) {
            for (auto& p : object_params())
                if (p.get(a.objects[i]) != p.get(b.objects[i])) mark(p.effective_stage(b));
            material_stage(a.objects[i].material, b.objects[i].material);
        }
    }
    if (bool(a.seafloor) != bool(b.seafloor))
        mark(Stage::Trace);
    else if (a.seafloor) {
        for (auto& p : seafloor_params())
            if (p.get(*a.seafloor) != p.get(*b.seafloor)) mark(p.effective_stage(b));
        material_stage(a.seafloor->material, b.seafloor->material);
    }
    return st;
}

} // namespace sonarsim
