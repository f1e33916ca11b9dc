// The mesh file formats, in one table: extension -> reader. load_mesh dispatches by it; scene file errors,
// the viewer's file dialog, its drop handling and its help texts list the extensions from it.
#pragma once
#include "core/meshfile/trimesh.hpp"

#include <string>
#include <vector>

namespace sonarsim {

/// A mesh file's bytes, read in full, and its path (OpenMesh's OBJ reader finds material files beside it).
struct MeshFile {
    const std::string& path;
    const std::string& bytes;
};

struct MeshFormat {
    const char* extension; ///< lower case, with the dot: ".obj"
    const char* name;      ///< what it is, for help texts: "Wavefront OBJ"
    /// Reads the whole file as written or rejects it: throws mesh_io::Problem (mesh_tokens.hpp), which
    /// load_mesh reports as an InputError. Never repairs.
    TriMesh (*read)(const MeshFile& file);
};

/// Every format a scene's "mesh" may have, in the order they are listed to users.
const std::vector<MeshFormat>& mesh_formats();

/// The extension of `path`, lower case, with the dot (".obj"; "" when there is none).
std::string mesh_extension_of(const std::string& path);

/// The format of `path` by its extension (any case), or null.
const MeshFormat* find_mesh_format(const std::string& path);

/// The extensions of mesh_formats(), in order: {".obj", ".ply", ...}.
std::vector<std::string> mesh_extensions();

/// The extensions joined by `separator`: ".obj, .ply, .stl, .off".
std::string mesh_extensions_text(const std::string& separator = ", ");

} // namespace sonarsim
