#include "ui/model/sonar_geometry.hpp"

#include "core/kinds/pings.hpp"

#include "core/grid/sonar_grid.hpp"
#include "core/geometry/mesh_cache.hpp"
#include "core/data/pose.hpp"
#include "core/shading/shade.hpp"

#include <algorithm>
#include <cstdint>
#include <cmath>

namespace sonarsim::ui {

glm::dvec3 sonar_point(const SonarParams& s, double r, double a_deg, double e_deg) {
    return to_glm(s.pose.position_m) +
           rotation_matrix(s.pose.orientation_deg) * (r * sonar_direction(deg2rad(a_deg), deg2rad(e_deg)));
}

FrustumShell frustum_shell(const SonarParams& s, int na, int ne) {
    na = std::max(1, na), ne = std::max(1, ne);
    const std::shared_ptr<const SonarGrid> grid_ptr =
        sonar_grid(s); // held: the registry keeps only what someone holds
    const SonarGrid& grid = *grid_ptr;
    const double r0 = s.range_min_m, r1 = s.range_max_m, pa = grid.port_edge_deg(),
                 sa = grid.starboard_edge_deg(), he = grid.elevation_half_deg();
    auto az = [&](int i) { return pa - (pa - sa) * i / na; };
    auto el = [&](int j) { return he - 2 * he * j / ne; };
    auto P = [&](double r, double a, double e) { return glm::vec3(sonar_point(s, r, a, e)); };
    FrustumShell f;
    auto quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
        f.triangles.insert(f.triangles.end(), {a, b, c, a, c, d});
    };
    auto seg = [&](glm::vec3 a, glm::vec3 b) { f.lines.insert(f.lines.end(), {a, b}); };

    // Near and far caps (spherical patches) with a coarse grid on the far cap.
    for (double r : {r0, r1}) {
        if (r <= 0) continue;
        for (int i = 0; i < na; ++i)
            for (int j = 0; j < ne; ++j)
                quad(P(r, az(i), el(j)), P(r, az(i + 1), el(j)), P(r, az(i + 1), el(j + 1)),
                     P(r, az(i), el(j + 1)));
        for (int i = 0; i < na; ++i)
            for (int j : {0, ne}) seg(P(r, az(i), el(j)), P(r, az(i + 1), el(j)));
        for (int j = 0; j < ne; ++j)
            for (int i : {0, na}) seg(P(r, az(i), el(j)), P(r, az(i), el(j + 1)));
    }
    for (int i = 1; i < na; i += std::max(1, na / 4))
        for (int j = 0; j < ne; ++j) seg(P(r1, az(i), el(j)), P(r1, az(i), el(j + 1)));
    for (int j = 1; j < ne; j += std::max(1, ne / 2))
        for (int i = 0; i < na; ++i) seg(P(r1, az(i), el(j)), P(r1, az(i + 1), el(j)));

    // Side faces: the planes of the edge azimuths and elevations between r_min and r_max.
    for (int i = 0; i < na; ++i)
        for (int j : {0, ne})
            quad(P(r0, az(i), el(j)), P(r1, az(i), el(j)), P(r1, az(i + 1), el(j)), P(r0, az(i + 1), el(j)));
    for (int j = 0; j < ne; ++j)
        for (int i : {0, na})
            quad(P(r0, az(i), el(j)), P(r1, az(i), el(j)), P(r1, az(i), el(j + 1)), P(r0, az(i), el(j + 1)));
    // Edges from the near to the far cap, and the lines from the sonar to the near cap's corners.
    for (int i : {0, na})
        for (int j : {0, ne}) {
            seg(P(r0, az(i), el(j)), P(r1, az(i), el(j)));
            seg(P(0, 0, 0), P(r0, az(i), el(j)));
        }
    return f;
}

