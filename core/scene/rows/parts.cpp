// The rows of a scene's parts: an object (a mesh file or a box, placed by position, orientation and scale,
// with its smoothing angle, its curved-surface factor and a label) and the seafloor (a flat plane at a
// height). Each part's material is the material rows (rows/material.cpp).
#include "core/scene/param_rows.hpp"

#include "core/base/errors.hpp"
#include "core/meshfile/mesh_formats.hpp"

#include <filesystem>

namespace sonarsim::rows {
namespace {

/// An object's vec3 member, shown in the viewer's object panel.
ObjectSpec object_vec3(std::string key, std::string unit, double lo, double hi, bool lo_ex, std::string help,
                       Vec3d ObjectDesc::*field) {
    ObjectSpec p = part<ObjectDesc>(std::move(key), std::move(unit), ParamType::Vec3, lo, hi, lo_ex,
                                    Stage::Geometry, std::move(help));
    p.get = [field](const ObjectDesc& o) { return json(o.*field); };
    p.put = [field](ObjectDesc& o, const json& v, const std::string&) { o.*field = v.get<Vec3d>(); };
    p.section = Section::Object;
    return p;
}

/// A check that the value is a string (`non_empty`: with something in it), naming what it is for.
auto string_check(bool non_empty, std::string what) {
    return
        [non_empty, what](const ValueSpec&, const json& v, const std::string& file, const std::string& key) {
            if (!v.is_string() || (non_empty && v.get<std::string>().empty()))
                throw InputError(file, key, "expected " + what);
            return v;
        };
}

} // namespace

std::vector<ObjectSpec> object_rows() {
    std::vector<ObjectSpec> t;
    ObjectSpec mesh =
        part<ObjectDesc>("mesh", "", ParamType::String, 0, 0, false, Stage::Geometry,
                         "Mesh file (" + mesh_extensions_text() + "), relative to the scene file");
    mesh.get = [](const ObjectDesc& o) {
        return o.box_m ? json(nullptr) : json(o.mesh_resolved.empty() ? o.mesh : o.mesh_resolved);
    };
    mesh.put = [](ObjectDesc& o, const json& v, const std::string& base) {
        o.mesh = v.get<std::string>();
        const std::filesystem::path p(o.mesh);
        o.mesh_resolved =
            p.is_absolute() ? p.string() : (std::filesystem::path(base) / p).lexically_normal().string();
        o.box_m.reset();
    };
    mesh.check = string_check(true, "a non-empty path string (" + mesh_extensions_text() + ")");
    t.push_back(mesh);
    ObjectSpec box = part<ObjectDesc>("box", "m", ParamType::Vec3, 0, 1e4, true, Stage::Geometry,
                                      "Box size dx, dy, dz (instead of a mesh)")
                         .with_log_slider(0.01, 10);
    box.get = [](const ObjectDesc& o) { return o.box_m ? json(*o.box_m) : json(nullptr); };
    box.put = [](ObjectDesc& o, const json& v, const std::string&) {
        o.box_m = v.get<Vec3d>();
        o.mesh.clear(), o.mesh_resolved.clear();
    };
    t.push_back(box);
    t.push_back(object_vec3("position", "m", -1e6, 1e6, false, "Box centre / mesh origin x, y, z",
                            &ObjectDesc::position_m)
                    .with_label("object position"));
    t.push_back(object_vec3("orientation_deg", "deg", -360, 360, false, "Roll, pitch, yaw of the object",
                            &ObjectDesc::orientation_deg)
                    .with_label("object roll pitch yaw"));
    ObjectSpec scale = object_vec3("scale", "", 0, 1e6, true, "Scale per axis, or one number for all three",
                                   &ObjectDesc::scale)
                           .with_label("object scale x y z")
                           .with_log_slider(1e-3, 1e3);
    scale.check = [](const ValueSpec& spec, const json& v, const std::string& file, const std::string& key) {
        if (!v.is_number()) return validate_value(spec, v, file, key);
        ValueSpec one = spec;
        one.type = ParamType::Number;
        const double x = validate_value(one, v, file, key).get<double>();
        return json(Vec3d{x, x, x});
    };
    t.push_back(scale);
    ObjectSpec crease =
        part<ObjectDesc>("crease_angle_deg", "deg", ParamType::Number, 0, 180, false, Stage::Geometry,
                         "Smooth shading: the normal at a hit is interpolated from corner normals "
                         "that average the faces meeting there within this angle of each other; "
                         "faces at a larger angle keep their edge (a box's 90 deg). 0: face "
                         "normals");
    crease.get = [](const ObjectDesc& o) { return json(o.crease_angle_deg); };
    crease.put = [](ObjectDesc& o, const json& v, const std::string&) {
        o.crease_angle_deg = v.get<double>();
    };
    crease.section = Section::Object;
    t.push_back(crease);
    ObjectSpec phong =
        part<ObjectDesc>("phong_alpha", "", ParamType::Number, 0, 1, false, Stage::Geometry,
                         "Curved surfaces (Phong tessellation's shape factor): rays meet a smooth object's "
                         "faces on the surface p* = (1 - alpha) p + alpha sum_i b_i (p - ((p - p_i).n_i) "
                         "n_i) (barycentric b_i, corners p_i, corner normals n_i), so a coarse mesh's "
                         "ranges follow the smooth shape; 0.5 follows a sphere, 1 bulges out of it. Faces "
                         "whose corners share one normal (a box, a crease) stay flat. 0: the flat faces");
    phong.get = [](const ObjectDesc& o) { return json(o.phong_alpha); };
    phong.put = [](ObjectDesc& o, const json& v, const std::string&) { o.phong_alpha = v.get<double>(); };
    phong.section = Section::Object;
    t.push_back(phong);
    ObjectSpec name = part<ObjectDesc>("name", "", ParamType::String, 0, 0, false, Stage::None, "A label");
    name.get = [](const ObjectDesc& o) { return json(o.name); };
    name.put = [](ObjectDesc& o, const json& v, const std::string&) { o.name = v.get<std::string>(); };
    name.check = string_check(false, "a string");
    name.written = false;
    t.push_back(name);
    return t;
}

std::vector<SeafloorSpec> seafloor_rows() {
    SeafloorSpec h = part<Seafloor>("height_m", "m", ParamType::Number, -1e6, 1e6, false, Stage::Trace,
                                    "Height z of the flat seafloor");
    h.get = [](const Seafloor& f) { return json(f.height_m); };
    h.put = [](Seafloor& f, const json& v, const std::string&) { f.height_m = v.get<double>(); };
    return {h};
}

} // namespace sonarsim::rows
