// `sonarsim devices`: the device presets (assets/devices/*.json) with their main figures, as a text table or
// as Markdown (--markdown, the table in docs/devices.md); `sonarsim devices NAME` lists one preset's values
// with sources.
#include "commands.hpp"

#include "core/scene/devices.hpp"
#include "core/scene/params.hpp"
#include "core/base/errors.hpp"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <iterator>
#include <memory>
#include <sstream>
#include <vector>

namespace sonarsim::app {

namespace {

/// The preset's value of `key`, or nullptr.
const DeviceValue* value_of(const DevicePreset& p, const std::string& key) {
    for (auto& v : p.values)
        if (v.key == key) return &v;
    return nullptr;
}

/// A number as short as it reads: 3000, 30.25, 0.578.
std::string number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", x);
    return buf;
}

/// The value as text (numbers scaled by `scale`), "?" appended when it is unsure, "-" when the preset has
/// none.
std::string show(const DevicePreset& p, const std::string& key, const std::string& unit = "",
                 double scale = 1) {
    const DeviceValue* v = value_of(p, key);
    if (!v) return "-";
    std::string s;
    if (v->value.is_number())
        s = number(v->value.get<double>() * scale) + unit;
    else if (v->value.is_string())
        s = v->value.get<std::string>();
    else
        s = v->value.dump();
    return v->sure ? s : s + "?";
}

struct Row {
    std::string name, title, frequency, beams, fov, beamwidth, window, resolution;
};

Row row_of(const DevicePreset& p) {
    Row r;
    r.name = p.name;
    r.title = p.title;
    r.frequency = show(p, "sonar.frequency_khz", " kHz");
    // A side-scan's two beams and a scanning head's one, each with its kind's figure.
    if (p.kind() == "sidescan")
        r.beams = "2 side-scan, " + show(p, "sidescan.depression_deg", "°") + " down";
    else if (p.kind() == "scanning")
        r.beams = "1 scanning, " + show(p, "scanning.step_deg", "°") + " steps";
    else
        r.beams = show(p, "sonar.beams");
    r.fov = show(p, "sonar.azimuth_fov_deg", "°") + " × " + show(p, "sonar.elevation_fov_deg", "°");
    r.beamwidth = show(p, "sensor.azimuth_beamwidth_deg", "°");
    const DeviceValue* beamformer = value_of(p, "sensor.beamformer");
    if (beamformer && beamformer->value == "array") r.beamwidth += " (array)";
    r.window = show(p, "sonar.range_min_m") + "–" + show(p, "sonar.range_max_m", " m");
    r.resolution = show(p, "sensor.range_resolution_m", " mm", 1000);
    const DeviceValue* pulse = value_of(p, "sensor.pulse");
    if (pulse && pulse->value == "chirp") r.resolution += " (chirp)";
    return r;
}

/// Display width of UTF-8 text: code points (the table's characters are all one column wide).
size_t width(const std::string& s) {
    size_t n = 0;
    for (unsigned char c : s) n += (c & 0xC0) != 0x80;
    return n;
}

const char* const kHeader[] = {"name",         "title",           "frequency",
                               "beams",        "HFOV × VFOV",     "azimuth beamwidth",
                               "range window", "range resolution"};
constexpr char kUnsureNote[] =
    "? = unsure: a value the device survey grades U (docs/devices.md), or a plausible default. Every "
    "value's source is in assets/devices/NAME.json (sonarsim devices NAME).";

void print_markdown(const std::vector<Row>& rows) {
    std::ostringstream out;
    out << "|";
    for (const char* h : kHeader) out << " " << h << " |";
    out << "\n|";
    for (size_t i = 0; i < std::size(kHeader); ++i) out << "---|";
    out << "\n";
    for (auto& r : rows)
        out << "| `" << r.name << "` | " << r.title << " | " << r.frequency << " | " << r.beams << " | "
            << r.fov << " | " << r.beamwidth << " | " << r.window << " | " << r.resolution << " |\n";
    out << "\n" << kUnsureNote << "\n";
    std::cout << out.str();
}

void print_text(const std::vector<Row>& rows) {
    std::vector<std::vector<std::string>> cells;
    cells.push_back(std::vector<std::string>(std::begin(kHeader), std::end(kHeader)));
    for (auto& r : rows)
        cells.push_back({r.name, r.title, r.frequency, r.beams, r.fov, r.beamwidth, r.window, r.resolution});
    std::vector<size_t> w(std::size(kHeader), 0);
    for (auto& c : cells)
        for (size_t i = 0; i < c.size(); ++i) w[i] = std::max(w[i], width(c[i]));
    std::ostringstream out;
    for (auto& c : cells) {
        for (size_t i = 0; i < c.size(); ++i) {
            out << c[i];
            if (i + 1 < c.size()) out << std::string(w[i] - width(c[i]) + 2, ' ');
        }
        out << "\n";
    }
    out << "\n" << kUnsureNote << "\n";
    std::cout << out.str();
}

/// One preset: every value with its confidence and source.
void print_preset(const DevicePreset& p) {
    std::ostringstream out;
    out << p.name << ": " << p.title << " (" << p.file << ")\n"
        << "sonar.device=" << p.name
        << " sets these values (* only with sensor.model=device). Named in a scene file, the file's own keys "
           "override them; named by --set (or the viewer's Device menu), they override the file's. Every "
           "override is listed in the metadata (device_overrides) and, by the command line, said once on "
           "stderr.\n";
    size_t wk = 0, wv = 0;
    for (auto& v : p.values) {
        wk = std::max(wk, v.key.size());
        wv = std::max(wv, v.value.dump().size());
    }
    for (auto& v : p.values) {
        const std::string value = v.value.dump();
        const ParamSpec* spec = find_param(v.key);
        const bool effect = spec && !spec->ideal_value.is_null();
        out << "  " << v.key << std::string(wk - v.key.size() + 2, ' ') << value
            << std::string(wv - value.size() + 2, ' ') << (effect ? "* " : "  ")
            << (v.sure ? "sure    " : "unsure  ") << v.source << "\n";
    }
    std::cout << out.str();
}

} // namespace

void register_devices(CLI::App& app, std::function<int()>& run) {
    CLI::App* cmd = app.add_subcommand(
        "devices",
        "List the device presets (sonar.device) with their main figures; NAME: one preset's values");
    auto markdown = std::make_shared<bool>(false);
    auto name = std::make_shared<std::string>();
    cmd->add_flag("--markdown", *markdown, "Print a Markdown table (as in docs/devices.md)");
    cmd->add_option("name", *name, "A preset: print each of its values with its source");
    cmd->callback([&run, markdown, name] {
        run = [markdown, name] {
            if (!name->empty()) {
                const DevicePreset* p = find_device(*name);
                if (!p) {
                    std::string known;
                    for (auto& q : device_presets()) known += (known.empty() ? "" : ", ") + q.name;
                    throw InputError("devices", "",
                                     "no device preset '" + *name + "' (known: " + known + ")");
                }
                print_preset(*p);
                return 0;
            }
            std::vector<Row> rows;
            for (auto& p : device_presets()) rows.push_back(row_of(p));
            if (*markdown)
                print_markdown(rows);
            else
                print_text(rows);
            return 0;
        };
    });
}

} // namespace sonarsim::app
