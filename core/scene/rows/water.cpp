// The water's rows of the parameter table: temperature and depth (absorption), the water surface
// (multipath). The surface's material is a material (rows/material.cpp) at water.surface_material.
#include "core/scene/param_rows.hpp"

namespace sonarsim::rows {

std::vector<ParamSpec> water_rows() {
    std::vector<ParamSpec> t;
    // Bounds: the absorption formula (Ainslie & McColm 1998) holds for -6 < T < 35 degC and 0 < z < 7 km;
    // below -2 degC sea water is ice.
    t.push_back(number("water.temperature_c", "degC", -2, 35, false, false, Stage::Shade,
                       "Water temperature T (absorption formula range)",
                       [](S s) -> double& { return s.water.temperature_c; })
                    .steers()
                    .with_label("T temperature")
                    .with_slider(-2, 35));
    t.push_back(number("water.depth_m", "m", 0, 7000, false, false, Stage::Shade,
                       "Water depth D (absorption)", [](S s) -> double& { return s.water.depth_m; })
                    .steers()
                    .with_label("D depth")
                    .with_slider(0, 6000));
    t.push_back(optional_number("water.surface_height_m", "m", -1e6, 1e6, Stage::Trace,
                                "Multipath: height z of the water surface, a pressure-release mirror that "
                                "also backscatters (water.surface_material); null: no surface",
                                [](S s) -> std::optional<double>& { return s.water.surface_height_m; })
                    .with_slider(-10, 20));
    t.push_back(number("water.surface_roughness_m", "m", 0, 1, false, false, Stage::Shade,
                       "Multipath: rms height sigma of the surface; coherent reflection (energy) R^2 = "
                       "exp(-(2 k sigma cos theta)^2) (Kirchhoff/Eckart; theta from the normal)",
                       [](S s) -> double& { return s.water.surface_roughness_m; })
                    .steers()
                    .with_slider(0, 0.005));
    return t;
}

} // namespace sonarsim::rows
