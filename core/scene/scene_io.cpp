#include "core/scene/scene_io.hpp"

#include "core/base/errors.hpp"
#include "core/base/file_io.hpp"

#include <algorithm>
#include <cmath>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <type_traits>
#include <vector>

namespace sonarsim {
namespace {

constexpr int kMaxNesting = 32;

/// 1-based line of byte offset `at` in `text`.
long line_of(const std::string& text, size_t at) {
    const size_t upto = std::min(at, text.size());
    return 1 + long(std::count(text.begin(), text.begin() + long(upto), '\n'));
}

/// Parser callback: limits nesting and rejects duplicate keys (nlohmann keeps the last one silently),
/// naming the key path, e.g. objects[2].material.q.
class KeyTracker {
  public:
    explicit KeyTracker(std::string file) : file_(std::move(file)) {}
    bool operator()(int depth, json::parse_event_t event, json& parsed) {
        using E = json::parse_event_t;
        if (depth > kMaxNesting)
            throw InputError(file_, path(), "nesting deeper than " + std::to_string(kMaxNesting) + " levels");
        switch (event) {
        case E::object_start:
        case E::array_start:
            frames_->push_back(Frame{event == E::array_start, 0, {}, {}});
            break;
        case E::key: {
            Frame& f = frames_->back();
            f.key = parsed.get<std::string>();
            if (!f.keys.insert(f.key).second)
                throw InputError(file_, path(), "duplicate key; each key may appear once per object");
            break;
        }
        case E::object_end:
        case E::array_end:
            frames_->pop_back();
            advance();
            break;
        case E::value:
            advance();
            break;
        }
        return true;
    }

