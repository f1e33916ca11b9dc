// Pose, beam and range-bin geometry against the paper's equations written out here independently.
#include "core/data/pose.hpp"
#include "core/scene/scene_io.hpp"

#include "core/grid/sonar_grid.hpp"
#include <catch2/catch.hpp>
#include <cmath>

using namespace sonarsim;

namespace {

/// Paper eq. 12 (psi = roll, theta = pitch, varphi = yaw), row by row as printed.
void paper_eq12(double roll_deg, double pitch_deg, double yaw_deg, double m[3][3]) {
    const double ps = deg2rad(roll_deg), th = deg2rad(pitch_deg), ph = deg2rad(yaw_deg);
    const double cps = std::cos(ps), sps = std::sin(ps), cth = std::cos(th), sth = std::sin(th);
    const double cph = std::cos(ph), sph = std::sin(ph);
    m[0][0] = cth * cph, m[0][1] = -cps * sph + cph * sth * sps, m[0][2] = sps * sph + cps * cph * sth;
    m[1][0] = cth * sph, m[1][1] = cps * cph + sth * sps * sph, m[1][2] = -cph * sps + cps * sth * sph;
    m[2][0] = -sth, m[2][1] = cth * sps, m[2][2] = cth * cps;
}

/// Rz(yaw) * Ry(pitch) * Rx(roll) as a product of the three elementary rotations.
void product_zyx(double roll_deg, double pitch_deg, double yaw_deg, double m[3][3]) {
    const double r = deg2rad(roll_deg), p = deg2rad(pitch_deg), y = deg2rad(yaw_deg);
    const double Rz[3][3] = {{std::cos(y), -std::sin(y), 0}, {std::sin(y), std::cos(y), 0}, {0, 0, 1}};
    const double Ry[3][3] = {{std::cos(p), 0, std::sin(p)}, {0, 1, 0}, {-std::sin(p), 0, std::cos(p)}};
    const double Rx[3][3] = {{1, 0, 0}, {0, std::cos(r), -std::sin(r)}, {0, std::sin(r), std::cos(r)}};
    double t[3][3] = {};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) t[i][j] += Ry[i][k] * Rx[k][j];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            m[i][j] = 0;
            for (int k = 0; k < 3; ++k) m[i][j] += Rz[i][k] * t[k][j];
        }
}

const Vec3d kOrientations[] = {Pose{}.orientation_deg,
                               kFig9Pose2.orientation_deg,
                               {0, 0, 0},
                               {90, 0, 0},
                               {0, 90, 0},
                               {0, 0, 90},
                               {-170, 45, 135},
                               {33, -60, -250}};

/// Azimuth and range of a world point computed here, without world_to_sonar_polar.
void own_polar(const Pose& pose, const Vec3d& pt, double& az_deg, double& range) {
    double m[3][3];
    paper_eq12(pose.orientation_deg[0], pose.orientation_deg[1], pose.orientation_deg[2], m);
    const double d[3] = {pt[0] - pose.position_m[0], pt[1] - pose.position_m[1], pt[2] - pose.position_m[2]};
    double local[3] = {};
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) local[j] += m[i][j] * d[i]; // R^T d
    az_deg = rad2deg(std::atan2(local[1], local[0]));
    range = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

} // namespace

TEST_CASE("rotation_matrix equals paper eq. 12 element by element", "[pose]") {
    for (const Vec3d& o : kOrientations) {
        INFO("roll " << o[0] << " pitch " << o[1] << " yaw " << o[2]);
        const glm::dmat3 R = rotation_matrix(o);
        double eq12[3][3], prod[3][3];
        paper_eq12(o[0], o[1], o[2], eq12);
        product_zyx(o[0], o[1], o[2], prod);
        for (int row = 0; row < 3; ++row)
            for (int col = 0; col < 3; ++col) {
                INFO("row " << row << " col " << col);
                CHECK(eq12[row][col] == Approx(prod[row][col]).margin(1e-14)); // the test's own two forms
                CHECK(R[col][row] == Approx(eq12[row][col]).margin(1e-14));    // glm: m[col][row]
            }
    }
}

TEST_CASE("rotation_matrix is a rotation and positive pitch looks down", "[pose]") {
    for (const Vec3d& o : kOrientations) {
        INFO("roll " << o[0] << " pitch " << o[1] << " yaw " << o[2]);
        const glm::dmat3 R = rotation_matrix(o);
        const glm::dmat3 I = glm::transpose(R) * R;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) CHECK(I[i][j] == Approx(i == j ? 1.0 : 0.0).margin(1e-14));
        CHECK(glm::determinant(R) == Approx(1.0).margin(1e-14));
        const glm::dvec3 bore = R * glm::dvec3(1, 0, 0);
        CHECK(bore.z == Approx(-std::sin(deg2rad(o[1]))).margin(1e-14));
        // Yaw turns the boresight's horizontal part by yaw from +x (for |pitch| < 90).
        if (std::abs(std::cos(deg2rad(o[1]))) > 1e-9)
            CHECK(std::atan2(bore.y, bore.x) == Approx(std::remainder(deg2rad(o[2]), 2 * kPi)).margin(1e-12));
    }
    const glm::dmat3 R = rotation_matrix({0, 30, 0});
    CHECK((R * glm::dvec3(1, 0, 0)).z < 0); // looks down
    const glm::dmat3 Y = rotation_matrix({0, 0, 90});
    const glm::dvec3 b = Y * glm::dvec3(1, 0, 0), port = Y * glm::dvec3(0, 1, 0);
    CHECK(b.y == Approx(1.0)); // yaw +90 deg: boresight along +y
    CHECK(port.x == Approx(-1.0));
    const glm::dvec3 up = rotation_matrix({20, 0, 0}) * glm::dvec3(0, 0, 1);
    CHECK(up.y == Approx(-std::sin(deg2rad(20.0)))); // positive roll turns the top towards starboard
}

