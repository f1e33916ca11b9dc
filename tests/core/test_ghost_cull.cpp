// Ghost culling (core/sampling/multipath.hpp, kGhostCullShare): a ghost whose whole echo lies below 1/8 of
// what the tolerance allows every bin it touches (against the direct echo there) is dropped before its
// shadow ray and its shading. The tank's ghosts on a regular grid, culled against its direct image and not
// culled: each bin of the image with ghosts changes by less than the tolerance allows it. And the gathering
// of ghosts into the beams they arrive in (gather_ghosts): its order, and a ghost's shares across beams.
#include "core/sampling/adaptive_node.hpp"
#include "core/sampling/multipath.hpp"
#include "core/scene/scene_io.hpp"
#include "core/shading/accumulate.hpp"

#include <catch2/catch.hpp>
#include <cmath>

using namespace sonarsim;

namespace {

/// The tank's cells on a grid of `rays` elevation rays per beam (as trace_uniform places them) and, when
/// `mp` is given, their ghosts.
TraceResult grid_trace(const SceneGeometry& g, const SceneDesc& s, const detail::RayFrame& frame, int rays,
                       const detail::Multipath* mp) {
    const int N = s.sonar.beams;
    const double phi = frame.elevation_weight.traced_fov_rad(), de = phi / rays;
    TraceResult out;
    out.beams = N;
    out.cells.resize(size_t(N));
    std::vector<std::vector<GhostCell>> ghosts(static_cast<size_t>(N));
    for (int i = 0; i < N; ++i) {
        const double a_c = frame.grid->beam_starboard_edge_rad(i) + 0.5 * frame.grid->beam_width_rad(i);
        const double da = frame.grid->beam_width_rad(i);
        const detail::Angle a(a_c), a_lo(a_c - da / 2), a_hi(a_c + da / 2);
        for (int j = 0; j < rays; ++j) {
            const detail::Angle e(phi / 2 - (j + 0.5) * de), e_lo(phi / 2 - (j + 1) * de),
                e_hi(phi / 2 - j * de);
            const auto h = detail::first_hit(g, s, frame.origin, frame.dir(a, e), frame.t_max);
            if (!h) continue;
            out.cells[size_t(i)].push_back(detail::make_cell(frame, *h, a, e, a_lo, a_hi, e_lo, e_hi));
            if (mp) mp->ghosts(*h, a, e, a_lo, a_hi, e_lo, e_hi, i, ghosts[size_t(i)]);
        }
    }
    if (mp) out.ghosts = detail::gather_ghosts(ghosts, s);
    return out;
}

} // namespace

