// Text placement checks for any window size, GL-free: the viewer exports where every piece of text landed
// (glyph boxes grouped into runs, from ImGui's draw data) and these functions find runs that overlap or are
// cut off by their clip rectangle. Used by `sonarsim view --layout FILE.json` and tests/ui.
#pragma once
#include "ui/model/layout.hpp"
#include "ui/model/panel_layout.hpp"

#include <optional>

#include <string>
#include <vector>

namespace sonarsim::ui {

/// One glyph as drawn: its box [window px], its clip rectangle, and which draw list (window) drew it.
struct Glyph {
    Rect box, clip;
    int list = 0;
};

/// A run of glyphs on one line of one draw list.
struct TextRun {
    Rect box; ///< visible part (inside the clip rectangle)
    int list = 0;
    std::string list_name; ///< ImGui window of the draw list (for messages)
    bool cut_x = false;    ///< some glyph is partly cut off left or right by its clip rectangle
    int glyphs = 0;
};

/// Groups glyphs into runs: same list, same line (top and bottom within 1 px), gaps below one line height.
/// Glyphs wholly outside their clip rectangle are not visible and are dropped.
std::vector<TextRun> text_runs(const std::vector<Glyph>& glyphs);

/// True for tooltips, popups, menus and combo lists: drawn over the panels on purpose.
bool floats_on_top(const std::string& list_name);

/// Pairs of runs (indices) whose visible boxes overlap (a floating window's text over a panel's is not an
/// overlap) by more than `min_px` in both directions.
std::vector<std::pair<size_t, size_t>> overlapping_runs(const std::vector<TextRun>& runs,
                                                        float min_px = 1.0f);

/// A region text must keep off (the sonar image, the colour bar): a rectangle, or (`fan`) the fan's
/// annular sector inside it.
struct KeepOut {
    std::string name;
    Rect rect;
    std::optional<FanOnScreen> fan;
};
/// True when the run's box covers part of the region (more than `min_px` of the rectangle, or any of a grid
/// of points over the box, inset by `min_px`, inside the fan).
bool covers(const TextRun& run, const KeepOut& region, float min_px = 1.0f);

/// Problems as text, one per line: overlaps, runs cut off sideways, runs outside the window, runs over a
/// keep-out region (floating windows, tooltips and popups, are drawn over everything on purpose). Empty =
/// good.
std::string layout_problems(const std::vector<TextRun>& runs, float window_w, float window_h,
                            const std::vector<KeepOut>& keep_out = {});

} // namespace sonarsim::ui
