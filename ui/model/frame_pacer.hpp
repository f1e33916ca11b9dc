// The viewer's frame pacing and timings: when the loop draws at once and when it sleeps until input or an
// image arrives, how long each frame took, and which images went into the --orbit statistics.
#pragma once
#include "ui/model/orbit.hpp"
#include "ui/model/render_worker.hpp"

#include <chrono>
#include <cstdint>

namespace sonarsim::ui {

class FramePacer {
  public:
    /// Frames drawn after input, a new image or a held drag before the loop may sleep: enough for ImGui to
    /// settle (hover states, a window that appears one frame after its button).
    static constexpr int kSettleFrames = 2;

    /// Whether this frame polls for events and draws at once (`continuous`: a script, --orbit or a playing
    /// trajectory; or frames still owed) rather than waiting for input first. Spends one owed frame; a
    /// frame that waited owes kSettleFrames after it.
    bool poll_now(bool continuous);
    /// The next kSettleFrames frames draw at once (an image was requested, a drag is held, a snapshot
    /// waits for the full-quality image).
    void keep_drawing() { owed_ = kSettleFrames; }
    int owed_frames() const { return owed_; }

    /// Marks the start and the end of a frame's work; the end records the frame's time.
    void begin_frame() { t0_ = Clock::now(); }
    void end_frame();
    double last_frame_ms() const { return last_frame_ms_; }

    /// The image on screen after this frame's poll, numbered by the session's shown_count: a new one's time
    /// (and estimate against the screen's precision) goes into stats() when `record` (--orbit leaves out
    /// frame 0's, which includes start-up). Counted once however many frames show it.
    void count_image(std::uint64_t shown_count, const RenderResult& shown, bool record);

    FrameStats& stats() { return stats_; }
    const FrameStats& stats() const { return stats_; }

  private:
    using Clock = std::chrono::steady_clock;
    Clock::time_point t0_ = Clock::now();
    double last_frame_ms_ = 0;
    int owed_ = 0;
    std::uint64_t counted_ = 0;
    FrameStats stats_;
};

} // namespace sonarsim::ui
