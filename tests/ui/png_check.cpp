// Checks the PNGs of the GL tests.
//   ui_png_check window FILE.png [SCENE.json] : the viewer's window is not blank, and its fan (placed by
//       ui/model/panel_layout.hpp) shows the echo where core's own sector image of the Fig. 9 scene (or of
//       SCENE.json, a snapshot's scene after a drag: then the sonar must have moved and the fan must match
//       the moved scene better than the Fig. 9 one) has it.
//   ui_png_check view3d FILE.png : the headless 3D view is not blank and shows the floor and the prism.
//   ui_png_check hover FILE.png yes|no : an annotated snapshot shows the hovered cell's yellow outline, or
//   not.
#include "ui/model/layout.hpp"
#include "ui/model/panel_layout.hpp"

#include "core/display/image.hpp"
#include "core/scene/scene_io.hpp"
#include "core/pipeline/simulator.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <set>
#include <stb_image.h>
#include <string>

namespace {

struct Png {
    int w = 0, h = 0;
    std::vector<unsigned char> rgb;
    const unsigned char* at(int x, int y) const { return &rgb[(size_t(y) * w + x) * 3]; }
};

bool load(const char* path, Png& out) {
    int n = 0;
    unsigned char* data = stbi_load(path, &out.w, &out.h, &n, 3);
    if (!data) return false;
    out.rgb.assign(data, data + size_t(out.w) * out.h * 3);
    stbi_image_free(data);
    return true;
}

int fail(const std::string& why) {
    std::fprintf(stderr, "FAIL: %s\n", why.c_str());
    return 1;
}

/// Not blank: many distinct colours and a spread of brightness.
bool not_blank(const Png& p, size_t min_colours, std::string& why) {
    std::set<unsigned> colours;
    double sum = 0, sum2 = 0;
    const size_t n = size_t(p.w) * p.h;
    for (size_t i = 0; i < n; i += 7) {
        const unsigned char* c = &p.rgb[i * 3];
        colours.insert(unsigned(c[0]) << 16 | unsigned(c[1]) << 8 | c[2]);
        const double l = (c[0] + c[1] + c[2]) / 3.0;
        sum += l, sum2 += l * l;
    }
    const double m = sum / double(n / 7), sd = std::sqrt(std::max(0.0, sum2 / double(n / 7) - m * m));
    std::printf("distinct colours %zu, brightness mean %.1f sd %.1f\n", colours.size(), m, sd);
    if (colours.size() < min_colours || sd < 8) {
        why = "the image is (nearly) blank";
        return false;
    }
    return true;
}

/// Correlation of the fan in the screenshot with core's sector image of `s`; counts bright fan pixels.
double fan_correlation(const Png& p, const sonarsim::SceneDesc& s, int& bright, std::string& why) {
    sonarsim::Simulator sim(s);
    const sonarsim::Image8& ref = sim.render()->sector();
    const auto L = sonarsim::ui::viewer_layout(p.w, p.h, 1.0f, sonarsim::ui::fan_aspect(s.sonar));
    const auto S = sonarsim::ui::sonar_panel_layout(
        L.sonar, {s.sonar, s.display.lo_db, s.display.hi_db, sonarsim::ui::colorbar_title(s), false}, {});
    const sonarsim::SectorLayout fan(s.sonar, ref.height);
    // Compare the screenshot's fan with the reference, pixel by pixel (nearest), inside the fan only.
    double n = 0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    bright = 0;
    for (int y = 0; y < int(S.image.h); ++y)
        for (int x = 0; x < int(S.image.w); ++x) {
            const double u = (x + 0.5) / S.image.w * ref.width, v = (y + 0.5) / S.image.h * ref.height;
            double r, a;
            if (!fan.pixel_to_polar(u, v, r, a)) continue;
            const int sx = int(S.image.x) + x, sy = int(S.image.y) + y;
            if (sx < 0 || sy < 0 || sx >= p.w || sy >= p.h) {
                why = "the fan lies outside the screenshot";
                return 0;
            }
            const double A = p.at(sx, sy)[0];
            const double B = ref.pixels[(size_t(int(v)) * ref.width + size_t(int(u))) * 3];
            n += 1, sa += A, sb += B, saa += A * A, sbb += B * B, sab += A * B;
            if (A > 150) ++bright;
        }
    if (n < 1000) {
        why = "the fan region is too small";
        return 0;
    }
    const double cov = sab / n - sa / n * sb / n;
    return cov / std::sqrt(std::max(1e-9, (saa / n - sa * sa / n / n) * (sbb / n - sb * sb / n / n)));
}

int check_window(const Png& p, const char* scene_file) {
    std::string why;
    if (!not_blank(p, 100, why)) return fail(why);
    const sonarsim::SceneDesc fig9 = sonarsim::default_scene();
    const sonarsim::SceneDesc s = scene_file ? sonarsim::load_scene(scene_file) : fig9;
    int bright = 0;
    const double corr = fan_correlation(p, s, bright, why);
    if (!why.empty()) return fail(why);
    std::printf("fan: %d bright px (> 150), correlation with core's sector image %.3f\n", bright, corr);
    if (bright < 200) return fail("the fan holds no bright echo");
    if (corr < 0.85) return fail("the fan does not show the echo where core's image has it");
    if (scene_file) {
        const auto& a = s.sonar.pose.position_m;
        const auto& b = fig9.sonar.pose.position_m;
        const double moved = std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
        int unused = 0;
        const double corr_fig9 = fan_correlation(p, fig9, unused, why);
        std::printf("sonar moved %.3f m; correlation with the Fig. 9 image %.3f\n", moved, corr_fig9);
        if (moved < 0.05) return fail("the drag did not move the sonar");
        if (!(corr > corr_fig9 + 0.02)) return fail("the fan did not follow the drag");
    }
    return 0;
}

int check_view3d(const Png& p) {
    std::string why;
    if (!not_blank(p, 12, why)) return fail(why); // flat shading: few distinct colours
    int sand = 0, prism = 0, shell = 0;
    for (int y = 0; y < p.h; ++y)
        for (int x = 0; x < p.w; ++x) {
            const unsigned char* c = p.at(x, y);
            const int r = c[0], g = c[1], b = c[2];
            if (r > 150 && g > 60 && g < r - 40 && b < 90)
                ++prism; // orange
            else if (r > 60 && r > g && g > b && r - b > 15 && r - b < 60)
                ++sand;
            if (b > r + 40 && g > r + 30) ++shell; // cyan field of view over the water or floor
        }
    std::printf("pixels: floor %d, prism %d, field of view %d\n", sand, prism, shell);
    if (sand < p.w * p.h / 10) return fail("no seafloor in the 3D view");
    if (prism < 30) return fail("no prism in the 3D view");
    if (shell < 200) return fail("no sonar field of view in the 3D view");
    return 0;
}

int check_hover(const Png& p, bool want) {
    int yellow = 0; // the hover colour of the sonar panel (255, 224, 25)
    for (int y = 0; y < p.h; ++y)
        for (int x = 0; x < p.w; ++x) {
            const unsigned char* c = p.at(x, y);
            if (c[0] > 230 && c[1] > 195 && c[1] < 245 && c[2] < 80) ++yellow;
        }
    std::printf("hover-yellow pixels: %d\n", yellow);
    if (want && yellow < 20) return fail("no hover marker where the pointer was over the image");
    if (!want && yellow > 4) return fail("a hover marker although the pointer was not over the image");
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 3 || argc > 4) {
        std::fprintf(
            stderr,
            "usage: ui_png_check window FILE.png [SCENE.json] | view3d FILE.png | hover FILE.png yes|no\n");
        return 2;
    }
    Png p;
    if (!load(argv[2], p)) return fail(std::string("cannot read ") + argv[2]);
    std::printf("%s: %d x %d\n", argv[2], p.w, p.h);
    if (std::strcmp(argv[1], "window") == 0) return check_window(p, argc == 4 ? argv[3] : nullptr);
    if (std::strcmp(argv[1], "view3d") == 0) return check_view3d(p);
    if (std::strcmp(argv[1], "hover") == 0 && argc == 4)
        return check_hover(p, std::strcmp(argv[3], "yes") == 0);
    std::fprintf(stderr, "unknown mode %s\n", argv[1]);
    return 2;
}