TEST_CASE("culled ghosts change no bin by more than the tolerance allows it", "[multipath]") {
    SceneDesc s = load_scene(std::string(SONARSIM_ASSETS) + "/scenes/tank.json");
    s.sampling.bounces = 1;
    const SceneGeometry g(s);
    const detail::RayFrame frame(s);
    const int N = s.sonar.beams, K = s.sonar.range_bins, rays = 303;

    // The floor: the direct image, [beam * bins + bin] (as the sampler's base image).
    const PolarImage direct = shade(grid_trace(g, s, frame, rays, nullptr), s);
    std::vector<float> floor_db(size_t(N) * size_t(K));
    for (int i = 0; i < N; ++i)
        for (int b = 0; b < K; ++b) floor_db[size_t(i) * size_t(K) + size_t(b)] = direct.at(b, i);
    // What the tolerance allows a bin, relative to its echo (refine_criteria: tolerance_per_bin_db).
    const double allowed = (std::pow(10.0, s.sampling.tolerance_db / 10) - 1) / adaptive::kErrorsPerBin;

    const detail::Multipath all(g, s, frame);
    detail::Multipath culling(g, s, frame);
    culling.set_cull_floor({&floor_db, 10 * std::log10(allowed * detail::kGhostCullShare)});
    const PolarImage full = shade(grid_trace(g, s, frame, rays, &all), s);
    const PolarImage culled = shade(grid_trace(g, s, frame, rays, &culling), s);
    REQUIRE(all.culled() == 0);
    INFO("ghosts culled: " << culling.culled());
    CHECK(culling.culled() > 100); // not a vacuous comparison

    // Per bin, the culled ghosts' echo against the image's; and the image's relative L1 change.
    double worst = 0, least = 0, num = 0, den = 0;
    size_t changed = 0;
    for (size_t n = 0; n < full.level_db.size(); ++n) {
        const double f = full.level_db[n], c = culled.level_db[n];
        if (!std::isfinite(f)) continue;
        const double lf = std::pow(10.0, f / 10), lc = std::isfinite(c) ? std::pow(10.0, c / 10) : 0.0;
        worst = std::max(worst, (lf - lc) / lf), least = std::min(least, (lf - lc) / lf);
        num += std::abs(lf - lc), den += lf;
        changed += lc != lf;
    }
    INFO("bins changed " << changed << ", worst relative change " << worst << " (allowed " << allowed
                         << "), rel L1 " << num / den);
    CHECK(changed > 0);
    CHECK(least > -1e-6); // culling only removes echo (float sums aside)
    CHECK(worst < allowed);
    // Together well within the image's tolerance: under kGhostCullShare of sampling.tolerance_rel_l1.
    CHECK(num / den < detail::kGhostCullShare * s.sampling.tolerance_rel_l1);
}

TEST_CASE(
    "gathered ghosts arrive with each beam's own first and the rest by source and keep their solid angle",
    "[multipath]") {
    SceneDesc s; // even beams: the share of an interval in each is the part of it in each
    s.sonar.beams = 16;
    const auto grid = sonar_grid(s.sonar);
    auto ghost = [&](int beam, float solid_angle_sr, std::uint8_t tx, std::uint8_t rx, double azimuth_rad,
                     double width_rad) {
        GhostCell g{};
        g.beam = std::uint32_t(beam), g.tx_bounces = tx, g.rx_bounces = rx;
        g.cell.solid_angle_sr = solid_angle_sr;
        g.cell.azimuth_rad = float(azimuth_rad), g.cell.azimuth_width_rad = float(width_rad);
        return g;
    };
    auto centre = [&](int i) { return grid->beam_port_edge_rad(i) - 0.5 * grid->beam_width_rad(i); };
    // Beam 7's edge to beam 8 (beam 8 lies to starboard of beam 7: lower azimuth).
    const double edge = grid->beam_port_edge_rad(7) - grid->beam_width_rad(7);
    const double w8 = grid->beam_width_rad(8);
    std::vector<std::vector<GhostCell>> by_source(size_t(grid->beams));
    by_source[7] = {
        ghost(7, 1, 1, 1, centre(7), 1e-4),      // a double path: stays in 7
        ghost(8, 2, 1, 0, centre(8), 1e-4),      // arrives from the scatterer, in beam 8
        ghost(7, 3, 0, 1, centre(7), 1e-4),      // back by the mirror: stays in 7
        ghost(8, 4, 1, 0, edge - 0.25 * w8, w8), // three quarters in 8, a quarter in 7
    };
    by_source[8] = {ghost(8, 5, 1, 1, centre(8), 1e-4)};
    by_source[3] = {ghost(8, 6, 1, 1, centre(8), 1e-4)}; // found in beam 3's list, arriving in 8
    // The sampler splits each source's ghosts as it makes them (stays_in_source): the same lists.
    std::vector<std::vector<GhostCell>> stay(by_source.size()), away(by_source.size());
    for (size_t k = 0; k < by_source.size(); ++k)
        for (const auto& g : by_source[k])
            (detail::stays_in_source(g, k, *grid) ? stay : away)[k].push_back(g);
    CHECK(stay[7].size() == 2);
    CHECK(away[7].size() == 2);
    CHECK(away[3].size() == 1);
    const auto split = detail::gather_ghosts(stay, away, s);
    const auto out = detail::gather_ghosts(by_source, s);
    REQUIRE(split.size() == out.size());
    for (size_t i = 0; i < out.size(); ++i) {
        REQUIRE(split[i].size() == out[i].size());
        for (size_t k = 0; k < out[i].size(); ++k) {
            CHECK(split[i][k].beam == out[i][k].beam);
            CHECK(split[i][k].cell.solid_angle_sr == out[i][k].cell.solid_angle_sr);
            CHECK(split[i][k].cell.azimuth_rad == out[i][k].cell.azimuth_rad);
        }
    }
    REQUIRE(out.size() == size_t(grid->beams));
    auto solid_angles = [&](int i) {
        std::vector<double> v;
        for (const auto& g : out[size_t(i)]) {
            CHECK(g.beam == std::uint32_t(i));
            v.push_back(g.cell.solid_angle_sr);
        }
        return v;
    };
    const auto in7 = solid_angles(7), in8 = solid_angles(8);
    REQUIRE(in7.size() == 3);
    CHECK(in7[0] == 1);
    CHECK(in7[1] == 3);
    CHECK(in7[2] == Approx(4 * 0.25).epsilon(1e-4)); // the straddling ghost's share in beam 7
    REQUIRE(in8.size() == 4);
    CHECK(in8[0] == 5); // beam 8's own, then the others by source (3, then 7 in its order)
    CHECK(in8[1] == 6);
    CHECK(in8[2] == 2);
    CHECK(in8[3] == Approx(4 * 0.75).epsilon(1e-4));
    for (int i = 0; i < grid->beams; ++i)
        if (i != 7 && i != 8) CHECK(out[size_t(i)].empty());
    for (const auto& src : by_source) CHECK(src.empty()); // moved out
}