std::vector<glm::vec3> floor_footprint(const SonarParams& s, double z0, int steps) {
    std::vector<glm::vec3> out;
    const glm::dvec3 o = to_glm(s.pose.position_m);
    const glm::dmat3 R = rotation_matrix(s.pose.orientation_deg);
    const std::shared_ptr<const SonarGrid> grid_ptr =
        sonar_grid(s); // held: the registry keeps only what someone holds
    const SonarGrid& grid = *grid_ptr;
    const double pa = grid.port_edge_deg(), sa = grid.starboard_edge_deg(), he = grid.elevation_half_deg();
    // Floor hit of the ray (a, e) when its range lies in the window.
    auto hit = [&](double a, double e) -> std::optional<glm::vec3> {
        const glm::dvec3 d = R * sonar_direction(deg2rad(a), deg2rad(e));
        if (d.z >= -1e-12) return std::nullopt;
        const double t = (z0 - o.z) / d.z;
        if (t < s.range_min_m || t > s.range_max_m) return std::nullopt;
        return glm::vec3(o + t * d);
    };
    auto edge = [&](auto point_at) {
        std::optional<glm::vec3> prev;
        for (int k = 0; k <= steps; ++k) {
            const auto p = point_at(double(k) / steps);
            if (p && prev) out.insert(out.end(), {*prev, *p});
            prev = p;
        }
    };
    // The four edges of the field of view where their rays meet the floor inside the range window ...
    for (double e : {-he, he}) edge([&](double u) { return hit(pa - (pa - sa) * u, e); });
    for (double a : {sa, pa}) edge([&](double u) { return hit(a, he - 2 * he * u); });
    // ... and the arcs where the spheres r_min and r_max cut the floor inside the field of view.
    for (double r : {s.range_min_m, s.range_max_m})
        edge([&](double u) -> std::optional<glm::vec3> {
            const double a = pa - (pa - sa) * u;
            auto f = [&](double e) { return o.z + r * (R * sonar_direction(deg2rad(a), deg2rad(e))).z - z0; };
            double lo = -he, hi = he, flo = f(lo), fhi = f(hi);
            if (r <= 0 || flo * fhi > 0) return std::nullopt;
            for (int it = 0; it < 50; ++it) {
                const double mid = 0.5 * (lo + hi), fm = f(mid);
                if ((fm < 0) == (flo < 0))
                    lo = mid, flo = fm;
                else
                    hi = mid;
            }
            return glm::vec3(sonar_point(s, r, a, 0.5 * (lo + hi)));
        });
    return out;
}

std::vector<SonarParams> fields_of_view(const SceneDesc& scene, const std::vector<Ping>* along) {
    if (scene.sonar.kind == SonarKind::Imaging) return {scene.sonar};
    const bool is_along = along && !along->empty();
    const std::vector<Ping> own = is_along ? std::vector<Ping>{} : ping_schedule(scene);
    const std::vector<Ping>& pings = is_along ? *along : own;
    if (pings.empty()) return {};
    std::vector<const Ping*> drawn;
    if (scene.sonar.kind == SonarKind::Sidescan) {
        drawn = {is_along ? &pings.back() : &pings.front()}; // the ping heard from the sonar's pose
    } else { // the sector's first step (the sweep's count 0 modulo its steps) and the head's newest step
        const auto n = std::int64_t(pings.size());
        drawn = {&pings[size_t((((-pings.front().number) % n) + n) % n)], &pings.back()};
        if (drawn[0] == drawn[1]) drawn.pop_back();
    }
    const SceneDesc beam = beam_scene(scene);
    std::vector<SonarParams> out;
    for (const Ping* p : drawn)
        for (int ch = 0; ch < channel_count(scene.sonar.kind); ++ch) {
            SonarParams s = beam.sonar;
            s.pose = transducer_pose(scene, *p, ch);
            out.push_back(s);
        }
    return out;
}

TriMesh sonar_body(const SonarParams& s) {
    const Vec3d size{0.16, 0.11, 0.09};
    TriMesh m = make_box(size);
    const glm::dmat3 R = rotation_matrix(s.pose.orientation_deg);
    const glm::dvec3 o = to_glm(s.pose.position_m);
    for (auto& v : m.vertices) v = glm::vec3(o + R * (glm::dvec3(v) - glm::dvec3(size[0] / 2, 0, 0)));
    return m;
}

