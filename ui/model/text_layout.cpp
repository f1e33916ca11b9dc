#include "ui/model/text_layout.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sonarsim::ui {
namespace {
Rect intersect(const Rect& a, const Rect& b) {
    const float x0 = std::max(a.x, b.x), y0 = std::max(a.y, b.y);
    const float x1 = std::min(a.x + a.w, b.x + b.w), y1 = std::min(a.y + a.h, b.y + b.h);
    return {x0, y0, std::max(0.0f, x1 - x0), std::max(0.0f, y1 - y0)};
}
Rect unite(const Rect& a, const Rect& b) {
    const float x0 = std::min(a.x, b.x), y0 = std::min(a.y, b.y);
    const float x1 = std::max(a.x + a.w, b.x + b.w), y1 = std::max(a.y + a.h, b.y + b.h);
    return {x0, y0, x1 - x0, y1 - y0};
}
} // namespace

std::vector<TextRun> text_runs(const std::vector<Glyph>& glyphs) {
    std::vector<TextRun> runs;
    for (const Glyph& g : glyphs) {
        const Rect vis = intersect(g.box, g.clip);
        if (vis.w <= 0 || vis.h <= 0) continue;
        const bool cut_x = vis.w + 0.5f < g.box.w;
        bool merged = false;
        for (auto it = runs.rbegin(); it != runs.rend() && !merged; ++it) {
            TextRun& r = *it;
            if (r.list != g.list) continue;
            const float line_h = std::max(r.box.h, vis.h);
            const bool same_line = std::abs(r.box.y - vis.y) <= line_h * 0.6f &&
                                   std::abs((r.box.y + r.box.h) - (vis.y + vis.h)) <= line_h * 0.6f;
            const float gap = std::max(vis.x - (r.box.x + r.box.w), r.box.x - (vis.x + vis.w));
            if (same_line && gap < 0.5f * line_h) {
                r.box = unite(r.box, vis);
                r.cut_x |= cut_x;
                ++r.glyphs;
                merged = true;
            }
        }
        if (!merged) runs.push_back({vis, g.list, "", cut_x, 1});
    }
    return runs;
}

bool floats_on_top(const std::string& list_name) {
    for (const char* prefix : {"##Tooltip", "##Popup", "##Menu_", "##Combo"})
        if (list_name.rfind(prefix, 0) == 0) return true;
    return false;
}

std::vector<std::pair<size_t, size_t>> overlapping_runs(const std::vector<TextRun>& runs, float min_px) {
    std::vector<std::pair<size_t, size_t>> out;
    for (size_t i = 0; i < runs.size(); ++i)
        for (size_t j = i + 1; j < runs.size(); ++j) {
            if (floats_on_top(runs[i].list_name) != floats_on_top(runs[j].list_name)) continue;
            const Rect o = intersect(runs[i].box, runs[j].box);
            if (o.w > min_px && o.h > min_px) out.emplace_back(i, j);
        }
    return out;
}

bool covers(const TextRun& run, const KeepOut& k, float min_px) {
    const Rect o = intersect(run.box, k.rect);
    if (o.w <= min_px || o.h <= min_px) return false;
    if (!k.fan) return true;
    const Rect b{run.box.x + min_px, run.box.y + min_px, run.box.w - 2 * min_px, run.box.h - 2 * min_px};
    for (int i = 0; i <= 8; ++i)
        for (int j = 0; j <= 3; ++j)
            if (k.fan->contains(b.x + b.w * float(i) / 8, b.y + b.h * float(j) / 3)) return true;
    return false;
}

std::string layout_problems(const std::vector<TextRun>& runs, float ww, float wh,
                            const std::vector<KeepOut>& keep_out) {
    std::string out;
    char buf[512];
    auto describe = [&](const TextRun& r) {
        std::snprintf(buf, sizeof buf, "%s [%.0f,%.0f %.0fx%.0f]", r.list_name.c_str(), double(r.box.x),
                      double(r.box.y), double(r.box.w), double(r.box.h));
        return std::string(buf);
    };
    for (auto [i, j] : overlapping_runs(runs))
        out += "overlap: " + describe(runs[i]) + " and " + describe(runs[j]) + "\n";
    for (const TextRun& r : runs) {
        if (!floats_on_top(r.list_name))
            for (const KeepOut& k : keep_out)
                if (covers(r, k)) out += "over the " + k.name + ": " + describe(r) + "\n";
        if (r.cut_x) out += "cut off: " + describe(r) + "\n";
        if (r.box.x < 0 || r.box.y < 0 || r.box.x + r.box.w > ww + 0.5f || r.box.y + r.box.h > wh + 0.5f)
            out += "outside the window: " + describe(r) + "\n";
    }
    return out;
}

} // namespace sonarsim::ui
