// Beam tables (sonar.beam_table): the tables themselves, the grid built from them, and the angles a
// rendered image, its metadata and its fan carry.
#include "core/base/errors.hpp"
#include "core/grid/beam_tables.hpp"
#include "core/scene/devices.hpp"
#include "core/pipeline/simulator.hpp"
#include "core/scene/params.hpp"
#include "core/grid/sonar_grid.hpp"

#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>

using namespace sonarsim;

namespace {

/// A sonar at the origin looking along +x at nothing but a thin vertical pole 3 m away at azimuth a.
SceneDesc pole_scene(const std::string& table, double a_deg) {
    SceneDesc s;
    s.seafloor.reset();
    s.sonar.pose.position_m = {0, 0, 0};
    s.sonar.pose.orientation_deg = {0, 0, 0};
    s.sonar.azimuth_fov_deg = 27.58, s.sonar.beams = 48, s.sonar.beam_table = table;
    s.sonar.range_min_m = 2.5, s.sonar.range_max_m = 3.5, s.sonar.range_bins = 100;
    s.sampling.azimuth_rays = 27; // rays 0.016 deg apart in the narrowest beam: the pole is 0.04 deg wide
    ObjectDesc pole;
    pole.box_m = Vec3d{0.002, 0.002, 0.4};
    const double a = a_deg * 3.14159265358979323846 / 180;
    pole.position_m = {3.0 * std::cos(a), 3.0 * std::sin(a), 0.0};
    s.objects.push_back(pole);
    return s;
}

/// The beam with the most echo.
int brightest_beam(const PolarImage& img) {
    int best = -1;
    double top = 0;
    for (int b = 0; b < img.beams; ++b) {
        double e = 0;
        for (int k = 0; k < img.bins; ++k)
            if (std::isfinite(img.at(k, b))) e += std::pow(10.0, img.at(k, b) / 10);
        if (e > top) top = e, best = b;
    }
    return best;
}

} // namespace

TEST_CASE("every beam table is ordered port to starboard, and its edges hold its centres", "[beam_table]") {
    REQUIRE(beam_table_names().size() >= 9);
    for (const std::string& name : beam_table_names()) {
        INFO(name);
        const BeamTable& t = *find_beam_table(name);
        for (int i = 0; i < t.beams(); ++i) {
            const size_t k = size_t(i);
            CHECK(t.starboard_edge_deg[k] < t.centre_deg[k]);
            CHECK(t.centre_deg[k] < t.port_edge_deg[k]);
            if (i > 0)
                CHECK(t.port_edge_deg[k] == Approx(t.starboard_edge_deg[k - 1]).margin(1e-9)); // no gaps
        }
    }
    // The vendor's numbers, as the SDK gives them (ARIS beam 0 the starboard-most, so our last beam).
    const BeamTable& aris = *find_beam_table("aris3000_128");
    CHECK(aris.centre_deg.back() == -15.0068);
    CHECK(aris.starboard_edge_deg.back() == -15.1218);
    CHECK(aris.centre_deg.front() == 15.0156);
    CHECK(aris.device_beam.front() == 127);
    // Oculus: evenly spaced in sin(bearing), the ends exactly at +-30 deg, 0.01 deg steps.
    const BeamTable& oculus = *find_beam_table("oculus_m1200d_hf_512");
    CHECK(oculus.centre_deg.front() == 30.0);
    CHECK(oculus.centre_deg.back() == -30.0);
    const double s1 = std::sin(30 * 3.14159265358979323846 / 180) * (1 - 2.0 * 100 / 511);
    CHECK(oculus.centre_deg[100] == Approx(std::asin(s1) * 180 / 3.14159265358979323846).margin(0.01));
    // Gemini: the same rule over +-60 deg, to 1e-6 deg (a device-reported GLF table follows it within 4e-6).
    const BeamTable& gemini = *find_beam_table("gemini720is_512");
    REQUIRE(gemini.beams() == 512);
    for (int i : {0, 1, 100, 255, 256, 511}) {
        const double s = std::sin(60 * 3.14159265358979323846 / 180) * (1 - 2.0 * i / 511);
        CHECK(gemini.centre_deg[size_t(i)] ==
              Approx(std::asin(s) * 180 / 3.14159265358979323846).margin(1e-6));
    }
    CHECK(gemini.centre_deg[256] - gemini.centre_deg[257] < 0.2); // 0.194 deg apart at the centre
    CHECK(gemini.centre_deg[0] - gemini.centre_deg[1] > 0.38);    // 0.386 deg at the edges
}

