// What an edit invalidates, from the table alone: each row's stage (Place under adaptive placement for the
// rows that steer the sampler, a mirror appearing or disappearing re-traces), and the earliest stage at
// which two scenes differ.
#include "core/scene/params.hpp"
#include "core/scene/sampling_scheme.hpp"
#include "core/scene/scene_parts.hpp"

#include <algorithm>
#include <cmath>

namespace sonarsim {

Stage ValueSpec::effective_stage(const SceneDesc& scene) const {
    return steers_sampler && placement_spec(scene.sampling.placement).placed_by_shading
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
    if (a.objects.size() != b.objects.size()) mark(Stage::Geometry);
    if (bool(a.seafloor) != bool(b.seafloor)) mark(Stage::Trace);
    // The parts both scenes have: their own rows, then their materials.
    if (a.seafloor && b.seafloor)
        for (auto& p : seafloor_params())
            if (p.get(*a.seafloor) != p.get(*b.seafloor)) mark(p.effective_stage(b));
    if (a.objects.size() == b.objects.size())
        for (size_t i = 0; i < a.objects.size(); ++i)
            for (auto& p : object_params())
                if (p.get(a.objects[i]) != p.get(b.objects[i])) mark(p.effective_stage(b));
    for (int part : material_parts(b)) {
        const Material *x = material_of(a, part), *y = material_of(b, part);
        if (x)
            for (auto& p : material_params())
                if (p.get(*x) != p.get(*y)) mark(p.stage_of_change((*x).*p.field, (*y).*p.field, b));
    }
    return st;
}

} // namespace sonarsim
