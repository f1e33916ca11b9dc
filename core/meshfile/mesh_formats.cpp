#include "core/meshfile/mesh_formats.hpp"

#include "core/meshfile/mesh_readers.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace sonarsim {

const std::vector<MeshFormat>& mesh_formats() {
    static const std::vector<MeshFormat> table = {
        {".obj", "Wavefront OBJ", mesh_io::read_obj},
        {".ply", "PLY (ASCII or binary)", mesh_io::read_ply},
        {".stl", "STL (ASCII or binary)", mesh_io::read_stl},
        {".off", "OFF (ASCII)", mesh_io::read_off},
    };
    return table;
}

std::string mesh_extension_of(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

const MeshFormat* find_mesh_format(const std::string& path) {
    const std::string ext = mesh_extension_of(path);
    for (const MeshFormat& f : mesh_formats())
        if (ext == f.extension) return &f;
    return nullptr;
}

std::vector<std::string> mesh_extensions() {
    std::vector<std::string> out;
    for (const MeshFormat& f : mesh_formats()) out.emplace_back(f.extension);
    return out;
}

std::string mesh_extensions_text(const std::string& separator) {
    std::string out;
    for (const MeshFormat& f : mesh_formats()) out += (out.empty() ? "" : separator) + f.extension;
    return out;
}

} // namespace sonarsim
