// The flat-floor echo integral of SONAR_MODEL.md ("What one pixel of the raw image is"), written for the
// tests only and independently of the tracer: its own rotation (eq. 12), its own absorption (eq. 7) and
// GSAB (eq. 9), closed-form breakpoints and Gauss-Legendre quadrature.
#pragma once
#include "core/data/scene.hpp"

#include <vector>

namespace sonarsim::test {

/// Everything the floor integral needs, derived once from a floor-only scene.
struct FloorSetup {
    double height_m;   ///< sonar height above the floor H > 0
    double rz[3];      ///< third row of R = Rz(yaw) Ry(pitch) Rx(roll): d_z = rz . d_sonar
    double theta, phi; ///< azimuth / elevation aperture [rad]
    int beams, bins;
    double r_min, r_max, dr;
    double source_lin;       ///< 10^(L_S / 10)
    double alpha;            ///< [dB/m]
    double nu, q, mu, h_rad; ///< GSAB, nu linear
};
FloorSetup floor_setup(const SceneDesc& scene);

/// Integrand of E at azimuth a, elevation e [rad] (0 where the ray misses the floor); its range in *range_m.
double floor_integrand(const FloorSetup& f, double a, double e, double* range_m);

/// E[k * beams + i] by the semi-analytic rule: per beam, the azimuth interval is split at the azimuths where
/// a bin edge crosses the elevation limits +-Phi/2 and each piece integrated with `az_panels` panels of
/// `az_nodes` Gauss-Legendre nodes; at each azimuth node the elevation integral is split at the closed-form
/// roots of r(e) = bin edge and each piece integrated with `el_nodes` nodes.
std::vector<double> floor_reference_intensity(const SceneDesc& scene, int az_panels = 2, int az_nodes = 6,
                                              int el_nodes = 4);

/// E[k] of one beam by brute-force 2-D midpoint quadrature over na x ne points (for checking the above).
std::vector<double> floor_bruteforce_beam(const SceneDesc& scene, int beam, int na, int ne);

} // namespace sonarsim::test