TEST_CASE("each device preset's beam table has the preset's beam count", "[beam_table][devices]") {
    int with_table = 0;
    for (const DevicePreset& p : device_presets()) {
        int beams = 0;
        std::string table;
        for (const auto& v : p.values) {
            if (v.key == "sonar.beams") beams = v.value.get<int>();
            if (v.key == "sonar.beam_table") table = v.value.get<std::string>();
        }
        if (table.empty()) continue;
        INFO(p.name << ": " << table);
        ++with_table;
        REQUIRE(find_beam_table(table));
        CHECK(find_beam_table(table)->beams() == beams);
    }
    CHECK(with_table == 11); // five ARIS, the DIDSON, four Oculus, the Gemini
}

TEST_CASE("a grid from a table has the table's angles and its lookups invert them", "[beam_table]") {
    SonarParams s;
    s.beams = 96, s.beam_table = "aris1800_96";
    const SonarGrid g(s);
    const BeamTable& t = *g.table();
    CHECK(g.beam_azimuths_deg() == t.centre_deg);
    CHECK(g.fov_deg == Approx(13.9831 + 13.8562));
    for (int i = 0; i < g.beams; ++i) {
        INFO("beam " << i);
        CHECK(g.beam_of_azimuth_deg(t.centre_deg[size_t(i)]) == i);
        CHECK(g.beam_index_of_azimuth_deg(t.centre_deg[size_t(i)]) == Approx(i).margin(1e-9));
        CHECK(g.beam_width_deg(i) == Approx(t.port_edge_deg[size_t(i)] - t.starboard_edge_deg[size_t(i)]));
        CHECK(g.column_of_azimuth_deg(g.column_azimuth_deg(i + 0.25)) == Approx(i + 0.25));
    }
    CHECK(g.inside(3.0, 13.98));
    CHECK_FALSE(g.inside(3.0, 13.99));
    CHECK(g.inside(3.0, -13.85));
    CHECK_FALSE(g.inside(3.0, -13.86)); // the table is asymmetric
    // The fan maps each beam's centre back to that beam.
    const SectorLayout L(sonar_grid(s), 400);
    double bin = 0, beam = 0;
    for (int i : {0, 7, 48, 95}) {
        L.polar_to_index(3.0, t.centre_deg[size_t(i)], bin, beam);
        CHECK(beam == Approx(i).margin(1e-9));
    }
}

TEST_CASE("the beam of an azimuth in radians is the first whose starboard edge is at most it, clamped",
          "[beam_table]") {
    for (const std::string& name : beam_table_names()) {
        SonarParams s;
        s.beams = find_beam_table(name)->beams(), s.beam_table = name;
        const SonarGrid g(s);
        auto first_below = [&](double a) { // a linear search over the starboard edges
            int i = 0;
            while (i < g.beams - 1 && g.beam_starboard_edge_rad(i) > a) ++i;
            return i;
        };
        std::vector<double> az = {INFINITY, -INFINITY, NAN, 0.0, 1.0, -1.0};
        for (int i = 0; i < g.beams; ++i)
            for (double e : {g.beam_starboard_edge_rad(i), g.beam_port_edge_rad(i), g.beam_azimuth_rad(i)})
                az.insert(az.end(), {e, std::nextafter(e, 1.0), std::nextafter(e, -1.0)});
        for (int k = 0; k <= 10000; ++k) az.push_back((k / 5000.0 - 1) * (g.fan_half_rad + 0.01));
        int wrong = 0;
        for (double a : az) wrong += g.beam_of_azimuth_rad(a) != first_below(a);
        INFO(name);
        CHECK(wrong == 0);
    }
}

