// The `sonarsim` Python module (pybind11): a Simulator, its frames as NumPy arrays that share the frame's
// memory, one-off renders, and the dataset functions the Dask example distributes.
#include "core/analysis/compare_report.hpp"
#include "core/dataset/batch.hpp"
#include "core/shading/ground_truth.hpp"
#include "core/base/errors.hpp"
#include "core/io/output.hpp"
#include "core/io/ping_output.hpp"
#include "core/kinds/ping_series.hpp"
#include "core/scene/params.hpp"
#include "core/scene/scene_io.hpp"
#include "core/pipeline/simulator.hpp"

#include <filesystem>
#include <memory>
#include <optional>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;
using namespace sonarsim;

namespace {

json to_json(const py::handle& value) {
    return json::parse(py::module_::import("json").attr("dumps")(value).cast<std::string>());
}

py::object to_python(const json& j) {
    return py::module_::import("json").attr("loads")(j.dump());
}

/// A scene from None (the built-in scene), a scene file path or a dict with the scene file's keys.
SceneDesc scene_from(const py::object& scene) {
    if (scene.is_none()) return default_scene();
    if (py::isinstance<py::str>(scene) || py::hasattr(scene, "__fspath__"))
        return load_scene(py::str(scene).cast<std::string>());
    if (py::isinstance<py::dict>(scene))
        return parse_scene(to_json(scene).dump(), "<dict>", std::filesystem::current_path().string());
    throw InputError("scene", "", "expected None, a scene file path or a dict of scene file keys");
}

/// An image for compare(): a path (.aris frame, .npy or fan .png), or a 2-D array of levels [dB] (range bins
/// x beams).
PolarImage compare_input(const py::object& x, std::size_t frame, const std::string& fan, const char* name) {
    if (py::isinstance<py::str>(x) || py::hasattr(x, "__fspath__"))
        return load_compare_image(py::str(x).cast<std::string>(), frame, fan);
    const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(x);
    if (!a || a.ndim() != 2)
        throw InputError(name, "", "expected a file path (.aris, .npy, .png) or a 2-D array of levels in dB");
    PolarImage img;
    img.bins = int(a.shape(0)), img.beams = int(a.shape(1));
    img.level_db.assign(a.data(), a.data() + a.size());
    return img;
}

Pose pose_from(const py::object& pose) {
    const auto v = pose.cast<std::vector<double>>();
    if (v.size() != 6) throw InputError("pose", "", "expected [x, y, z, roll, pitch, yaw] (m, deg)");
    return {{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
}

/// A rendered frame; its arrays view the frame's own memory, which lives as long as any of them.
struct PyFrame {
    std::shared_ptr<const Frame> frame;
    SceneDesc scene;
    std::shared_ptr<const GroundTruth> gt; ///< when render(ground_truth=True)

    py::array level_db() const {
        const PolarImage& p = frame->polar();
        auto owner = new std::shared_ptr<const Frame>(frame);
        py::capsule base(owner, [](void* o) { delete static_cast<std::shared_ptr<const Frame>*>(o); });
        py::array a(py::dtype::of<float>(), {p.bins, p.beams}, p.level_db.data(), base);
        py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
        return a;
    }
    py::array sector() const {
        const Image8& img = frame->sector();
        auto owner = new std::shared_ptr<const Frame>(frame);
        py::capsule base(owner, [](void* o) { delete static_cast<std::shared_ptr<const Frame>*>(o); });
        py::array a(py::dtype::of<std::uint8_t>(), {img.height, img.width, img.channels}, img.pixels.data(),
                    base);
        py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
        return a;
    }
    py::dict metadata() const { return to_python(frame_metadata(scene, *frame)); }
    /// The ground truth arrays by name (views of gt's memory, kept alive by each array), or {}.
    py::dict ground_truth() const {
        py::dict d;
        if (!gt) return d;
        auto view = [&](const auto& v, std::vector<py::ssize_t> shape) {
            auto owner = new std::shared_ptr<const GroundTruth>(gt);
            py::capsule base(owner,
                             [](void* o) { delete static_cast<std::shared_ptr<const GroundTruth>*>(o); });
            using T = typename std::decay_t<decltype(v)>::value_type;
            py::array a(py::dtype::of<T>(), shape, v.data(), base);
            py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
            return a;
        };
        for (const GroundTruthField& f : ground_truth_fields()) {
            std::vector<py::ssize_t> shape{gt->bins, gt->beams};
            if (f.components > 1) shape.push_back(f.components);
            d[f.name] = f.f32 ? view((*gt).*f.f32, shape) : view((*gt).*f.i32, shape);
        }
        return d;
    }
};

class PySimulator {
  public:
    explicit PySimulator(const py::object& scene) : scene_(scene_from(scene)) {
        validate_scene(scene_, scene_.source_file);
        sim_ = std::make_unique<Simulator>(scene_);
    }
    void set(const std::string& key, const py::object& value) {
        SceneDesc s = scene_;
        apply_setting(s, key, to_json(value), "set");
        update(s);
    }
    void set_pose(const py::object& pose) {
        SceneDesc s = scene_;
        s.sonar.pose = pose_from(pose);
        update(s);
    }
    PyFrame render(bool ground_truth) {
        std::shared_ptr<const Frame> f;
        std::shared_ptr<const GroundTruth> gt;
        {
            py::gil_scoped_release release;
            sim_->request({ground_truth, false});
            f = sim_->render();
            gt = f->truth_ptr;
        }
        return {f, scene_, gt};
    }
    py::dict scene() const { return to_python(scene_to_json(scene_)); }

  private:
    void update(const SceneDesc& s) {
        validate_scene(s, "set");
        sim_->set_scene(s);
        scene_ = s;
    }
    SceneDesc scene_;
    std::unique_ptr<Simulator> sim_;
};

/// The ground_truth property's help: the arrays' names from the one list (ground_truth_fields).
const std::string& ground_truth_doc() {
    static const std::string doc = [] {
        std::string names;
        for (const GroundTruthField& f : ground_truth_fields())
            names += (names.empty() ? "" : ", ") + std::string(f.name) +
                     (f.components > 1 ? " (bins, beams, " + std::to_string(f.components) + ")" : "");
        return "with render(ground_truth=True): per (range bin, beam) arrays by name, as the files render "
               "--ground-truth writes (" +
               names + "); otherwise {}";
    }();
    return doc;
}

} // namespace

PYBIND11_MODULE(sonarsim, m) {
    m.doc() = "sonarsim: simulated forward-looking imaging sonar (acoustic camera) images";
    py::register_exception<InputError>(m, "InputError", PyExc_ValueError);

    py::class_<PyFrame>(m, "Frame")
        .def_property_readonly("level_db", &PyFrame::level_db,
                               "L_EN [dB], float32 (range_bins, beams): row 0 nearest, column 0 port-most; "
                               "-inf where nothing echoes. Read-only, shares the frame's memory")
        .def_property_readonly("sector", &PyFrame::sector, "the sector (fan) image, uint8 (H, W, 3)")
        .def_property_readonly("ground_truth", &PyFrame::ground_truth, ground_truth_doc().c_str())
        .def_property_readonly("metadata", &PyFrame::metadata, "the metadata `render` writes as JSON");

    py::class_<PySimulator>(m, "Simulator")
        .def(py::init<const py::object&>(), py::arg("scene") = py::none(),
             "scene: a scene file path, a dict with the scene file's keys, or None for the built-in scene")
        .def("set", &PySimulator::set, py::arg("key"), py::arg("value"),
             "set one parameter, e.g. sim.set('sonar.beams', 64) or sim.set('objects.0.position', [1, 2, 0])")
        .def("set_pose", &PySimulator::set_pose, py::arg("pose"), "[x, y, z, roll, pitch, yaw] in m and deg")
        .def("render", &PySimulator::render, py::arg("ground_truth") = false,
             "render (the GIL is released meanwhile); recomputes only what changed")
        .def_property_readonly("scene", &PySimulator::scene, "every effective parameter, as a scene file");

    m.def(
        "render",
        [](const py::object& scene, const py::object& pose, const py::object& set, bool ground_truth) {
            PySimulator sim(scene);
            if (!set.is_none())
                for (auto item : set.cast<py::dict>())
                    sim.set(py::str(item.first), py::reinterpret_borrow<py::object>(item.second));
            if (!pose.is_none()) sim.set_pose(pose);
            return sim.render(ground_truth);
        },
        py::arg("scene") = py::none(), py::arg("pose") = py::none(), py::arg("set") = py::none(),
        py::arg("ground_truth") = false,
        "one frame: sonarsim.render(scene, pose=[...], set={'sonar.beams': 64})");

    m.def(
        "render_pings",
        [](const py::object& scene, const py::object& set, bool ground_truth, const std::string& trajectory,
           const py::object& at_s) {
            SceneDesc s = scene_from(scene);
            std::vector<std::string> keys;
            if (!set.is_none())
                for (auto item : set.cast<py::dict>()) {
                    const std::string key = py::str(item.first);
                    apply_setting(s, key, to_json(item.second), "set");
                    keys.push_back(key);
                }
            validate_scene(s, "set", keys);
            if (s.sonar.kind == SonarKind::Imaging)
                throw InputError(
                    s.source_file, "sonar.kind",
                    "render_pings takes sonar.kind sidescan or scanning; an imaging sonar: render()");
            PingControl control;
            control.ground_truth = ground_truth;
            std::optional<double> at;
            if (!at_s.is_none()) {
                if (trajectory.empty())
                    throw InputError("at_s", "", "is a time on a trajectory: give trajectory= too");
                try {
                    at = at_s.cast<double>();
                } catch (const py::cast_error&) {
                    throw InputError("at_s", "", "expected a number of seconds");
                }
            }
            if (!trajectory.empty())
                control.schedule = ping_schedule_along_file(s, trajectory, at, "trajectory", "at_s");
            PingSeries p;
            {
                py::gil_scoped_release release;
                p = render_pings(s, control);
            }
            auto array = [](const std::vector<float>& v, std::vector<py::ssize_t> shape) {
                py::array_t<float> a(shape);
                std::copy(v.begin(), v.end(), a.mutable_data());
                return a;
            };
            std::vector<py::ssize_t> shape = {p.pings, p.channels, p.bins};
            if (p.channels == 1) shape.erase(shape.begin() + 1);
            py::dict d;
            d["level_db"] = array(p.level_db, shape);
            d["ideal_db"] = array(p.ideal_db, shape);
            const PingViews views = ping_views(s, p);
            if (s.sonar.kind == SonarKind::Sidescan)
                d["waterfall_db"] = array(views.shown.level_db, {views.shown.bins, views.shown.beams});
            const Image8 img = ping_image(s, p, views);
            py::array_t<std::uint8_t> rgb({img.height, img.width, img.channels});
            std::copy(img.pixels.begin(), img.pixels.end(), rgb.mutable_data());
            d["image"] = rgb;
            d["metadata"] = to_python(ping_metadata(s, p, views));
            if (ground_truth) { // per ping, channel and sample, shaped as level_db (point_m: a last axis of
                                // 3)
                py::dict gt;
                for (const GroundTruthField& f : ground_truth_fields()) {
                    std::vector<py::ssize_t> fshape = shape;
                    if (f.components > 1) fshape.push_back(f.components);
                    auto joined = [&](auto member) {
                        using T = typename std::decay_t<decltype(p.truth[0].*member)>::value_type;
                        py::array_t<T> a(fshape);
                        T* out = a.mutable_data();
                        for (const GroundTruth& g : p.truth)
                            out = std::copy((g.*member).begin(), (g.*member).end(), out);
                        return py::object(a);
                    };
                    gt[f.name] = f.f32 ? joined(f.f32) : joined(f.i32);
                }
                d["ground_truth"] = gt;
            }
            return d;
        },
        py::arg("scene") = py::none(), py::arg("set") = py::none(), py::arg("ground_truth") = false,
        py::arg("trajectory") = "", py::arg("at_s") = py::none(),
        "a side-scan's waterfall or a scanning sonar's sweep: {'level_db': (pings, channels, bins) or "
        "(steps, bins), 'ideal_db', 'waterfall_db' (side-scan), 'image' (RGB), 'metadata', with "
        "ground_truth=True 'ground_truth' (arrays by name, shaped as level_db)}, as `sonarsim render` writes "
        "them; trajectory='line.csv', at_s=12.0: the pings heard along that trajectory, the newest at 12 s "
        "(render's --trajectory, --at)");

    m.def(
        "prepare_dataset",
        [](const std::string& out, const py::object& scene, const std::string& trajectory,
           const std::string& circle, const std::string& line, double rate_hz) {
            SceneDesc s = scene_from(scene);
            validate_scene(s, s.source_file);
            const Trajectory t =
                make_trajectory(trajectory, circle, line, rate_hz, s.sonar.pose.orientation_deg);
            prepare_dataset(out, s, t);
            return t.size();
        },
        py::arg("out"), py::arg("scene") = py::none(), py::arg("trajectory") = "", py::arg("circle") = "",
        py::arg("line") = "", py::arg("rate_hz") = 10.0,
        "start (or check) the dataset directory `out` as `sonarsim batch` does, with the poses of exactly "
        "one of a trajectory CSV file, a circle or a line spec (as batch's --circle, --line); returns its "
        "number of frames");
    m.def(
        "render_frames",
        [](const std::string& out, const std::vector<size_t>& frames, bool resume, bool ground_truth) {
            BatchOptions o;
            o.frames = frames;
            o.resume = resume;
            o.ground_truth = ground_truth;
            o.index = false; // once, by the caller, after all tasks
            py::gil_scoped_release release;
            return run_batch(out, o).rendered;
        },
        py::arg("out"), py::arg("frames"), py::arg("resume") = false, py::arg("ground_truth") = false,
        "render these frames of a prepared dataset (one Simulator for all); returns how many were rendered");
    m.def(
        "compare",
        [](const py::object& a, const py::object& b, std::size_t frame_a, std::size_t frame_b,
           const std::string& fan_a, const std::string& fan_b) {
            const PolarImage ia = compare_input(a, frame_a, fan_a, "a"),
                             ib = compare_input(b, frame_b, fan_b, "b");
            nlohmann::json r;
            {
                py::gil_scoped_release release;
                r = compare_images_report(ia, ib);
            }
            return to_python(r);
        },
        py::arg("a"), py::arg("b"), py::arg("frame_a") = 0, py::arg("frame_b") = 0, py::arg("fan_a") = "",
        py::arg("fan_b") = "",
        "realism statistics of two images, as `sonarsim compare` writes them: each of a and b a path (.aris "
        "recording, with frame_a/frame_b, an .npy level image, or a gray fan .png with fan_a/fan_b its "
        "geometry as `sonarsim compare --fan-a` takes it, by default the metadata render wrote beside it) or "
        "a 2-D array of levels [dB] (range bins "
        "x "
        "beams). Returns {'a': ..., 'b': ..., 'pair': ...}: floor fraction, mean level, range profile, "
        "speckle "
        "contrast (intensity, amplitude), dB quantiles around the local mean, grain (correlation at lags "
        "along "
        "range and across beams), histogram; the pair's profile rms difference, histogram distance and, on "
        "the "
        "same grid, correlation and highlight/shadow overlaps");
    m.def("write_index", py::overload_cast<const std::string&>(&write_index), py::arg("out"),
          "rebuild out/index.csv; returns the frames listed");
}
