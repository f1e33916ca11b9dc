// Files compiled into the library (core/base/embed_files.cmake writes, per folder of assets, an array of
// {file name, text} pairs and its count): the presets read from them, by name, and their names alone.
#pragma once
#include <algorithm>
#include <string>
#include <vector>

namespace sonarsim {

/// One folder's embedded files: `files[i]` = {file name, text}, `count` of them.
struct EmbeddedFiles {
    const char* const (*files)[2];
    int count;

    /// The files' names without `extension` (".json"), sorted; files of other extensions are left out.
    std::vector<std::string> names(const std::string& extension) const {
        std::vector<std::string> out;
        for (int i = 0; i < count; ++i) {
            const std::string file = files[i][0];
            if (file.size() > extension.size() &&
                file.compare(file.size() - extension.size(), extension.size(), extension) == 0)
                out.push_back(file.substr(0, file.size() - extension.size()));
        }
        std::sort(out.begin(), out.end());
        return out;
    }

    /// Every file parsed by `parse(path, text)` (path: `folder` + "/" + file name), sorted by their `name`.
    template <class Preset, class Parse>
    std::vector<Preset> parse_all(const std::string& folder, Parse parse) const {
        std::vector<Preset> out;
        for (int i = 0; i < count; ++i) out.push_back(parse(folder + "/" + files[i][0], files[i][1]));
        std::sort(out.begin(), out.end(), [](const Preset& a, const Preset& b) { return a.name < b.name; });
        return out;
    }
};

/// A preset file's name: the file's name without its folder and `extension` (".json").
inline std::string preset_name_of(const std::string& file, const std::string& extension) {
    const std::string base = file.substr(file.find_last_of('/') + 1);
    return base.size() > extension.size() &&
                   base.compare(base.size() - extension.size(), extension.size(), extension) == 0
               ? base.substr(0, base.size() - extension.size())
               : base;
}

/// The preset called `name` in `presets`, or null.
template <class Preset>
const Preset* find_by_name(const std::vector<Preset>& presets, const std::string& name) {
    for (const Preset& p : presets)
        if (p.name == name) return &p;
    return nullptr;
}

} // namespace sonarsim
