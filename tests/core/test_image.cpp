// Display geometry: gray mapping, the raw image's orientation and the sector-formed (fan) image layout.
#include "core/display/image.hpp"
#include "core/data/pose.hpp"

#include "core/grid/sonar_grid.hpp"
#include <catch2/catch.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <limits>

using namespace sonarsim;

namespace {

/// A raw image with every bin -inf except beam `beam`, which holds `level` in every bin.
PolarImage one_beam(const SonarParams& s, int beam, float level) {
    PolarImage img;
    img.bins = s.range_bins, img.beams = s.beams;
    img.level_db.assign(size_t(img.bins) * img.beams, -std::numeric_limits<float>::infinity());
    for (int b = 0; b < img.bins; ++b) img.level_db[size_t(b) * img.beams + beam] = level;
    return img;
}

} // namespace

TEST_CASE("gray level = 255 clamp((L - lo) / (hi - lo))", "[image]") {
    CHECK(gray_level(100.0f, 80, 120) == Approx(127.5));
    CHECK(gray_level(80.0f, 80, 120) == 0.0f);
    CHECK(gray_level(130.0f, 80, 120) == 255.0f);
    CHECK(gray_level(-std::numeric_limits<float>::infinity(), 80, 120) == 0.0f);
    CHECK(gray_level(10.0f, 0, 40) == Approx(63.75));
}

TEST_CASE("SectorLayout: pixel <-> polar round trip", "[image]") {
    SonarParams s;
    const SectorLayout L(s, 512);
    REQUIRE(L.height() == 512);
    for (double r : {0.6, 1.0, 2.5, 4.9})
        for (double a : {-15.9, -7.0, 0.0, 3.3, 15.9}) {
            double px, py, r2, a2;
            L.polar_to_pixel(r, a, px, py);
            CHECK(L.pixel_to_polar(px, py, r2, a2));
            CHECK(r2 == Approx(r).epsilon(1e-12));
            CHECK(a2 == Approx(a).margin(1e-10));
        }
    // And the other way, for pixel centres inside the fan.
    int inside = 0;
    for (int py = 0; py < L.height(); py += 37)
        for (int px = 0; px < L.width(); px += 29) {
            double r, a, qx, qy;
            if (!L.pixel_to_polar(px + 0.5, py + 0.5, r, a)) continue;
            ++inside;
            CHECK(r >= s.range_min_m);
            CHECK(r < s.range_max_m);
            L.polar_to_pixel(r, a, qx, qy);
            CHECK(qx == Approx(px + 0.5).margin(1e-9));
            CHECK(qy == Approx(py + 0.5).margin(1e-9));
        }
    CHECK(inside > 50);
}

TEST_CASE("SectorLayout: apex at the bottom centre, range up, port on the left", "[image]") {
    SonarParams s;
    s.range_min_m = 0; // the apex itself is then inside the image's bottom edge
    const SectorLayout L(s, 400);
    double px, py;
    L.polar_to_pixel(0, 0, px, py);
    CHECK(px == Approx(L.width() / 2.0));
    CHECK(py == Approx(double(L.height())));
    // Range grows upward along the boresight; r_max at the top edge.
    L.polar_to_pixel(s.range_max_m, 0, px, py);
    CHECK(px == Approx(L.width() / 2.0));
    CHECK(py == Approx(0.0).margin(1e-9));
    // Port (positive azimuth) is on the left, starboard on the right, symmetric.
    double lx, ly, rx, ry;
    L.polar_to_pixel(3, 10, lx, ly);
    L.polar_to_pixel(3, -10, rx, ry);
    CHECK(lx < L.width() / 2.0);
    CHECK(rx > L.width() / 2.0);
    CHECK(lx + rx == Approx(double(L.width())));
    CHECK(ly == Approx(ry));
    // The fan's edges: +-Theta/2 at r_max touch the image's sides.
    L.polar_to_pixel(s.range_max_m, s.azimuth_fov_deg / 2, lx, ly);
    CHECK(lx == Approx(0.0).margin(1.0));
    double r, a;
    CHECK_FALSE(L.pixel_to_polar(0.5, 0.5, r, a)); // top-left corner lies outside the fan
    CHECK_FALSE(L.pixel_to_polar(L.width() / 2.0, L.height() + 5.0, r, a)); // below the apex
}

