// The active sonar equation's terms (SONAR_MODEL.md), all levels in dB.
#pragma once
#include "core/base/units.hpp"
#include "core/data/scene.hpp"

namespace sonarsim {

/// Absorption alpha [dB/m] = 0.00049 f^2 exp(-(T/27 + D/17)) / 1000, f [kHz], T [degC], D [km] (eq. 7 as
/// fixed).
double absorption_db_per_m(double frequency_khz, double temperature_c, double depth_m);

/// Speed of sound in sea water [m/s] (Medwin 1975, salinity 35 ppt): T [degC], depth z [m].
double sound_speed_m_s(double temperature_c, double depth_m);

/// One-way transmission loss L_TL = 20 log10 R + alpha R [dB] (eq. 6).
double transmission_loss_db(double range_m, double alpha_db_per_m);

/// GSAB backscatter strength L_BS(theta) = 10 log10(mu exp(-theta^2 / 2h^2) + nu cos^q theta) [dB] (eq. 9).
/// Evaluated in the log domain: finite wherever the linear value is positive, -inf where it is zero.
double backscatter_db(const Material& m, double cos_incidence);

/// Physics constants of one image, derived once per shade.
struct ShadeConstants {
    double source_level_db, noise_level_db, alpha_db_per_m;
    double wavenumber_rad_per_m; ///< k = 2 pi f / c (the surface's roughness loss)
};
ShadeConstants shade_constants(const SceneDesc& scene);

/// Echo level of one ray's cell before noise [dB]: L_S - 2 L_TL(r) + L_BS(theta) + 10 log10(r^2 dOmega / cos
/// theta). -inf when nothing returns (cos theta <= 0, or range <= 0).
double cell_echo_db(const ShadeConstants& c, const Material& m, double range_m, double cos_incidence,
                    double solid_angle_sr);

} // namespace sonarsim
