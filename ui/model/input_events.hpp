// GL-free input events of the viewer: what GLFW's callbacks deliver (and what a --script replays through the
// same callbacks), queued in order so that presses and releases inside one frame are never lost.
#pragma once
#include <glm/glm.hpp>
#include <vector>

namespace sonarsim::ui {

/// Key codes and modifier bits: the values GLFW uses (kept here so that non-GL code can name them).
namespace key {
constexpr int Space = 32, A = 65, B = 66, F = 70, H = 72, M = 77, O = 79, P = 80, Q = 81, R = 82, S = 83,
              T = 84, Y = 89, Z = 90, Escape = 256, Enter = 257, Delete = 261, Down = 264, Up = 265,
              KeypadEnter = 335, LeftShift = 340, LeftControl = 341, LeftAlt = 342, RightShift = 344,
              RightControl = 345, RightAlt = 346;
} // namespace key
namespace mods {
constexpr int Shift = 1, Control = 2, Alt = 4;
}
namespace button {
constexpr int Left = 0, Right = 1, Middle = 2;
}

struct InputEvent {
    enum class Type { Move, Press, Release, Wheel, Key } type = Type::Move;
    glm::dvec2 pos{0};    ///< mouse position at the event [window px]
    int button = 0;       ///< Press / Release
    int key = 0;          ///< Key: GLFW key code
    bool key_down = true; ///< Key: pressed (true) or released
    bool repeat = false;  ///< Key: auto-repeat of a held key
    int mods = 0;         ///< modifier bits held (mods::)
    double wheel = 0;     ///< Wheel: steps (positive away from the user)
    double time_s = 0;    ///< Press: when it happened [s] (any monotonic clock)
};

/// Two left presses at most this far apart in time [s] and space [px] are a double click.
constexpr double kDoubleClickS = 0.4, kDoubleClickPx = 6.0;

/// The mouse state assembled from events: position, buttons held, and presses seen since the last frame (so
/// that a click shorter than a frame still counts as held for one frame).
struct MouseState {
    glm::dvec2 pos{-1e9};
    bool down[3] = {false, false, false};
    bool pressed_since_frame[3] = {false, false, false};
    /// A left press completed a double click since the last frame (from the events' times, so a double
    /// click stays one even when both clicks fall into one slow frame).
    bool double_clicked_since_frame = false;
    int mods = 0;
    void apply(const InputEvent& e);
    /// Held this frame for ImGui: held now or pressed since the last frame.
    bool held_for_frame(int b) const { return down[b] || pressed_since_frame[b]; }
    void next_frame() {
        pressed_since_frame[0] = pressed_since_frame[1] = pressed_since_frame[2] = false;
        double_clicked_since_frame = false;
    }

  private:
    double last_left_press_s_ = -1e9;
    glm::dvec2 last_left_press_pos_{-1e9};
};

inline void MouseState::apply(const InputEvent& e) {
    pos = e.pos;
    if (e.type == InputEvent::Type::Key) mods = e.mods;
    if (e.button < 0 || e.button > 2) return;
    if (e.type == InputEvent::Type::Press) down[e.button] = true, pressed_since_frame[e.button] = true;
    if (e.type == InputEvent::Type::Release) down[e.button] = false;
    if (e.type == InputEvent::Type::Press && e.button == 0) {
        if (e.time_s - last_left_press_s_ <= kDoubleClickS &&
            glm::length(e.pos - last_left_press_pos_) <= kDoubleClickPx) {
            double_clicked_since_frame = true;
            last_left_press_s_ = -1e9; // a third press starts anew
        } else {
            last_left_press_s_ = e.time_s, last_left_press_pos_ = e.pos;
        }
    }
}

} // namespace sonarsim::ui