  private:
    struct Frame {
        bool array;
        size_t index;
        std::set<std::string> keys;
        std::string key;
    };
    void advance() {
        if (!frames_->empty() && frames_->back().array) ++frames_->back().index;
    }
    std::string path() const {
        std::string p;
        for (const Frame& f : *frames_)
            p += f.array ? "[" + std::to_string(f.index) + "]" : (p.empty() ? "" : ".") + f.key;
        return p;
    }
    std::string file_;
    // json::parse copies the callback; the copies share one stack.
    std::shared_ptr<std::vector<Frame>> frames_ = std::make_shared<std::vector<Frame>>();
};

const json& require_object(const json& v, const std::string& file, const std::string& key) {
    if (!v.is_object()) throw InputError(file, key, "expected an object");
    return v;
}

/// A material object: its preset first, so that its other keys override the preset's values.
Material parse_material(const json& v, const std::string& file, const std::string& key) {
    require_object(v, file, key);
    Material m;
    const std::string preset = material_preset_param().key;
    if (v.contains(preset)) set_material(m, preset, v[preset], file, key + "." + preset);
    for (auto& [k, val] : v.items())
        if (k != preset) set_material(m, k, val, file, key + "." + k);
    return m;
}

ObjectDesc parse_object(const json& v, const std::string& file, const std::string& key,
                        const std::string& base) {
    require_object(v, file, key);
    ObjectDesc o;
    for (auto& [k, val] : v.items()) {
        const std::string kk = key + "." + k;
        if (k == "material") {
            o.material = parse_material(val, file, kk);
        } else if (const ObjectSpec* p = find_object_param(k)) {
            p->put(o, p->validated(val, file, kk), base);
        } else {
            throw InputError(file, kk, "unknown key; allowed: " + part_keys_text(object_params()));
        }
    }
    if (v.contains("mesh") == v.contains("box"))
        throw InputError(file, key, "an object needs exactly one of \"mesh\" or \"box\"");
    return o;
}

/// The sections of a scene file that hold the table's scene rows ("sonar", "water", ...), in table order.
const std::vector<std::string>& table_sections() {
    static const std::vector<std::string> sections = [] {
        std::vector<std::string> out;
        for (auto& p : scene_params()) {
            const std::string head = p.key.substr(0, p.key.find('.'));
            if (std::find(out.begin(), out.end(), head) == out.end()) out.push_back(head);
        }
        return out;
    }();
    return sections;
}

bool is_table_section(const std::string& name) {
    const auto& all = table_sections();
    return std::find(all.begin(), all.end(), name) != all.end();
}

std::string table_sections_text() {
    std::string text;
    for (auto& s : table_sections()) text += (text.empty() ? "" : ", ") + s;
    return text;
}

} // namespace

SceneDesc default_scene() {
    SceneDesc s;
    ObjectDesc prism;
    prism.box_m = Vec3d{0.07, 0.12, 0.22};
    prism.position_m = {1.5, 1.5, 0.11};
    s.objects.push_back(prism);
    return s;
}

SceneDesc parse_scene(const std::string& text, const std::string& file, const std::string& base_dir,
                      const GroupOverrides& group_overrides) {
    json root;
    try {
        root = json::parse(text, KeyTracker(file));
    } catch (const json::parse_error& e) {
        // Turn the byte offset into a line number.
        std::string what = e.what();
        const size_t pos = what.find("parse error");
        throw InputError(file + ":" + std::to_string(line_of(text, e.byte)), "",
                         "invalid JSON: " + what.substr(pos == std::string::npos ? 0 : pos));
    } catch (const json::exception& e) {
        // e.g. out_of_range 406 "number overflow parsing '1e400'": find the literal for a line number.
        std::string what = e.what();
        const size_t bracket = what.find("] ");
        what = what.substr(bracket == std::string::npos ? 0 : bracket + 2);
        std::string where = file;
        const size_t q0 = what.find('\''), q1 = what.rfind('\'');
        if (q0 != std::string::npos && q1 > q0 + 1) {
            const size_t at = text.find(what.substr(q0 + 1, q1 - q0 - 1));
            if (at != std::string::npos) where += ":" + std::to_string(line_of(text, at));
        }
        throw InputError(where, "", "invalid JSON: " + what + " (numbers must be finite doubles)");
    }
    if (!root.is_object()) throw InputError(file, "", "the top level must be a JSON object");

    SceneDesc scene;
    scene.source_file = file;
    // Group keys first (a device preset, then the sensor model), so that every other key overrides them.
    for (const std::string& k : group_keys()) {
        const std::string section = k.substr(0, k.find('.')), name = k.substr(k.find('.') + 1);
        auto over = std::find_if(group_overrides.begin(), group_overrides.end(),
                                 [&](auto& o) { return o.first == k; });
        if (over != group_overrides.end())
            apply_setting(scene, k, over->second, "--set");
        else if (root.contains(section) && root[section].is_object() && root[section].contains(name))
            apply_setting(scene, k, root[section][name], file);
    }
    for (auto& [section, body] : root.items()) {
        if (is_table_section(section)) {
            require_object(body, file, section);
            for (auto& [k, val] : body.items()) {
                const std::string key = section + "." + k;
                if (is_group_key(key)) continue;
                if (key == "water.surface_material") {
                    scene.water.surface_material = parse_material(val, file, key);
                    continue;
                }
                const ParamSpec* p = find_param(key);
                if (!p) {
                    std::string allowed;
                    for (const auto* list : {&scene_params(), &input_params()})
                        for (auto& q : *list)
                            if (q.key.rfind(section + ".", 0) == 0)
                                allowed += (allowed.empty() ? "" : ", ") + q.key.substr(section.size() + 1);
                    if (section == "water") allowed += ", surface_material";
                    throw InputError(file, key, "unknown key; allowed: " + allowed);
                }
                p->put(scene, validate_value(*p, val, file, key));
            }
        } else if (section == "seafloor") {
            if (body.is_null()) {
                scene.seafloor.reset();
                continue;
            }
            require_object(body, file, section);
            Seafloor f;
            for (auto& [k, val] : body.items()) {
                if (k == "material") {
                    f.material = parse_material(val, file, "seafloor.material");
                } else if (const SeafloorSpec* p = find_seafloor_param(k)) {
                    p->put(f, p->validated(val, file, "seafloor." + k), base_dir);
                } else {
                    throw InputError(file, "seafloor." + k,
                                     "unknown key; allowed: " + part_keys_text(seafloor_params()));
                }
            }
            scene.seafloor = f;
        } else if (section == "objects") {
            if (!body.is_array()) throw InputError(file, "objects", "expected an array of objects");
            for (size_t i = 0; i < body.size(); ++i)
                scene.objects.push_back(
                    parse_object(body[i], file, "objects[" + std::to_string(i) + "]", base_dir));
        } else {
            throw InputError(file, section,
                             "unknown key; allowed: " + table_sections_text() + ", seafloor, objects");
        }
    }
    if (!root.contains("seafloor")) scene.seafloor.reset(); // omit the seafloor key: no floor
    validate_scene(scene, file);
    return scene;
}

SceneDesc load_scene(const std::string& path, const GroupOverrides& group_overrides) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError(path, "", "scene file not found");
    if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "", "not a regular file");
    const auto size = std::filesystem::file_size(path, ec);
    if (!ec && size > kMaxSceneFileBytes)
        throw InputError(path, "",
                         "file is " + std::to_string(size) + " bytes; scene files may be at most " +
                             std::to_string(kMaxSceneFileBytes) + " bytes (meshes belong in mesh files)");
    const std::string text = read_file_bytes(path, kMaxSceneFileBytes);
    const std::string base = std::filesystem::absolute(path, ec).parent_path().string();
    return parse_scene(text, path, base, group_overrides);
}