std::vector<glm::dvec3> elevation_arc(const SonarParams& s, double r, double a_deg, int n) {
    n = std::max(2, n);
    std::vector<glm::dvec3> pts;
    pts.reserve(size_t(n));
    const double he = sonar_grid(s)->elevation_half_deg();
    for (int j = 0; j < n; ++j) pts.push_back(sonar_point(s, r, a_deg, he - 2 * he * j / (n - 1)));
    return pts;
}

bool polar_to_cell(const SonarParams& s, double r, double a_deg, int& bin, int& beam) {
    const std::shared_ptr<const SonarGrid> grid = sonar_grid(s);
    if (!grid->inside(r, a_deg)) return false;
    bin = grid->bin_of(r), beam = grid->beam_of_azimuth_deg(a_deg);
    return true;
}

std::optional<ImagePlace> sector_pixel_place(const SectorLayout& L, const SonarParams& s, double px,
                                             double py) {
    ImagePlace p;
    if (!L.pixel_to_polar(px, py, p.range_m, p.azimuth_deg)) return std::nullopt;
    if (!polar_to_cell(s, p.range_m, p.azimuth_deg, p.bin, p.beam)) return std::nullopt;
    return p;
}

std::optional<ImagePlace> polar_pixel_place(const SonarParams& s, double col, double row) {
    if (!(col >= 0 && col < s.beams && row >= 0 && row < s.range_bins)) return std::nullopt;
    ImagePlace p;
    const std::shared_ptr<const SonarGrid> grid = sonar_grid(s);
    p.range_m = s.range_max_m - row * grid->bin_m;
    p.azimuth_deg = grid->column_azimuth_deg(col);
    p.beam = std::min(int(col), s.beams - 1);
    p.bin = s.range_bins - 1 - std::min(int(row), s.range_bins - 1);
    return p;
}

PointInImage locate_world_point(const SonarParams& s, const SectorLayout& L, const glm::dvec3& p) {
    const Polar q = world_to_sonar_polar(s.pose, p);
    PointInImage out;
    out.range_m = q.range_m, out.azimuth_deg = q.azimuth_deg, out.elevation_deg = q.elevation_deg;
    L.polar_to_pixel(q.range_m, q.azimuth_deg, out.px, out.py);
    out.in_view = polar_to_cell(s, q.range_m, q.azimuth_deg, out.bin, out.beam) &&
                  L.grid().in_elevation_deg(q.elevation_deg);
    return out;
}

std::vector<glm::vec3> echoing_points(const TraceResult& hits, const SceneDesc& s, int bin, int beam) {
    std::vector<glm::vec3> out;
    if (beam < 0 || beam >= hits.beams || size_t(beam) >= hits.cells.size()) return out;
    const std::shared_ptr<const SonarGrid> grid = sonar_grid(s.sonar);
    const double r0 = grid->bin_near_edge_m(bin), r1 = grid->bin_near_edge_m(bin + 1);
    for (const Cell& c : hits.cells[size_t(beam)])
        if (cell_fraction_in(c, s.sampling.binning, r0, r1) > 0) out.push_back(c.point_m);
    return out;
}

std::vector<std::shared_ptr<const TriMesh>> object_meshes(const SceneDesc& s) {
    std::vector<std::shared_ptr<const TriMesh>> out;
    for (size_t i = 0; i < s.objects.size(); ++i) {
        const ObjectDesc& o = s.objects[i];
        const std::string key = "objects[" + std::to_string(i) + "]";
        out.push_back(o.box_m ? std::make_shared<const TriMesh>(make_box(*o.box_m))
                              : cached_mesh(o.mesh_resolved, s.source_file, key + ".mesh"));
        glm::vec3 lo, hi;
        mesh_bounds(*out.back(), lo, hi);
        const glm::dmat4 m = object_transform(o);
        for (int c = 0; c < 8; ++c)
            check_single_precision(glm::dvec3(m * glm::dvec4(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y,
                                                             c & 4 ? hi.z : lo.z, 1.0)),
                                   s.source_file, key);
    }
    return out;
}

} // namespace sonarsim::ui
