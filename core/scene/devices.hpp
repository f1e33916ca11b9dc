// Device presets: assets/devices/NAME.json, embedded in the library at build time (embed_files.cmake), so
// the executable, the tests and the Python module find them wherever they run.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace sonarsim {

/// One value of a preset: a parameter-table key's value, where it comes from and whether it is sure.
struct DeviceValue {
    std::string key; ///< a key of the parameter table, e.g. "sonar.beams" or "sensor.azimuth_window"
    nlohmann::json value;
    bool sure = false;  ///< stated or derived in a cited source (graded S or D), not a plausible default
    std::string source; ///< e.g. "device survey [ARIS-CORE] ..." (docs/devices.md explains the keys)
};

struct DevicePreset {
    std::string name;                ///< file name without .json, the value of sonar.device
    std::string title;               ///< e.g. "Sound Metrics ARIS Explorer 3000, high frequency"
    std::string file;                ///< "assets/devices/NAME.json", for error messages
    std::vector<DeviceValue> values; ///< in file order
    /// sonar.kind's value in the preset ("imaging" when it sets none).
    std::string kind() const {
        for (auto& v : values)
            if (v.key == "sonar.kind") return v.value.get<std::string>();
        return "imaging";
    }
};

/// Reads a preset from its text: `file` (".../NAME.json") names it in errors and gives its name. Every value
/// must be a row a preset may set (ValueSpec::preset_may_set) with a valid value; otherwise throws
/// InputError naming the file, the key and what presets may set.
DevicePreset parse_device_preset(const std::string& file, const std::string& text);

/// All presets, sorted by name, read once (parse_device_preset: a malformed one throws InputError).
const std::vector<DevicePreset>& device_presets();

/// The preset called `name`, or nullptr.
const DevicePreset* find_device(const std::string& name);

/// "none" followed by every preset's name: the values sonar.device allows (from the embedded files' names,
/// without reading them).
std::vector<std::string> device_choices();
/// "none" followed by the presets whose kind (DevicePreset::kind) is `kind_name` ("imaging", ...).
std::vector<std::string> device_choices(const std::string& kind_name);

} // namespace sonarsim
