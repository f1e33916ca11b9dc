#include "ui/model/frame_pacer.hpp"

#include "core/base/timing.hpp"
#include "core/display/display_range.hpp"

#include <algorithm>

namespace sonarsim::ui {

bool FramePacer::poll_now(bool continuous) {
    if (continuous || owed_ > 0) {
        owed_ = std::max(0, owed_ - 1);
        return true;
    }
    owed_ = kSettleFrames;
    return false;
}

void FramePacer::end_frame() {
    last_frame_ms_ = ms_since(t0_);
    stats_.frame_ms.push_back(last_frame_ms_);
}

void FramePacer::count_image(std::uint64_t shown_count, const RenderResult& shown, bool record) {
    if (shown_count == counted_) return;
    counted_ = shown_count;
    if (!record) return;
    stats_.image_ms.push_back(shown.wall_ms);
    if (shown.frame && shown.frame->error_estimate.valid) {
        stats_.estimate_median_db.push_back(shown.frame->error_estimate.median_abs_db);
        stats_.screen_median_db.push_back(half_grey_level_db(shown.frame->display));
    }
}

} // namespace sonarsim::ui
