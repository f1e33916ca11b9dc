// The display's and the exports' rows of the parameter table: the image's display range and colour map,
// the 8-bit exports' byte mapping and the dataset's start time.
#include "core/scene/param_rows.hpp"

namespace sonarsim::rows {

std::vector<ParamSpec> display_rows() {
    std::vector<ParamSpec> t;
    t.push_back(number("display.lo_db", "dB", -1000, 1000, false, false, Stage::Display,
                       "L_EN shown as black", [](S s) -> double& { return s.display.lo_db; })
                    .preset()
                    .with_label("lo (black)")
                    .with_slider(-50, 200));
    t.push_back(number("display.hi_db", "dB", -1000, 1000, false, false, Stage::Display,
                       "L_EN shown as white", [](S s) -> double& { return s.display.hi_db; })
                    .preset()
                    .with_label("hi (white)")
                    .with_slider(-50, 250));
    t.push_back(enumeration<Colormap>("display.colormap", {"gray", "viridis", "copper", "hot"},
                                      Stage::Display, "Colour map of the image (copper: ARIS-like)",
                                      [](S s) -> Colormap& { return s.display.colormap; })
                    .preset());
    t.push_back(boolean("display.auto", Stage::Display,
                        "Display range from the image itself: white at its 99.5th percentile (finite "
                        "levels), black at its 5th but at most 50 dB below white; instead of lo_db, hi_db",
                        [](S s) -> bool& { return s.display.auto_range; })
                    .sensor_values(nullptr, true)
                    .preset());
    return t;
}

std::vector<ParamSpec> export_rows() {
    std::vector<ParamSpec> t;
    t.push_back(boolean("export.auto", Stage::None,
                        "8-bit exports (.aris, MCAP uint8): byte 255 at the 99.5th percentile of the "
                        "exported frames' finite levels, byte 0 80 dB below (ARIS's 80 dB over 255 steps), "
                        "one mapping for all frames; instead of export.lo_db, export.hi_db",
                        [](S s) -> bool& { return s.exports.auto_range; }));
    t.push_back(number("export.lo_db", "dB", -1000, 1000, false, false, Stage::None,
                       "8-bit exports without export.auto: the image level written as byte 0 (and below)",
                       [](S s) -> double& { return s.exports.lo_db; }));
    t.push_back(number("export.hi_db", "dB", -1000, 1000, false, false, Stage::None,
                       "8-bit exports without export.auto: the image level written as byte 255 (and above)",
                       [](S s) -> double& { return s.exports.hi_db; }));
    t.push_back(
        number("export.start_time_s", "s", 0, 4102444800, false, false, Stage::None,
               "UNIX time of the dataset's t = 0 in exports (ARIS FrameTime, MCAP stamps = start + t); 0: "
               "the dataset's, kept in DIR/dataset.json when batch first prepared it (this value then, "
               "else 2026-01-01 00:00:00 UTC = 1767225600, or the wall clock with batch --start-now)",
               [](S s) -> double& { return s.exports.start_time_s; }));
    return t;
}

} // namespace sonarsim::rows
