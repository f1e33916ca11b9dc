// The viewer's event path: GLFW callbacks that queue every mouse and key event in order (then pass it on to
// Dear ImGui's backend), and the same entry points for --script, so scripted input takes the real path.
#pragma once
#include "ui/model/input_events.hpp"

#include <string>
#include <vector>

struct GLFWwindow;

namespace sonarsim::ui {

class GlfwInput {
  public:
    /// Installs the callbacks on `window` after ImGui_ImplGlfw_InitForOpenGL(window, true) installed its
    /// own: ours run first and forward to ImGui's.
    explicit GlfwInput(GLFWwindow* window);
    ~GlfwInput();
    GlfwInput(const GlfwInput&) = delete;
    GlfwInput& operator=(const GlfwInput&) = delete;

    /// Delivers an event as GLFW would: through the installed callbacks (used by --script).
    void inject(const InputEvent& e);
    /// Call after ImGui_ImplGlfw_NewFrame(): ImGui's mouse comes from the event stream (a press and release
    /// inside one frame still reads as held for that frame), not from polled state.
    void feed_imgui();
    /// The events since the last call, in order.
    std::vector<InputEvent> take_events();
    const MouseState& mouse() const { return mouse_; }
    /// A left double click happened since the frame before this one (kDoubleClickS, kDoubleClickPx).
    bool double_clicked() const { return double_clicked_; }
    /// `key` went down (not a repeat) since the frame before this one: from the event stream, so a tap
    /// shorter than a frame counts.
    bool key_pressed(int key) const;
    std::vector<std::string> take_dropped();

  private:
    static void on_cursor(GLFWwindow* w, double x, double y);
    static void on_button(GLFWwindow* w, int button, int action, int mods);
    static void on_scroll(GLFWwindow* w, double dx, double dy);
    static void on_key(GLFWwindow* w, int key, int scancode, int action, int mods);
    static void on_enter(GLFWwindow* w, int entered);
    static void on_drop(GLFWwindow* w, int count, const char** paths);
    void push(InputEvent e);

    GLFWwindow* window_;
    MouseState mouse_;
    bool double_clicked_ = false;
    std::vector<int> keys_pressed_; ///< this frame's key presses
    std::vector<InputEvent> events_;
    std::vector<std::string> dropped_;
    // ImGui's callbacks, forwarded to.
    void (*imgui_button_)(GLFWwindow*, int, int, int) = nullptr;
    void (*imgui_scroll_)(GLFWwindow*, double, double) = nullptr;
    void (*imgui_key_)(GLFWwindow*, int, int, int, int) = nullptr;
    void (*imgui_enter_)(GLFWwindow*, int) = nullptr;
    void (*imgui_cursor_)(GLFWwindow*, double, double) = nullptr;
};

} // namespace sonarsim::ui