TEST_CASE("sonar_direction is (cos e cos a, cos e sin a, sin e)", "[pose]") {
    const glm::dvec3 fwd = sonar_direction(0, 0), port = sonar_direction(kPi / 2, 0),
                     up = sonar_direction(0, kPi / 2);
    CHECK(fwd.x == Approx(1.0));
    CHECK(port.y == Approx(1.0)); // positive azimuth is port (sonar +y)
    CHECK(port.x == Approx(0.0).margin(1e-15));
    CHECK(up.z == Approx(1.0)); // positive elevation is up
    const double a = deg2rad(12.5), e = deg2rad(-6.0);
    const glm::dvec3 d = sonar_direction(a, e);
    CHECK(d.x == Approx(std::cos(e) * std::cos(a)).epsilon(1e-15));
    CHECK(d.y == Approx(std::cos(e) * std::sin(a)).epsilon(1e-15));
    CHECK(d.z == Approx(std::sin(e)).epsilon(1e-15));
    CHECK(glm::length(d) == Approx(1.0).epsilon(1e-15));
}

TEST_CASE("beam azimuths: a_i = Theta/2 - (i + 1/2) Theta/N, beam 0 port-most", "[pose]") {
    SonarParams s; // 32 deg, 128 beams
    const std::vector<double> a = sonar_grid(s)->beam_azimuths_deg();
    REQUIRE(a.size() == 128);
    CHECK(a[0] == Approx(16.0 - 0.125));
    CHECK(a[127] == Approx(-16.0 + 0.125));
    CHECK(a[63] == Approx(0.125));
    CHECK(a[64] == Approx(-0.125));
    for (size_t i = 1; i < a.size(); ++i) CHECK(a[i - 1] - a[i] == Approx(0.25));
    s.azimuth_fov_deg = 30, s.beams = 3;
    const std::vector<double> b = sonar_grid(s)->beam_azimuths_deg();
    REQUIRE(b.size() == 3);
    CHECK(b[0] == Approx(10.0));
    CHECK(b[1] == Approx(0.0).margin(1e-14));
    CHECK(b[2] == Approx(-10.0));
}

TEST_CASE("range bin edges: K + 1 edges, r_min + k dr, last exactly r_max", "[pose]") {
    SonarParams s; // [0.5, 5) m, 512 bins
    const std::vector<double> e = sonar_grid(s)->bin_edges_m();
    REQUIRE(e.size() == 513);
    CHECK(e.front() == 0.5);
    CHECK(e.back() == 5.0);
    CHECK(e[256] == Approx(0.5 + 256 * 4.5 / 512));
    for (size_t k = 1; k < e.size(); ++k) CHECK(e[k] - e[k - 1] == Approx(4.5 / 512).epsilon(1e-9));
    s.range_min_m = 1.0, s.range_max_m = 2.0, s.range_bins = 4;
    CHECK(sonar_grid(s)->bin_edges_m() == std::vector<double>{1.0, 1.25, 1.5, 1.75, 2.0});
}

TEST_CASE("world_to_sonar_polar of points placed along known directions", "[pose]") {
    Pose p;
    p.position_m = {1, -2, 3};
    p.orientation_deg = {15, 25, -70};
    const glm::dmat3 R = rotation_matrix(p.orientation_deg);
    for (double a_deg : {-15.0, 0.0, 7.5})
        for (double e_deg : {-6.0, 0.0, 4.0}) {
            const glm::dvec3 w =
                to_glm(p.position_m) + 2.5 * (R * sonar_direction(deg2rad(a_deg), deg2rad(e_deg)));
            const Polar q = world_to_sonar_polar(p, w);
            CHECK(q.range_m == Approx(2.5).epsilon(1e-12));
            CHECK(q.azimuth_deg == Approx(a_deg).margin(1e-10));
            CHECK(q.elevation_deg == Approx(e_deg).margin(1e-10));
        }
}

TEST_CASE("Fig. 9 pose 1 sees the prism centre at +0.45 deg, 1.68 m", "[pose]") {
    const SceneDesc s = default_scene();
    const Polar p = world_to_sonar_polar(s.sonar.pose, to_glm(s.objects[0].position_m));
    CHECK(p.azimuth_deg == Approx(0.45).margin(0.05));
    CHECK(p.range_m == Approx(1.68).margin(0.005));
    double az, r;
    own_polar(s.sonar.pose, s.objects[0].position_m, az, r);
    CHECK(p.azimuth_deg == Approx(az).margin(1e-9));
    CHECK(p.range_m == Approx(r).epsilon(1e-12));
}

TEST_CASE("Fig. 9 pose 2 sees the prism centre at -11.6 deg, 1.32-1.45 m", "[pose]") {
    const SceneDesc s = default_scene();
    const Polar p = world_to_sonar_polar(kFig9Pose2, to_glm(s.objects[0].position_m));
    CHECK(p.azimuth_deg == Approx(-11.6).margin(0.1));
    CHECK(p.range_m >= 1.32);
    CHECK(p.range_m <= 1.45);
    double az, r;
    own_polar(kFig9Pose2, s.objects[0].position_m, az, r);
    CHECK(p.azimuth_deg == Approx(az).margin(1e-9));
    CHECK(p.range_m == Approx(r).epsilon(1e-12));
}
