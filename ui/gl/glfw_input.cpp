#include <epoxy/gl.h>
#include <GLFW/glfw3.h>

#include "ui/gl/glfw_input.hpp"

#include <algorithm>

#include <imgui.h>

namespace sonarsim::ui {
namespace {
GlfwInput* self(GLFWwindow* w) {
    return static_cast<GlfwInput*>(glfwGetWindowUserPointer(w));
}
int mods_of(int glfw_mods) {
    return (glfw_mods & GLFW_MOD_SHIFT ? mods::Shift : 0) |
           (glfw_mods & GLFW_MOD_CONTROL ? mods::Control : 0) | (glfw_mods & GLFW_MOD_ALT ? mods::Alt : 0);
}
int glfw_mods_of(int m) {
    return (m & mods::Shift ? GLFW_MOD_SHIFT : 0) | (m & mods::Control ? GLFW_MOD_CONTROL : 0) |
           (m & mods::Alt ? GLFW_MOD_ALT : 0);
}
} // namespace

GlfwInput::GlfwInput(GLFWwindow* window) : window_(window) {
    glfwSetWindowUserPointer(window, this);
    imgui_cursor_ = glfwSetCursorPosCallback(window, on_cursor);
    imgui_button_ = glfwSetMouseButtonCallback(window, on_button);
    imgui_scroll_ = glfwSetScrollCallback(window, on_scroll);
    imgui_key_ = glfwSetKeyCallback(window, on_key);
    imgui_enter_ = glfwSetCursorEnterCallback(window, on_enter);
    glfwSetDropCallback(window, on_drop);
    double x = 0, y = 0;
    glfwGetCursorPos(window, &x, &y);
    mouse_.pos = {x, y};
}

GlfwInput::~GlfwInput() {
    glfwSetCursorPosCallback(window_, imgui_cursor_);
    glfwSetMouseButtonCallback(window_, imgui_button_);
    glfwSetScrollCallback(window_, imgui_scroll_);
    glfwSetKeyCallback(window_, imgui_key_);
    glfwSetCursorEnterCallback(window_, imgui_enter_);
    glfwSetDropCallback(window_, nullptr);
    glfwSetWindowUserPointer(window_, nullptr);
}

void GlfwInput::push(InputEvent e) {
    mouse_.apply(e);
    events_.push_back(e);
}

void GlfwInput::on_cursor(GLFWwindow* w, double x, double y) {
    GlfwInput* in = self(w);
    if (!in) return;
    InputEvent e;
    e.type = InputEvent::Type::Move;
    e.pos = {x, y};
    e.mods = in->mouse_.mods;
    in->push(e);
    if (in->imgui_cursor_) in->imgui_cursor_(w, x, y);
}

void GlfwInput::on_button(GLFWwindow* w, int b, int action, int m) {
    GlfwInput* in = self(w);
    if (!in) return;
    InputEvent e;
    e.type = action == GLFW_PRESS ? InputEvent::Type::Press : InputEvent::Type::Release;
    e.button = b;
    e.time_s = glfwGetTime();
    e.pos = in->mouse_.pos;
    e.mods = mods_of(m);
    in->push(e);
    if (in->imgui_button_) in->imgui_button_(w, b, action, m);
}

void GlfwInput::on_scroll(GLFWwindow* w, double dx, double dy) {
    GlfwInput* in = self(w);
    if (!in) return;
    InputEvent e;
    e.type = InputEvent::Type::Wheel;
    e.pos = in->mouse_.pos;
    e.wheel = dy;
    e.mods = in->mouse_.mods;
    in->push(e);
    if (in->imgui_scroll_) in->imgui_scroll_(w, dx, dy);
}

void GlfwInput::on_key(GLFWwindow* w, int k, int scancode, int action, int m) {
    GlfwInput* in = self(w);
    if (!in) return;
    InputEvent e;
    e.type = InputEvent::Type::Key;
    e.key = k;
    e.key_down = action != GLFW_RELEASE;
    e.repeat = action == GLFW_REPEAT;
    e.pos = in->mouse_.pos;
    e.mods = mods_of(m);
    // GLFW reports the modifiers held before this event: keep the held set current for mouse events.
    int held = e.mods;
    const int bit = (k == GLFW_KEY_LEFT_SHIFT || k == GLFW_KEY_RIGHT_SHIFT)       ? mods::Shift
                    : (k == GLFW_KEY_LEFT_CONTROL || k == GLFW_KEY_RIGHT_CONTROL) ? mods::Control
                    : (k == GLFW_KEY_LEFT_ALT || k == GLFW_KEY_RIGHT_ALT)         ? mods::Alt
                                                                                  : 0;
    held = e.key_down ? (held | bit) : (held & ~bit);
    in->push(e);
    in->mouse_.mods = held;
    if (in->imgui_key_) in->imgui_key_(w, k, scancode, action, m);
}

void GlfwInput::on_enter(GLFWwindow* w, int entered) {
    GlfwInput* in = self(w);
    if (!in) return;
    if (!entered && !in->mouse_.down[0] && !in->mouse_.down[1] && !in->mouse_.down[2])
        in->mouse_.pos = glm::dvec2(-1e9); // no hover outside the window
    if (in->imgui_enter_) in->imgui_enter_(w, entered);
}

void GlfwInput::on_drop(GLFWwindow* w, int count, const char** paths) {
    GlfwInput* in = self(w);
    if (!in) return;
    for (int i = 0; i < count; ++i) in->dropped_.push_back(paths[i]);
}

void GlfwInput::inject(const InputEvent& e) {
    switch (e.type) {
    case InputEvent::Type::Move:
        on_cursor(window_, e.pos.x, e.pos.y);
        break;
    case InputEvent::Type::Press:
    case InputEvent::Type::Release:
        if (e.pos != mouse_.pos) on_cursor(window_, e.pos.x, e.pos.y);
        on_button(window_, e.button, e.type == InputEvent::Type::Press ? GLFW_PRESS : GLFW_RELEASE,
                  glfw_mods_of(e.mods));
        break;
    case InputEvent::Type::Wheel:
        on_scroll(window_, 0, e.wheel);
        break;
    case InputEvent::Type::Key:
        on_key(window_, e.key, glfwGetKeyScancode(e.key), e.key_down ? GLFW_PRESS : GLFW_RELEASE,
               glfw_mods_of(e.mods));
        break;
    }
}

void GlfwInput::feed_imgui() {
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = ImVec2(float(mouse_.pos.x), float(mouse_.pos.y));
    for (int b = 0; b < 3; ++b) io.MouseDown[b] = mouse_.held_for_frame(b);
    double_clicked_ = mouse_.double_clicked_since_frame;
    keys_pressed_.clear();
    for (const InputEvent& e : events_) // this frame's (handle_events takes them after the panels)
        if (e.type == InputEvent::Type::Key && e.key_down && !e.repeat) keys_pressed_.push_back(e.key);
    mouse_.next_frame();
}

bool GlfwInput::key_pressed(int key) const {
    return std::find(keys_pressed_.begin(), keys_pressed_.end(), key) != keys_pressed_.end();
}

std::vector<InputEvent> GlfwInput::take_events() {
    std::vector<InputEvent> out;
    out.swap(events_);
    return out;
}

std::vector<std::string> GlfwInput::take_dropped() {
    std::vector<std::string> out;
    out.swap(dropped_);
    return out;
}

} // namespace sonarsim::ui