TEST_CASE("SectorLayout: polar_to_index hits bin and beam centres", "[image]") {
    SonarParams s;
    const SectorLayout L(s, 512);
    const std::vector<double> az = sonar_grid(s)->beam_azimuths_deg();
    const double dr = (s.range_max_m - s.range_min_m) / s.range_bins;
    for (int k : {0, 100, 511})
        for (int i : {0, 40, 127}) {
            double bin, beam;
            L.polar_to_index(s.range_min_m + (k + 0.5) * dr, az[size_t(i)], bin, beam);
            CHECK(bin == Approx(k).margin(1e-9));
            CHECK(beam == Approx(i).margin(1e-9));
        }
}

TEST_CASE("sector and raw images put beam 0 (port) on the left, near range at the bottom", "[image]") {
    SonarParams s;
    s.range_bins = 64, s.beams = 32;
    DisplayParams d; // 80..120 dB
    const Image8 sec = sector_image(one_beam(s, 0, 120.0f), s, d, 256);
    REQUIRE(sec.channels == 3);
    const SectorLayout L(s, 256);
    REQUIRE(sec.width == L.width());
    auto gray_at = [&](double r, double a) {
        double px, py;
        L.polar_to_pixel(r, a, px, py);
        return int(sec.pixels[(size_t(py) * sec.width + size_t(px)) * 3]);
    };
    const std::vector<double> az = sonar_grid(s)->beam_azimuths_deg();
    CHECK(gray_at(3.0, az[0]) > 128); // the lit beam (bilinear across beams), left side
    CHECK(gray_at(3.0, az[2]) == 0);
    CHECK(gray_at(3.0, az[31]) == 0); // the starboard-most beam stays black
    CHECK(gray_at(3.0, 0.0) == 0);
    // The raw image: column i = beam i, data row 0 (nearest) at the bottom.
    PolarImage raw = one_beam(s, 0, 120.0f);
    raw.level_db[0 * 32 + 5] = 100.0f; // bin 0, beam 5
    const Image8 g = polar_gray_image(raw, d);
    REQUIRE(g.width == 32);
    REQUIRE(g.height == 64);
    CHECK(int(g.pixels[0]) == 255);                   // top row, column 0
    CHECK(int(g.pixels[31]) == 0);                    // top row, column 31
    CHECK(int(g.pixels[size_t(63) * 32 + 5]) == 128); // bottom row = bin 0
    CHECK(int(g.pixels[5]) == 0);                     // top row = last bin
}

namespace {

/// The fan by its definition, one pixel at a time: what SectorResampler must reproduce exactly.
Image8 reference_sector(const PolarImage& img, const SonarParams& s, const DisplayParams& d, int height_px) {
    const SectorLayout L(s, height_px > 0 ? height_px : default_sector_height(s));
    const int K = s.range_bins, N = s.beams;
    Image8 out;
    out.width = L.width(), out.height = L.height(), out.channels = 3;
    for (int py = 0; py < L.height(); ++py)
        for (int px = 0; px < L.width(); ++px) {
            std::array<std::uint8_t, 3> c = kFanBackground;
            double r, a, fb, fi;
            if (L.pixel_to_polar(px + 0.5, py + 0.5, r, a)) {
                L.polar_to_index(r, a, fb, fi);
                fb = std::clamp(fb, 0.0, K - 1.0), fi = std::clamp(fi, 0.0, N - 1.0);
                const int b0 = std::min(int(fb), K - 1), i0 = std::min(int(fi), N - 1);
                const int b1 = std::min(b0 + 1, K - 1), i1 = std::min(i0 + 1, N - 1);
                // Weights kept to 1/32768.
                const float tb = float(std::lround((fb - b0) * 32768)) / 32768,
                            ti = float(std::lround((fi - i0) * 32768)) / 32768;
                auto g = [&](int b, int i) { return gray_level(img.at(b, i), d.lo_db, d.hi_db); };
                const float v = (1 - tb) * ((1 - ti) * g(b0, i0) + ti * g(b0, i1)) +
                                tb * ((1 - ti) * g(b1, i0) + ti * g(b1, i1));
                c = colormap_rgb(d.colormap, std::clamp(int(std::lround(v)), 0, 255) / 255.0);
            }
            out.pixels.insert(out.pixels.end(), c.begin(), c.end());
        }
    return out;
}

/// Levels spread over and beyond the display window, with holes (-inf) where nothing echoes.
PolarImage varied_image(const SonarParams& s) {
    PolarImage img;
    img.bins = s.range_bins, img.beams = s.beams;
    img.level_db.resize(size_t(img.bins) * img.beams);
    for (size_t n = 0; n < img.level_db.size(); ++n)
        img.level_db[n] = n % 11 == 0 ? -std::numeric_limits<float>::infinity()
                                      : float(60 + double((n * 7919) % 8000) / 100);
    img.level_db[img.level_db.size() / 2] = std::numeric_limits<float>::quiet_NaN();
    img.level_db[img.level_db.size() / 3] = std::numeric_limits<float>::infinity();
    return img;
}

} // namespace