TEST_CASE("a pole at a table's beam centre lands in that beam and the metadata lists the table's angles",
          "[beam_table]") {
    // ARIS 1800 LF / 1200 (48 beams): the edge beams are narrower than the middle ones, so beam 9's centre
    // (9.2206 deg) lies two beams away under even spacing (beam 7).
    const BeamTable& t = *find_beam_table("aris1800_1200_48");
    const double a = t.centre_deg[9];
    {
        const SceneDesc s = pole_scene("aris1800_1200_48", a);
        Simulator sim(s);
        const auto f = sim.render();
        CHECK(brightest_beam(f->polar()) == 9);
        const json m = frame_metadata(s, *f);
        CHECK(m["beam_azimuths_deg"].get<std::vector<double>>() == t.centre_deg);
        CHECK(m["sonar"]["beam_table"] == "aris1800_1200_48");
    }
    {
        Simulator sim(pole_scene("uniform", a));
        CHECK(brightest_beam(sim.render()->polar()) == 7);
    }
}

TEST_CASE("a beam table of another beam count, or none of that name, is an input error", "[beam_table]") {
    SceneDesc s;
    s.sonar.beam_table = "aris3000_128";
    s.sonar.beams = 64;
    try {
        validate_scene(s, "scene.json", {});
        FAIL("no error");
    } catch (const InputError& e) {
        CHECK(e.key() == "sonar.beam_table");
        CHECK_THAT(e.message(), Catch::Contains("has 128 beams, sonar.beams is 64") &&
                                    Catch::Contains("allowed for 64 beams: uniform, aris3000_64"));
    }
    s.sonar.beams = 128;
    try { // the table's fan is 30.25 deg wide: a field of view of 32 deg is another fan
        validate_scene(s, "scene.json", {});
        FAIL("no error");
    } catch (const InputError& e) {
        CHECK(e.key() == "sonar.azimuth_fov_deg");
        CHECK_THAT(e.message(), Catch::Contains("not the fan of beam table aris3000_128"));
    }
    s.sonar.azimuth_fov_deg = 30.25;
    CHECK_NOTHROW(validate_scene(s, "scene.json", {}));
    CHECK_THROWS_AS(apply_setting_text(s, "sonar.beam_table=aris9000", "test"), InputError);
}

TEST_CASE("the fan of an asymmetric table ends at each side's own edge", "[beam_table]") {
    // ARIS 1800 with 96 beams: the port edge at +13.9831 deg, the starboard edge at -13.8562 deg.
    SonarParams s;
    s.beams = 96, s.beam_table = "aris1800_96", s.range_min_m = 1, s.range_max_m = 5, s.range_bins = 200;
    const SectorResampler fan(sonar_grid(s), 600);
    PolarImage img;
    img.bins = s.range_bins, img.beams = s.beams;
    img.level_db.assign(size_t(img.bins) * size_t(img.beams), 60.0f);
    DisplayParams d;
    d.lo_db = 0, d.hi_db = 100;
    const Image8 out = fan.apply(img, d);
    auto shown = [&](double a_deg) {
        double px = 0, py = 0;
        fan.layout().polar_to_pixel(4.5, a_deg, px, py);
        const size_t at = (size_t(py) * size_t(out.width) + size_t(px)) * 3;
        return !(out.pixels[at] == kFanBackground[0] && out.pixels[at + 1] == kFanBackground[1] &&
                 out.pixels[at + 2] == kFanBackground[2]);
    };
    CHECK(shown(13.93));
    CHECK(shown(-13.80));
    CHECK_FALSE(shown(-13.93)); // beyond the starboard edge, though within the port side's reach
    CHECK_FALSE(shown(14.05));
}

TEST_CASE("the cost of looking the grid up", "[.bench]") {
    SonarParams s;
    const auto held = sonar_grid(s); // as a frame holds it
    const int n = 1000000;
    const auto t0 = std::chrono::steady_clock::now();
    double sum = 0;
    for (int i = 0; i < n; ++i) sum += sonar_grid(s)->bin_m;
    const double ns =
        std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() / n;
    WARN("sonar_grid(): " << ns << " ns per call (" << sum << ")");
    s.beam_table = "oculus_m1200d_lf_512", s.beams = 512;
    const auto t0p = std::chrono::steady_clock::now();
    find_beam_table(s.beam_table); // the first use parses every table
    const double parse_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0p).count();
    WARN("parsing every beam table (first use): " << parse_ms << " ms");
    const auto t1 = std::chrono::steady_clock::now();
    const SonarGrid g(s);
    const double us =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t1).count();
    WARN("building a 512-beam table grid: " << us << " us (" << g.beams << " beams)");
}
