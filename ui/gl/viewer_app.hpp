// The viewer application (internal to ui/): the window and frame loop (viewer.cpp), event handling and
// scene edits (viewer_input.cpp), menus and dialogs (menus.cpp), drawing helpers and snapshots
// (viewer_draw.cpp), and automation: --script, screenshots, state and layout export (automation.cpp).
#pragma once
#include "ui/gl/controls_panel.hpp"
#include "ui/gl/file_dialog.hpp"
#include "ui/model/frame_pacer.hpp"
#include "ui/gl/glfw_input.hpp"
#include "ui/model/orbit.hpp"
#include "ui/gl/scene_renderer.hpp"
#include "ui/model/script_player.hpp"
#include "ui/model/session.hpp"
#include "ui/model/snapshot.hpp"
#include "ui/gl/sonar_panel.hpp"
#include "ui/gl/trajectory_panel.hpp"
#include "ui/model/undo.hpp"
#include "ui/model/view_controller.hpp"
#include "ui/gl/viewer.hpp"
#include "ui/model/bindings.hpp"

#include "core/io/output.hpp"

#include <memory>
#include <string>
#include <vector>

struct GLFWwindow;

namespace sonarsim::ui {

class Viewer {
  public:
    explicit Viewer(const ViewerOptions& o);
    ~Viewer();
    Viewer(const Viewer&) = delete;
    Viewer& operator=(const Viewer&) = delete;
    int run();

  private:
    // viewer.cpp
    void frame(int index);
    void update_scale();
    void upload_meshes();
    void draw_gl(int fb_w, int fb_h, int win_w, int win_h);
    // viewer_input.cpp
    void handle_events();
    void handle_key(const InputEvent& e);
    void run_key_action(KeyAction action); ///< a key shortcut of the bindings table
    void apply_edit(const SceneDesc& next);
    void record_undo();
    void undo(bool redo);
    void open_files(const std::vector<std::string>& paths);
    /// sampling.bounces between 0 and its last non-zero value (one edit, so one undo step).
    void toggle_multipath();
    // menus.cpp
    void menu_bar();
    void help_window();
    void dialogs();
    void close_menus();
    // viewer_draw.cpp
    ViewOverlay overlay() const;
    void draw_view_text(const Rect& view);
    void take_snapshot(const std::string& prefix, bool as_shown = false, const Bytes& annotated = {});
    Bytes annotated_now(int fb_w, int fb_h, int win_w, int win_h) const;
    void take_pending_snapshots(bool full_on_screen, int fb_w, int fb_h, int win_w, int win_h);
    void reset_camera();
    void update_title();
    ViewContext view_context() const;
    // automation.cpp
    void script_actions(int index, int fb_w, int fb_h);
    void write_state(const std::string& path) const;
    void write_layout(const std::string& path, int win_w, int win_h) const;
    void write_screenshot(const std::string& path, int fb_w, int fb_h) const;
    void trajectory_snapshots(const std::string& prefix);

    ViewerOptions opt_;
    Orbiter orbiter_;
    GLFWwindow* window_ = nullptr;
    Session session_;
    std::unique_ptr<GlfwInput> input_;
    std::unique_ptr<SceneRenderer> renderer_;
    std::unique_ptr<SonarPanel> sonar_;
    ControlsUi ui_;
    ViewController controller_;
    UndoStack undo_;
    TrajectoryUi trajectory_;
    FileDialog open_dialog_, mesh_dialog_, save_dialog_, snapshot_dir_dialog_;
    std::uint64_t meshes_uploaded_ = 0;
    std::string title_file_ = "?";

    // Scale: monitor content scale x the user's UI scale; fonts rebuilt when it changes.
    float content_scale_ = 1, font_scale_ = 0;
    bool software_gl_ = false;
    ViewerLayout layout_;

    ScriptPlayer script_; ///< --script, --mouse, --drag; its last_frame: frames > 0 or the script's end

    bool interacting_ = false; ///< a drag that edits the scene (frustum, object, slider) is held
    bool show_help_ = false;
    int last_bounces_ = 1; ///< the last non-zero sampling.bounces: what the multipath toggle turns on
    SnapshotRequests snapshots_;

    FramePacer pacer_; ///< when frames draw, their times, the --orbit statistics
    bool quit_ = false;
};

} // namespace sonarsim::ui
