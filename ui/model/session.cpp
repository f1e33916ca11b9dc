#include "ui/model/session.hpp"

#include "ui/model/snapshot.hpp"
#include "ui/model/sonar_geometry.hpp"

#include "core/io/ping_output.hpp"
#include "core/scene/scene_parts.hpp"
#include "core/base/errors.hpp"
#include "core/geometry/mesh_cache.hpp"
#include "core/data/pose.hpp"
#include "core/scene/scene_io.hpp"

#include <filesystem>

namespace sonarsim::ui {

Session::Session(const SceneDesc& scene)
    : scene_(scene), last_good_(scene), geometry_(std::make_unique<SceneGeometry>(scene)),
      meshes_version_(1) {}

std::vector<std::shared_ptr<const TriMesh>> Session::local_meshes() const {
    std::vector<std::shared_ptr<const TriMesh>> out;
    for (size_t i = 0; i < geometry_->object_count(); ++i) out.push_back(geometry_->local_mesh(i));
    return out;
}

void Session::update_geometry(const SceneDesc& scene) {
    if (geometry_->update_transforms(scene)) return; // only poses changed: milliseconds, on this thread
    geometry_ = std::make_unique<SceneGeometry>(scene);
    ++meshes_version_;
}

void Session::set_scene(SceneDesc next, std::optional<Stage> known) {
    const Stage st = known ? *known : changed_stage(scene_, next);
    if (st == Stage::None && next.source_file == scene_.source_file) return;
    if (st == Stage::Geometry) update_geometry(next); // throws InputError: caller keeps the old scene
    scene_ = std::move(next);
    if (changed_) changed_ = std::min(*changed_, st);
    dirty_ = true;
}

bool Session::edit(const std::function<void(SceneDesc&)>& change) {
    return edit_known(change, nullptr);
}

bool Session::edit_known(const std::function<void(SceneDesc&)>& change, const std::optional<Stage>* stage) {
    try {
        SceneDesc next = scene_;
        change(next);
        validate_scene(next, next.source_file.empty() ? "viewer" : next.source_file);
        set_scene(std::move(next), stage ? *stage : std::nullopt);
        return true;
    } catch (const InputError& e) {
        error_ = e.what();
        return false;
    }
}

bool Session::set(const std::string& key, const json& value) {
    std::optional<Stage> stage; // apply_setting's: what the edit invalidates, computed once
    return edit_known([&](SceneDesc& s) { stage = apply_setting(s, key, value, "viewer"); }, &stage);
}

bool Session::reset_to_paper() {
    return edit([](SceneDesc& s) {
        const SceneDesc paper;
        for (auto& p : scene_params())
            if (p.type != ParamType::Vec3) p.put(s, p.get(paper));
        for (int part : material_parts(s))
            *material_of(s, part) = part == kSurfacePart ? WaterParams{}.surface_material : Material{};
    });
}

bool Session::open_scene(const std::string& path) {
    try {
        SceneDesc next = load_scene(path);
        auto geometry = std::make_unique<SceneGeometry>(next);
        scene_ = std::move(next);
        geometry_ = std::move(geometry);
        ++meshes_version_;
        dirty_ = true;
        changed_.reset(); // the worker compares the scenes
        status_ = "opened " + path;
        error_.clear();
        return true;
    } catch (const InputError& e) {
        error_ = e.what();
        return false;
    }
}

bool Session::add_mesh(const std::string& path) {
    try {
        std::error_code ec;
        ObjectDesc o;
        o.mesh = std::filesystem::absolute(path, ec).lexically_normal().string();
        o.mesh_resolved = o.mesh;
        const std::shared_ptr<const TriMesh> m = cached_mesh(o.mesh, path, "mesh"); // the geometry reuses it
        glm::vec3 lo, hi;
        mesh_bounds(*m, lo, hi);
        // Stand it on the floor where the boresight meets it (or 1.5 m ahead), centred in x and y.
        const SonarParams& s = scene_.sonar;
        const glm::dvec3 bore = rotation_matrix(s.pose.orientation_deg) * glm::dvec3(1, 0, 0);
        const glm::dvec3 pos = to_glm(s.pose.position_m);
        const double floor_z = scene_.seafloor ? scene_.seafloor->height_m : 0.0;
        double reach = 1.5;
        if (bore.z < -1e-3) reach = std::min(s.range_max_m, (pos.z - floor_z) / -bore.z);
        const glm::dvec3 at = pos + reach * bore;
        o.position_m = {at.x - 0.5 * (lo.x + hi.x), at.y - 0.5 * (lo.y + hi.y), floor_z - lo.z};
        const bool ok = edit([&](SceneDesc& sc) { sc.objects.push_back(o); });
        if (ok) status_ = "added " + path;
        return ok;
    } catch (const InputError& e) {
        error_ = e.what();
        return false;
    }
}

bool Session::save_scene(const std::string& path) {
    try {
        write_files_atomically({{path, to_bytes(snapshot_scene_text(scene_))}});
        status_ = "saved " + path;
        return true;
    } catch (const std::exception& e) {
        error_ = std::string("cannot save the scene: ") + e.what();
        return false;
    }
}

std::uint64_t Session::submit(bool interacting, Clock::time_point now) {
    if (dirty_) {
        dirty_ = false;
        last_change_ = now;
        full_pending_ = interacting;
        requested_id_ =
            worker_.request(scene_, interacting, ground_truth_, changed_, fan_height_px_, requested_pings());
        changed_ = Stage::None;
        return requested_id_;
    }
    if (full_pending_ && (!interacting || now - last_change_ >= kRest)) {
        // The input rests: the same scene again, in full quality (the worker re-traces a preview).
        full_pending_ = false;
        // The worker compares the scenes.
        requested_id_ =
            worker_.request(scene_, false, ground_truth_, std::nullopt, fan_height_px_, requested_pings());
        changed_ = Stage::None;
        return requested_id_;
    }
    return 0;
}

bool Session::poll() {
    std::optional<RenderResult> r = worker_.take();
    if (!r) return false;
    if (!r->error.empty()) {
        error_ = r->error;
        // The newest request failed (a mesh that the worker could not load): go back to the last good scene.
        if (r->id == requested_id_ && !dirty_) {
            scene_ = last_good_;
            changed_.reset();                            // the worker compares the scenes
            full_pending_ = shown_ && shown_->preview(); // the full image of the last good scene
            try {
                update_geometry(scene_);
            } catch (const InputError&) {
            }
        }
        return false;
    }
    // A preview request that came back in full quality (uniform and spread ignore TraceControl::preview).
    if (r->id == requested_id_ && !r->preview()) full_pending_ = false;
    last_good_ = r->scene;
    shown_ = std::make_shared<const RenderResult>(std::move(*r));
    ++shown_count_;
    return true;
}

bool Session::wait_latest(std::chrono::milliseconds timeout) {
    const bool ok = requested_id_ == 0 || worker_.wait_for(requested_id_, timeout);
    poll();
    return ok;
}

bool Session::wait_full(std::chrono::milliseconds timeout) {
    submit(false);
    return wait_latest(timeout) && shown_ && !shown_->preview();
}

bool Session::busy() const {
    return dirty_ || full_pending_ || worker_.busy();
}

void Session::set_ground_truth(bool on) {
    if (on == ground_truth_) return;
    ground_truth_ = on;
    if (on) dirty_ = true; // the shown frame has none: render it again with it
}

void Session::set_ping_track(std::shared_ptr<const sonarsim::Trajectory> track, double now_s) {
    if (track == ping_track_ && (!track || now_s == ping_track_now_s_)) return;
    ping_track_ = std::move(track);
    ping_track_now_s_ = now_s;
    if (scene_.sonar.kind != SonarKind::Imaging) dirty_ = true; // other pings: a new waterfall or sweep
}

std::vector<Ping> Session::requested_pings() const {
    if (!ping_track_ || scene_.sonar.kind == SonarKind::Imaging) return {};
    return ping_schedule_along(scene_, *ping_track_, ping_track_now_s_);
}

void Session::set_fan_height_px(int height_px) {
    if (height_px == fan_height_px_) return;
    fan_height_px_ = height_px;
    dirty_ = true; // the same scene again: the worker re-forms its fan
}

void Session::snapshot_status(const std::string& prefix, const std::vector<std::string>& paths) {
    const std::filesystem::path folder = std::filesystem::absolute(prefix).lexically_normal().parent_path();
    // Short enough for the panel's footer: the prefix's name once, then what each file adds to it.
    const std::string stem = std::filesystem::path(prefix).filename().string();
    status_ = "snapshot " + stem + " in " + folder.string() + ":";
    for (auto& p : paths) {
        const std::string name = std::filesystem::path(p).filename().string();
        status_ +=
            " " + (name.rfind(stem, 0) == 0 && name.size() > stem.size() ? name.substr(stem.size()) : name);
    }
    error_.clear();
}

bool Session::shown_kept_placement() const {
    return shown_ && ((shown_->frame && shown_->frame->placement_kept) ||
                      (shown_->pings && shown_->pings->kept_placement_profiles > 0));
}

std::uint64_t Session::request_placed_anew() {
    requested_id_ = worker_.request(shown_->scene, false, ground_truth_, std::nullopt, fan_height_px_,
                                    requested_pings(), false);
    // That request replaces any of a newer edit: the edited scene is requested again after it.
    if (changed_stage(scene_, shown_->scene) != Stage::None) dirty_ = true, changed_.reset();
    return requested_id_;
}

bool Session::place_anew() {
    if (!shown_kept_placement()) return false;
    // A newer edit is on its way (its image comes next): nothing to ask; a snapshot now is of this image
    // and snapshot() places it anew itself.
    if (dirty_ || changed_stage(scene_, shown_->scene) != Stage::None) return false;
    // Asked already for this image: on its way until the worker has finished it (an error, or a result
    // replaced, leaves the kept image on screen: then not asked again).
    if (placed_anew_for_ == shown_count_ && placed_anew_id_ != 0)
        return !worker_.wait_for(placed_anew_id_, std::chrono::milliseconds(0));
    placed_anew_for_ = shown_count_;
    placed_anew_id_ = request_placed_anew();
    return true;
}

bool Session::snapshot(const std::string& prefix, const Bytes& view3d_png, const Bytes& annotated_png) {
    if (!shown_) {
        error_ = "no sonar image yet: nothing to snapshot";
        return false;
    }
    if (shown_->preview() && !wait_full(std::chrono::milliseconds(60000))) {
        error_ = "snapshot: the full-quality image is not ready";
        return false;
    }
    try {
        if (ground_truth_ && !shown_->ground_truth && !wait_full(std::chrono::milliseconds(60000))) {
            error_ = "snapshot: the ground truth is not ready";
            return false;
        }
        // An image whose rays were kept from an earlier shading (a slider that steers the sampler): placed
        // anew first, so that the files are what `render` makes of the scene.
        if (shown_kept_placement()) {
            request_placed_anew();
            const bool ready = wait_latest(std::chrono::milliseconds(60000)) && shown_ &&
                               !shown_->preview() && !shown_kept_placement();
            if (!ready) {
                error_ = "snapshot: the image with its rays placed anew is not ready";
                return false;
            }
        }
        if (shown_->pings) { // a side-scan's or scan's files, as render writes them, and the 3D view
            std::vector<std::pair<std::string, Bytes>> extra;
            if (!view3d_png.empty()) extra.emplace_back(prefix + "_3d.png", view3d_png);
            snapshot_status(prefix, write_ping_files(prefix, shown_->scene, *shown_->pings, extra));
            return true;
        }
        // The files hold the fan at one row per range bin, whatever the panel shows.
        Frame frame = *shown_->frame;
        if (frame.sector().height != frame.grid().default_fan_height_px()) {
            frame.sector_map_ptr = std::make_shared<const SectorResampler>(frame.grid_ptr, 0);
            frame.sector_ptr =
                std::make_shared<const Image8>(frame.sector_map_ptr->apply(frame.polar(), frame.display));
        }
        const auto paths =
            write_snapshot(prefix, shown_->scene, frame, view3d_png,
                           ground_truth_ ? shown_->ground_truth.get() : nullptr, annotated_png);
        snapshot_status(prefix, paths);
        return true;
    } catch (const std::exception& e) {
        error_ = std::string("snapshot failed: ") + e.what();
        return false;
    }
}

} // namespace sonarsim::ui