TEST_CASE("the fast fan equals the per-pixel definition exactly", "[image]") {
    struct Case {
        const char* what;
        double fov_deg, r_min_m, r_max_m;
        int beams, bins, height_px;
        const char* table = "uniform"; ///< a beam table: its own field of view
    };
    const Case cases[] = {
        {"the paper's sonar", 32, 0.5, 5, 128, 512, 0},
        {"a wide fan", 130, 1, 120, 96, 300, 0},
        {"apex inside the image", 90, 0, 10, 64, 200, 333},
        {"one beam, few bins", 20, 1, 2, 1, 3, 64},
        {"a thin annulus", 130, 100, 120, 40, 2048, 0},
        {"a half disc", 180, 0.2, 3, 50, 256, 0},
        {"wider than a right angle", 100, 0.5, 8, 33, 400, 401},
        {"a measured beam table (Oculus M750d LF)", 0, 0.1, 40, 512, 500, 0, "oculus_m750d_lf_512"},
        {"an asymmetric beam table (ARIS 1800)", 0, 1, 5, 96, 300, 0, "aris1800_96"}};
    for (const Case& c : cases)
        for (Colormap map : {Colormap::Gray, Colormap::Viridis}) {
            SonarParams s;
            s.azimuth_fov_deg = c.fov_deg, s.range_min_m = c.r_min_m, s.range_max_m = c.r_max_m;
            s.beams = c.beams, s.range_bins = c.bins, s.beam_table = c.table;
            if (s.beam_table != "uniform") s.azimuth_fov_deg = sonar_grid(s)->fov_deg;
            DisplayParams d;
            d.colormap = map;
            const PolarImage img = varied_image(s);
            const SectorResampler fast(s, c.height_px);
            const Image8 want = reference_sector(img, s, d, c.height_px);
            for (auto kernel : {SectorResampler::Kernel::Best, SectorResampler::Kernel::Portable}) {
                const Image8 got = fast.apply(img, d, kernel);
                INFO(c.what << (kernel == SectorResampler::Kernel::Best ? " (best kernel)" : " (portable)"));
                REQUIRE(got.width == want.width);
                REQUIRE(got.height == want.height);
                CHECK(got.width <= kMaxSectorWidth);
                CHECK(got.pixels == want.pixels);
            }
        }
}

TEST_CASE("the no-echo colour marks the pixels whose nearest sample has no echo", "[image]") {
    // Reference: each pixel's (bin, beam) from its range and azimuth, rounded to the nearest sample. The taps
    // keep the fractions to 1/32768, so a pixel within that of the half-way line may go either way.
    struct Case {
        const char* what;
        double fov_deg, r_min_m, r_max_m;
        int beams, bins;
        const char* table;
    };
    const Case cases[] = {{"a wide fan", 130, 1, 120, 96, 300, "uniform"},
                          {"apex inside the image", 90, 0, 10, 64, 200, "uniform"},
                          {"an asymmetric beam table", 28, 1, 5, 96, 200, "aris1800_96"}};
    const std::array<std::uint8_t, 3> mark{1, 254, 3};
    for (const Case& c : cases) {
        INFO(c.what);
        SonarParams s;
        s.azimuth_fov_deg = c.fov_deg, s.range_min_m = c.r_min_m, s.range_max_m = c.r_max_m;
        s.beams = c.beams, s.range_bins = c.bins, s.beam_table = c.table;
        if (std::string(c.table) != "uniform") s.azimuth_fov_deg = sonar_grid(s)->fov_deg;
        const PolarImage img = varied_image(s); // every 11th sample -inf
        const SectorResampler fan(s, 0);
        Image8 out = fan.apply(img, DisplayParams{});
        fan.paint_no_echo(img, mark, out);
        const SectorLayout& L = fan.layout();
        long marked = 0, want_marked = 0, ties = 0, wrong = 0;
        for (int py = 0; py < L.height(); ++py)
            for (int px = 0; px < L.width(); ++px) {
                const std::uint8_t* p = out.pixels.data() + (size_t(py) * size_t(L.width()) + size_t(px)) * 3;
                const bool got = p[0] == mark[0] && p[1] == mark[1] && p[2] == mark[2];
                marked += got;
                double r, a, fb, fi;
                if (!L.pixel_to_polar(px + 0.5, py + 0.5, r, a)) {
                    wrong += got;
                    continue;
                }
                L.polar_to_index(r, a, fb, fi);
                fb = std::clamp(fb, 0.0, s.range_bins - 1.0), fi = std::clamp(fi, 0.0, s.beams - 1.0);
                const int b = int(std::lround(fb)), i = int(std::lround(fi));
                const bool want = !(img.at(b, i) > -INFINITY);
                want_marked += want;
                if (got == want) continue;
                const double tie =
                    std::min(std::abs(fb - std::floor(fb) - 0.5), std::abs(fi - std::floor(fi) - 0.5));
                (tie < 2.0 / SectorResampler::kWeightOne ? ties : wrong) += 1;
            }
        CHECK(want_marked > 1000);
        CHECK(wrong == 0);
        CHECK(ties <= want_marked / 1000);
        CHECK(std::abs(marked - want_marked) <= ties);
    }
}

