// `sonarsim view` (and `sonarsim` with no arguments): the interactive viewer of ui/.
#include "commands.hpp"
#include "load.hpp"

#include "core/scene/scene_io.hpp"

#include <iostream>
#include <memory>

#ifdef SONARSIM_HAVE_VIEWER
#include "ui/gl/viewer.hpp"
#endif

namespace sonarsim::app {
namespace {

struct ViewOptions {
    SceneOptions scene;
    int frames = 0;
    std::string screenshot;
    bool orbit = false, orbit_pipelined = false, orbit_preview = false;
    int width = 1280, height = 800;
    std::string snapshot;
    std::vector<double> mouse, drag;
    std::string script, state, layout;
    float ui_scale = 1.0f;
};

int run_view(const ViewOptions& o) {
#ifdef SONARSIM_HAVE_VIEWER
    ui::ViewerOptions v;
    v.scene = load_scene_from_options(o.scene);
    v.frames = o.frames;
    v.screenshot = o.screenshot;
    v.orbit = o.orbit || o.orbit_preview;
    v.orbit_preview = o.orbit_preview;
    v.orbit_pipelined = o.orbit_pipelined;
    v.width = o.width;
    v.height = o.height;
    v.snapshot = o.snapshot;
    v.script = o.script;
    v.state = o.state;
    v.layout = o.layout;
    v.ui_scale = o.ui_scale;
    if (o.mouse.size() == 2) v.mouse = glm::dvec2(o.mouse[0], o.mouse[1]);
    if (o.drag.size() == 4)
        v.drag =
            std::array<glm::dvec2, 2>{glm::dvec2(o.drag[0], o.drag[1]), glm::dvec2(o.drag[2], o.drag[3])};
    return ui::run_viewer(v);
#else
    (void)o;
    std::cerr << "sonarsim: built without the viewer (SONARSIM_BUILD_VIEWER=OFF); use `sonarsim render`\n";
    return 1;
#endif
}

} // namespace

void register_view(CLI::App& app, std::function<int()>& run) {
    auto o = std::make_shared<ViewOptions>();
    CLI::App* cmd = app.add_subcommand("view", "Open the interactive viewer (3D scene + live sonar image)");
    add_scene_options(*cmd, o->scene);
    cmd->add_option("--frames", o->frames, "Draw N frames, then exit (each frame waits for its image)")
        ->check(CLI::Range(1, 1000000));
    cmd->add_option("--screenshot", o->screenshot, "After the last frame, save the whole window as a PNG");
    cmd->add_flag(
        "--orbit", o->orbit,
        "Move the sonar every frame (forces a retrace) and show each frame with its new image; print frame "
        "timings as JSON at exit");
    cmd->add_flag("--orbit-preview", o->orbit_preview,
                  "As --orbit, but request each pose as a drag does: the adaptive sampler's base grid only "
                  "(the preview shown while dragging)");
    cmd->add_flag(
        "--orbit-pipelined", o->orbit_pipelined,
        "With --orbit: show the previous pose's image while the next one is traced (default: every frame "
        "waits for the image of its own pose)");
    cmd->add_option("--snapshot", o->snapshot,
                    "After the last frame, write a snapshot to this prefix (as the S key does): PREFIX.png, "
                    "_polar.png, .npy, .json, _3d.png, _scene.json");
    cmd->add_option("--mouse", o->mouse, "Hold the mouse at window pixel X Y (hover feedback in screenshots)")
        ->expected(2);
    cmd->add_option(
           "--drag", o->drag,
           "Script a left-button drag from window pixel X0 Y0 to X1 Y1 over the frames (tests, demos)")
        ->expected(4);
    cmd->add_option("--script", o->script,
                    "Replay timed mouse and key events (and actions) from FILE through the window's event "
                    "callbacks; runs until the script's last frame (see ui/model/script.hpp for the format)");
    cmd->add_option(
        "--state", o->state,
        "After the last frame, write the camera, pose, objects, selection, snapshot count and undo "
        "depth as JSON");
    cmd->add_option(
        "--layout", o->layout,
        "After the last frame, write every text run on screen as JSON with overlapping or cut-off "
        "text listed under \"problems\"");
    cmd->add_option("--ui-scale", o->ui_scale,
                    "UI scale (fonts and widgets), times the monitor's content scale (HiDPI)")
        ->check(CLI::Range(0.75, 2.5));
    cmd->add_option("--width", o->width, "Window width [px]")->check(CLI::Range(640, 8192));
    cmd->add_option("--height", o->height, "Window height [px]")->check(CLI::Range(480, 8192));
    cmd->callback([o, &run] { run = [o] { return run_view(*o); }; });
}

int run_default_view() {
    return run_view(ViewOptions{});
}

} // namespace sonarsim::app
