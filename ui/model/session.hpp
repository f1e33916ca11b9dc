// Non-GL state of a viewer session: the scene being edited, the last good scene and frame, the render worker,
// errors, file operations and snapshots. A bad file or value leaves the last good scene and image in place
// and sets error().
#pragma once
#include "ui/model/render_worker.hpp"

#include "core/geometry/geometry.hpp"
#include "core/geometry/mesh.hpp"
#include "core/io/output.hpp"
#include "core/data/trajectory.hpp"
#include "core/kinds/pings.hpp"
#include "core/scene/params.hpp"

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sonarsim::ui {

class Session {
  public:
    /// Starts the worker on `scene` (already validated). Throws InputError when a mesh cannot be loaded.
    explicit Session(const SceneDesc& scene);

    /// The scene as edited (what was last requested).
    const SceneDesc& scene() const { return scene_; }
    /// The traceable geometry of scene() (for picking), its objects' meshes in their own coordinates (for
    /// drawing, placed by each object's transform) and a counter that changes when the meshes do (not when
    /// objects only move: that updates the geometry in place).
    const SceneGeometry& geometry() const { return *geometry_; }
    std::vector<std::shared_ptr<const TriMesh>> local_meshes() const;
    std::uint64_t meshes_version() const { return meshes_version_; }

    /// Applies a change to a copy of the scene and validates it. On InputError: the scene stays, error() is
    /// set, and false is returned. Returns true when accepted (whether or not anything changed).
    bool edit(const std::function<void(SceneDesc&)>& change);
    /// `key = value` through core's parameter table (apply_setting), then edit().
    bool set(const std::string& key, const json& value);
    /// Resets every non-pose parameter and all materials to the paper's values.
    bool reset_to_paper();

    bool open_scene(const std::string& path);
    /// Adds a mesh file (OBJ/PLY/STL/OFF) as an object placed on the floor in front of the sonar.
    bool add_mesh(const std::string& path);
    /// Writes the edited scene as a scene file (atomically).
    bool save_scene(const std::string& path);

    using Clock = std::chrono::steady_clock;
    /// How long the input must rest before a drag's previews are followed by the full-quality image.
    static constexpr std::chrono::milliseconds kRest{150};
    /// Sends the scene to the worker if it changed since the last request. `interacting` (a drag or a slider
    /// is held): the change goes as a preview (TraceControl::preview); the full-quality image of the same
    /// scene follows once the input is released or has not changed for kRest. Returns the request id (0:
    /// none).
    std::uint64_t submit(bool interacting = false, Clock::time_point now = Clock::now());
    /// True while a preview was requested and its full-quality image not yet.
    bool full_pending() const { return full_pending_; }
    /// Takes a finished result from the worker. Returns true when the shown frame changed.
    bool poll();
    /// Waits for the newest request to finish, then polls. False on timeout.
    bool wait_latest(std::chrono::milliseconds timeout);
    /// Requests the full-quality image of the edited scene if it is not on its way, and waits for it.
    bool wait_full(std::chrono::milliseconds timeout);
    /// True while the worker has work queued or running, or the scene changed since the last request.
    bool busy() const;
    /// Called on the worker thread whenever a result is ready.
    void set_notify(std::function<void()> notify) { worker_.set_notify(std::move(notify)); }

    /// The frame on screen and the scene it was made from (null until the first image arrives);
    /// shown()->frame->preview() while it is a drag's preview.
    const RenderResult* shown() const { return shown_ ? shown_.get() : nullptr; }
    std::uint64_t shown_count() const { return shown_count_; }

    const std::string& error() const { return error_; }
    void set_error(const std::string& e) { error_ = e; }
    void clear_error() { error_.clear(); }
    const std::string& status() const { return status_; }
    void set_status(const std::string& s) { status_ = s; }

    /// Writes the sonar files of the shown frame, the 3D view PNG, the annotated panel PNG (when not empty)
    /// and the scene file in one step (see snapshot.hpp), and lists every file in status(); a preview on
    /// screen is first replaced by the full-quality image (wait_full).
    /// Returns false (and sets error()) when there is nothing to save or writing fails.
    bool snapshot(const std::string& prefix, const Bytes& view3d_png, const Bytes& annotated_png = {});
    /// The image on screen keeps rays placed for an earlier shading (a slider that steers the sampler), so
    /// it differs from what `render` makes of its scene.
    bool shown_kept_placement() const;
    /// Requests the shown scene's image with its rays placed anew, once per kept image on screen (a
    /// snapshot's annotated PNG is read back from the screen, so it waits for that image to be drawn).
    /// Returns whether such an image is on its way: false when nothing is kept, when a newer edit's image
    /// comes next, or when the one asked for has finished and the kept image is still on screen (an error).
    bool place_anew();
    /// The id of the newest request sent to the worker (0: none yet).
    std::uint64_t requested_id() const { return requested_id_; }
    /// Ground truth per pixel for full-quality frames (computed by the worker): shown by the hover readout
    /// and written by snapshots as PREFIX_gt_<name>.npy. Turning it on re-requests the shown scene.
    void set_ground_truth(bool on);
    bool ground_truth() const { return ground_truth_; }
    /// Height of the fan the worker forms [px] (Simulator::set_fan_height_px; 0: one row per range bin), as
    /// the panel shows it. A change re-forms the shown frame's fan; snapshots still write the full fan.
    void set_fan_height_px(int height_px);
    /// A side-scan's or scan's pings heard along `track` at its time `now_s` (ping_schedule_along: the
    /// waterfall scrolls, the sweep fills as a trajectory plays); null: from the scene's pose forward. A
    /// change goes with the next submit().
    void set_ping_track(std::shared_ptr<const sonarsim::Trajectory> track, double now_s);
    bool on_ping_track() const { return ping_track_ != nullptr; }

  private:
    /// Requests the shown scene's image with its rays placed anew (the edited scene again after it, if it
    /// differs). Returns the request's id.
    std::uint64_t request_placed_anew();
    /// The status after a snapshot: its folder and files.
    void snapshot_status(const std::string& prefix, const std::vector<std::string>& paths);
    /// `st`: changed_stage from the current scene to `next` when the caller knows it (apply_setting's).
    void set_scene(SceneDesc next, std::optional<Stage> st = std::nullopt);
    /// edit() with the stage the change reports (`stage`, filled by `change`; null: computed here).
    bool edit_known(const std::function<void(SceneDesc&)>& change, const std::optional<Stage>* stage);
    /// Makes geometry_ match `scene`: new transforms when only poses differ, else a new SceneGeometry (meshes
    /// from the cache). Throws InputError, keeping the old geometry.
    void update_geometry(const SceneDesc& scene);

    SceneDesc scene_, last_good_;
    std::unique_ptr<SceneGeometry> geometry_;
    std::uint64_t meshes_version_ = 0;
    bool dirty_ = true;
    /// changed_stage since the last request, accumulated edit by edit (empty: unknown, the worker compares).
    std::optional<Stage> changed_;
    bool ground_truth_ = false;
    int fan_height_px_ = 0;
    std::shared_ptr<const sonarsim::Trajectory> ping_track_;
    double ping_track_now_s_ = 0;
    /// The pings to ask the worker for: along ping_track_, or empty (the scene's own).
    std::vector<Ping> requested_pings() const;
    std::uint64_t requested_id_ = 0, shown_count_ = 0;
    std::uint64_t placed_anew_for_ = 0; ///< the shown_count_ whose kept image place_anew() asked again
    std::uint64_t placed_anew_id_ = 0;  ///< and the request it sent
    bool full_pending_ = false;         ///< the last request for scene_ was a preview
    Clock::time_point last_change_{};   ///< when the last changed scene was sent
    std::shared_ptr<const RenderResult> shown_;
    std::string error_, status_;
    RenderWorker worker_;
};

} // namespace sonarsim::ui