TEST_CASE("a ghost shared among beams gives each the part of its range footprint over that beam's azimuths",
          "[multipath]") {
    SceneDesc s;
    s.sonar.beams = 16;
    const auto grid = sonar_grid(s.sonar);
    const double edge = grid->beam_port_edge_rad(7) - grid->beam_width_rad(7); // beam 7 | beam 8
    const double w8 = grid->beam_width_rad(8);
    // Out by the mirror, back directly, over [edge - 0.75 w8, edge + 0.25 w8]: its range on the scatterer's
    // plane runs from 10 m at the interval's lower (starboard) azimuth to 14 m at its upper.
    GhostCell g{};
    g.beam = 8, g.tx_bounces = 1, g.rx_bounces = 0;
    g.cell.solid_angle_sr = 4, g.cell.range_m = 12;
    g.cell.azimuth_rad = float(edge - 0.25 * w8), g.cell.azimuth_width_rad = float(w8);
    g.cell.range_a_lo_m = 10, g.cell.range_a_hi_m = 14;
    g.cell.range_e_lo_m = 12, g.cell.range_e_hi_m = 12;
    std::vector<std::vector<GhostCell>> by_source(size_t(grid->beams));
    by_source[8] = {g};
    const auto out = detail::gather_ghosts(by_source, s);
    REQUIRE(out[7].size() == 1);
    REQUIRE(out[8].size() == 1);
    // Three quarters of the interval in beam 8 (10 -> 13 m), a quarter in beam 7 (13 -> 14 m).
    CHECK(out[8][0].cell.range_a_lo_m == Approx(10).margin(1e-3));
    CHECK(out[8][0].cell.range_a_hi_m == Approx(13).margin(1e-3));
    CHECK(out[7][0].cell.range_a_lo_m == Approx(13).margin(1e-3));
    CHECK(out[7][0].cell.range_a_hi_m == Approx(14).margin(1e-3));
    CHECK(out[8][0].cell.solid_angle_sr == Approx(3).epsilon(1e-4));
    CHECK(out[7][0].cell.solid_angle_sr == Approx(1).epsilon(1e-4));
}