json scene_to_json(const SceneDesc& s) {
    json j = json::object();
    for (auto& p : scene_params()) {
        if (!p.used_by(s.sonar.kind)) continue; // another kind's row: at its default, not written
        const size_t dot = p.key.find('.');
        j[p.key.substr(0, dot)][p.key.substr(dot + 1)] = p.get(s);
    }
    auto material = [](const Material& m) {
        json o;
        o[material_preset_param().key] = m.preset;
        for (auto& p : material_params()) o[p.key] = p.get(m);
        return o;
    };
    if (s.water.surface_height_m) j["water"]["surface_material"] = material(s.water.surface_material);
    auto part = [&](const auto& rows, const auto& x) {
        json o;
        for (auto& p : rows) {
            const json v = p.get(x);
            if (p.written && !v.is_null()) o[p.key] = v;
        }
        return o;
    };
    if (s.seafloor) {
        j["seafloor"] = part(seafloor_params(), *s.seafloor);
        j["seafloor"]["material"] = material(s.seafloor->material);
    }
    j["objects"] = json::array();
    for (auto& o : s.objects) {
        json jo = part(object_params(), o);
        jo["material"] = material(o.material);
        j["objects"].push_back(jo);
    }
    return j;
}

Pose parse_pose_text(const std::string& text, const std::string& origin) {
    if (std::count(text.begin(), text.end(), ',') != 5)
        throw InputError(
            origin, "", "\"" + text + "\": expected 6 comma-separated numbers x,y,z,roll,pitch,yaw (m, deg)");
    std::vector<double> v;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        size_t used = 0;
        double x = 0;
        try {
            x = std::stod(item, &used);
        } catch (...) {
            used = 0;
        }
        while (used < item.size() && std::isspace((unsigned char)item[used])) ++used;
        if (used == 0 || used != item.size() || !std::isfinite(x))
            throw InputError(origin, "",
                             "\"" + item +
                                 "\" is not a finite number; expected x,y,z,roll,pitch,yaw in m and deg");
        v.push_back(x);
    }
    if (v.size() != 6)
        throw InputError(origin, "",
                         "expected 6 comma-separated numbers x,y,z,roll,pitch,yaw (m, deg), got " +
                             std::to_string(v.size()));
    SceneDesc tmp;
    apply_setting(tmp, "sonar.position", json::array({v[0], v[1], v[2]}), origin);
    apply_setting(tmp, "sonar.orientation_deg", json::array({v[3], v[4], v[5]}), origin);
    return tmp.sonar.pose;
}

} // namespace sonarsim
