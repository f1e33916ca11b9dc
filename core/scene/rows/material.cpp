// The material's rows of the parameter table: the preset, GSAB backscatter (nu, q, mu, h), the mirror's
// loss, and the seabed texture. Every surface has them: seafloor.material.*, objects.N.material.*,
// water.surface_material.*.
#include "core/scene/materials.hpp"
#include "core/scene/param_rows.hpp"

namespace sonarsim::rows {

ValueSpec material_preset_row() {
    auto p = blank<ValueSpec>("preset", "", ParamType::Enum, Stage::Shade,
                              "Material preset (assets/materials/NAME.json, docs/model.md): sets its sourced "
                              "values first; the surface's other keys override them; none: no preset");
    p.choices = material_preset_choices();
    p.section = Section::Material;
    return p;
}

std::vector<MaterialSpec> material_rows() {
    std::vector<MaterialSpec> t;
    t.push_back(material("nu_db", "dB", -200, 50, false, "Lambert strength 10 log10 nu", &Material::nu_db)
                    .with_label("10 log nu")
                    .with_slider(-90, 0));
    t.push_back(material("q", "", 0, 1000, false, "Lambert exponent q (fall-off at grazing)", &Material::q)
                    .with_label("q exponent")
                    .with_slider(0, 20));
    t.push_back(material("mu", "", 0, 1e6, false, "Specular amplitude mu (linear; 0 = off)", &Material::mu)
                    .with_label("mu specular")
                    .with_slider(0, 10));
    t.push_back(material("h_deg", "deg", 0, 90, true, "Specular lobe width h", &Material::h_deg)
                    .with_label("h lobe width")
                    .with_slider(0.5, 45));
    MaterialSpec mirror = material("reflection_db", "dB", 0, 200, false,
                                   "Multipath: energy lost per specular reflection, -10 log10 R^2; absent "
                                   "(null): not a mirror",
                                   &Material::reflection_db)
                              .with_slider(0, 40);
    mirror.optional = true;
    t.push_back(mirror);
    t.push_back(
        material("texture_rms_db", "dB", 0, 20, false,
                 "Seabed texture: rms of a random backscatter level fixed to the surface (linear mean "
                 "kept); 0 = off",
                 &Material::texture_rms_db)
            .with_slider(0, 8));
    t.push_back(material("texture_correlation_m", "m", 0, 1e4, true,
                         "Seabed texture and slope: lag at which their autocorrelation falls to 1/e",
                         &Material::texture_correlation_m)
                    .with_log_slider(0.02, 20));
    t.push_back(
        material("ripple_amplitude_db", "dB", 0, 20, false,
                 "Ripples: peak amplitude of a sinusoidal backscatter level (linear mean kept); 0 = off",
                 &Material::ripple_amplitude_db)
            .with_slider(0, 6));
    t.push_back(material("ripple_wavelength_m", "m", 0, 1e4, true, "Ripples: crest spacing",
                         &Material::ripple_wavelength_m)
                    .with_log_slider(0.05, 5));
    t.push_back(
        material("ripple_direction_deg", "deg", -360, 360, false,
                 "Ripples: direction of the wave vector, from the surface's x axis toward y (seafloor: "
                 "world)",
                 &Material::ripple_direction_deg)
            .with_slider(-180, 180));
    t.push_back(material("slope_rms_deg", "deg", 0, 45, false,
                         "Small-scale slope: rms tilt of the facets in the plane of incidence; 0 = off",
                         &Material::slope_rms_deg)
                    .with_slider(0, 20));
    return t;
}

} // namespace sonarsim::rows
