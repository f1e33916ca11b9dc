#include "plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stb/stb_easy_font.h>

namespace sonarsim::app {
namespace {

struct Canvas {
    Image8 img;
    Canvas(int w, int h) {
        img.width = w, img.height = h, img.channels = 3;
        img.pixels.assign(size_t(w) * h * 3, 255);
    }
    void px(int x, int y, std::array<std::uint8_t, 3> c) {
        if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
        std::copy(c.begin(), c.end(), img.pixels.begin() + (size_t(y) * img.width + x) * 3);
    }
    void rect(int x0, int y0, int x1, int y1, std::array<std::uint8_t, 3> c) {
        for (int y = std::min(y0, y1); y <= std::max(y0, y1); ++y)
            for (int x = std::min(x0, x1); x <= std::max(x0, x1); ++x) px(x, y, c);
    }
    void line(double x0, double y0, double x1, double y1, std::array<std::uint8_t, 3> c, int thick = 1) {
        const int n = int(std::max(std::abs(x1 - x0), std::abs(y1 - y0))) + 1;
        for (int i = 0; i <= n; ++i) {
            const double t = double(i) / n;
            const int x = int(std::lround(x0 + t * (x1 - x0))), y = int(std::lround(y0 + t * (y1 - y0)));
            rect(x - thick / 2, y - thick / 2, x + (thick - 1) / 2, y + (thick - 1) / 2, c);
        }
    }
    /// Text at (x, y) (top-left), scaled; stb_easy_font builds glyphs from quads.
    void text(int x, int y, const std::string& s, std::array<std::uint8_t, 3> c, int scale = 2) {
        static char buf[60000];
        std::string copy = s;
        const int quads = stb_easy_font_print(0, 0, copy.data(), nullptr, buf, sizeof(buf));
        for (int q = 0; q < quads; ++q) {
            const float* v = reinterpret_cast<const float*>(buf + q * 4 * 16);
            const float* w = reinterpret_cast<const float*>(buf + q * 4 * 16 + 2 * 16);
            rect(x + int(v[0] * scale), y + int(v[1] * scale), x + int(w[0] * scale) - 1,
                 y + int(w[1] * scale) - 1, c);
        }
    }
    static int text_width(const std::string& s, int scale = 2) {
        std::string copy = s;
        return stb_easy_font_width(copy.data()) * scale;
    }
};

std::string decade_label(int p) {
    if (p >= 0 && p <= 4) return std::to_string(int(std::lround(std::pow(10, p))));
    if (p < 0 && p >= -4) {
        std::string s = "0.";
        for (int i = 0; i < -p - 1; ++i) s += '0';
        return s + "1";
    }
    return "1e" + std::to_string(p);
}

/// A round tick step giving about `n` ticks over [lo, hi].
double tick_step(double lo, double hi, int n) {
    const double raw = (hi - lo) / n, p = std::pow(10, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0})
        if (m * p >= raw) return m * p;
    return 10 * p;
}

std::string tick_label(double v, double step) {
    char buf[32];
    std::snprintf(buf, sizeof buf,
                  step >= 1     ? "%.0f"
                  : step >= 0.1 ? "%.1f"
                                : "%.2f",
                  std::abs(v) < 1e-12 ? 0.0 : v);
    return buf;
}

/// The plot area's border, the title and the axis labels.
void draw_frame(Canvas& c, int L, int T, int R, int B, int H, const std::string& title, const std::string& xl,
                const std::string& yl) {
    const std::array<std::uint8_t, 3> black{0, 0, 0};
    c.line(L, B, R, B, black), c.line(L, T, L, B, black), c.line(R, T, R, B, black),
        c.line(L, T, R, T, black);
    c.text(L, 8, title, black);
    c.text((L + R) / 2 - Canvas::text_width(xl) / 2, H - 35, xl, black);
    c.text(10, T - 22, yl, black);
}

} // namespace