TEST_CASE("default sector height: one row per bin, width within bounds", "[image]") {
    SonarParams s;
    s.azimuth_fov_deg = 130, s.range_min_m = 1, s.range_max_m = 120, s.beams = 512, s.range_bins = 1500;
    CHECK(default_sector_height(s) == 1500);
    // 2 r_max sin(65 deg) wide over r_max - r_min cos(65 deg) high.
    CHECK(SectorLayout(s, 1500).width() ==
          int(std::ceil(2 * 120 * std::sin(deg2rad(65.0)) / ((120 - std::cos(deg2rad(65.0))) / 1500))));
    CHECK(SectorLayout(s, 1500).width() == 2729);
    s.range_bins = 4096;
    CHECK(default_sector_height(s) == 2048);
    s.range_bins = 100;
    CHECK(default_sector_height(s) == 256);
    s.range_min_m = 100, s.range_bins = 2048; // a thin far annulus: its width would pass 4096 px
    const int h = default_sector_height(s);
    CHECK(h < 2048);
    CHECK(SectorLayout(s, h).width() <= kMaxSectorWidth);
    CHECK(SectorLayout(s, h + 2).width() > kMaxSectorWidth - 8);
}

// Speed of forming the fan of wide sonars (hidden: `test_core "[.bench]"`). Prints the median of repeats.
TEST_CASE("SectorResampler speed on wide sonars", "[.bench]") {
    struct Case {
        int beams, bins;
    };
    for (const Case c : {Case{512, 1500}, Case{1024, 4096}}) {
        SonarParams s;
        s.beams = c.beams, s.range_bins = c.bins;
        s.azimuth_fov_deg = 130, s.range_min_m = 1, s.range_max_m = 120;
        PolarImage img;
        img.bins = s.range_bins, img.beams = s.beams;
        img.level_db.resize(size_t(img.bins) * img.beams);
        for (size_t n = 0; n < img.level_db.size(); ++n)
            img.level_db[n] =
                n % 7 == 0 ? -std::numeric_limits<float>::infinity() : float(70 + (n * 37) % 60);
        auto median_ms = [](int repeats, const auto& f) {
            std::vector<double> t;
            for (int k = 0; k < repeats; ++k) {
                const auto t0 = std::chrono::steady_clock::now();
                f();
                t.push_back(
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
            }
            std::sort(t.begin(), t.end());
            return t[t.size() / 2];
        };
        std::unique_ptr<SectorResampler> r;
        const double build_ms = median_ms(5, [&] { r = std::make_unique<SectorResampler>(s, 0); });
        DisplayParams d;
        size_t sink = 0;
        const double gray_ms = median_ms(11, [&] { sink += r->apply(img, d).pixels[0]; });
        d.colormap = Colormap::Viridis;
        const double viridis_ms = median_ms(11, [&] { sink += r->apply(img, d).pixels[0]; });
        std::printf(
            "%d beams x %d bins -> %dx%d px: taps %.1f ms, apply gray %.1f ms, viridis %.1f ms (%zu)\n",
            c.beams, c.bins, r->layout().width(), r->layout().height(), build_ms, gray_ms, viridis_ms, sink);
    }
}