Image8 linear_plot(const std::vector<Series>& series, const std::string& title, const std::string& xl,
                   const std::string& yl, int W, int H) {
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    for (auto& s : series)
        for (auto& [x, y] : s.points)
            if (std::isfinite(x) && std::isfinite(y))
                xmin = std::min(xmin, x), xmax = std::max(xmax, x), ymin = std::min(ymin, y),
                ymax = std::max(ymax, y);
    if (!(xmin < INFINITY)) xmin = 0, xmax = 1, ymin = 0, ymax = 1;
    if (!(xmax > xmin)) xmax = xmin + 1;
    if (!(ymax > ymin)) ymin -= 0.5, ymax += 0.5;
    const double sx = tick_step(xmin, xmax, 8), sy = tick_step(ymin, ymax, 6);
    const double x0 = std::floor(xmin / sx) * sx, x1 = std::ceil(xmax / sx) * sx;
    const double y0 = std::floor(ymin / sy) * sy, y1 = std::ceil(ymax / sy) * sy;
    const int L = 110, R = W - 230, T = 56, B = H - 70;
    auto X = [&](double x) { return L + (x - x0) / (x1 - x0) * (R - L); };
    auto Y = [&](double y) { return B - (y - y0) / (y1 - y0) * (B - T); };
    Canvas c(W, H);
    const std::array<std::uint8_t, 3> black{0, 0, 0}, grid{225, 225, 225};
    for (double x = x0; x <= x1 + 1e-9 * sx; x += sx) {
        c.line(X(x), T, X(x), B, grid);
        const std::string s = tick_label(x, sx);
        c.text(int(X(x)) - Canvas::text_width(s) / 2, B + 10, s, black);
    }
    for (double y = y0; y <= y1 + 1e-9 * sy; y += sy) {
        c.line(L, Y(y), R, Y(y), grid);
        const std::string s = tick_label(y, sy);
        c.text(L - 10 - Canvas::text_width(s), int(Y(y)) - 6, s, black);
    }
    draw_frame(c, L, T, R, B, H, title, xl, yl);
    int ly = T + 10;
    for (auto& s : series) {
        for (size_t k = 0; k + 1 < s.points.size(); ++k) {
            const auto &p = s.points[k], &q = s.points[k + 1];
            if (std::isfinite(p.second) && std::isfinite(q.second))
                c.line(X(p.first), Y(p.second), X(q.first), Y(q.second), s.rgb, 2);
        }
        c.rect(R + 15, ly + 2, R + 35, ly + 10, s.rgb);
        c.text(R + 42, ly, s.name, black);
        ly += 24;
    }
    return c.img;
}

Image8 stack_vertically(const std::vector<Image8>& images) {
    Image8 out;
    for (const Image8& i : images) {
        out.width = std::max(out.width, i.width), out.channels = 3;
        out.height += i.height;
    }
    out.pixels.assign(size_t(out.width) * size_t(out.height) * 3, 255);
    int y0 = 0;
    for (const Image8& i : images) {
        for (int y = 0; y < i.height; ++y)
            std::copy(i.pixels.begin() + std::ptrdiff_t(size_t(y) * size_t(i.width) * 3),
                      i.pixels.begin() + std::ptrdiff_t(size_t(y + 1) * size_t(i.width) * 3),
                      out.pixels.begin() + std::ptrdiff_t(size_t(y0 + y) * size_t(out.width) * 3));
        y0 += i.height;
    }
    return out;
}

Image8 loglog_plot(const std::vector<Series>& series, const std::string& title, const std::string& xl,
                   const std::string& yl, int W, int H) {
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    for (auto& s : series)
        for (auto& [x, y] : s.points)
            if (x > 0 && y > 0)
                xmin = std::min(xmin, x), xmax = std::max(xmax, x), ymin = std::min(ymin, y),
                ymax = std::max(ymax, y);
    if (!(xmin < INFINITY)) xmin = 1, xmax = 10, ymin = 1, ymax = 10;
    const int px0 = int(std::floor(std::log10(xmin))),
              px1 = std::max(px0 + 1, int(std::ceil(std::log10(xmax))));
    const int py0 = int(std::floor(std::log10(ymin))),
              py1 = std::max(py0 + 1, int(std::ceil(std::log10(ymax))));
    const int L = 110, R = W - 230, T = 56, B = H - 70;
    auto X = [&](double x) { return L + (std::log10(x) - px0) / (px1 - px0) * (R - L); };
    auto Y = [&](double y) { return B - (std::log10(y) - py0) / (py1 - py0) * (B - T); };

    Canvas c(W, H);
    const std::array<std::uint8_t, 3> black{0, 0, 0}, grid{225, 225, 225};
    for (int p = px0; p <= px1; ++p) {
        c.line(X(std::pow(10, p)), T, X(std::pow(10, p)), B, grid);
        const std::string s = decade_label(p);
        c.text(int(X(std::pow(10, p))) - Canvas::text_width(s) / 2, B + 10, s, black);
    }
    for (int p = py0; p <= py1; ++p) {
        c.line(L, Y(std::pow(10, p)), R, Y(std::pow(10, p)), grid);
        const std::string s = decade_label(p);
        c.text(L - 10 - Canvas::text_width(s), int(Y(std::pow(10, p))) - 6, s, black);
    }
    draw_frame(c, L, T, R, B, H, title, xl, yl);
    int ly = T + 10;
    for (auto& s : series) {
        for (size_t k = 0; k + 1 < s.points.size(); ++k)
            c.line(X(s.points[k].first), Y(s.points[k].second), X(s.points[k + 1].first),
                   Y(s.points[k + 1].second), s.rgb, 2);
        for (auto& [x, y] : s.points)
            c.rect(int(X(x)) - 3, int(Y(y)) - 3, int(X(x)) + 3, int(Y(y)) + 3, s.rgb);
        c.rect(R + 15, ly + 2, R + 35, ly + 10, s.rgb);
        c.text(R + 42, ly, s.name, black);
        ly += 24;
    }
    return c.img;
}

} // namespace sonarsim::app
