// The mesh readers behind the format table (mesh_formats.hpp), for the files of core/geometry only.
//
// OpenMesh accepts much that is broken: it reads a binary STL with a lying triangle count as ASCII and
// returns no faces, skips OBJ vertex lines it cannot read ("v nan 0 0"), drops faces with out-of-range
// indices, allocates whatever a PLY or OFF header or face valence claims (a 2e9-corner OFF face takes
// gigabytes and minutes), loops forever on some malformed PLY headers, and reads some PLY properties out of
// step (printing to std::cerr directly). So OBJ, PLY and STL files get a structural check first (counts
// against the bytes that are really there, every index in range, every coordinate a finite float, only
// property types OpenMesh converts), then OpenMesh parses them into a flat triangle array whose importer
// watches for faces it would drop; its log streams are routed to the load, never to the terminal. OFF files
// are read without OpenMesh. Nothing is "repaired": a file either loads as written or is rejected. Faces with
// fewer than 3 distinct corners have no area and are skipped (OpenMesh does the same); a face that repeats a
// corner of a larger polygon is an error.
//
// One file per format: mesh_obj.cpp, mesh_ply.cpp, mesh_stl.cpp (checks, then OpenMesh), mesh_off.cpp (a
// complete reader); openmesh_import.cpp runs OpenMesh on checked bytes. Every reader throws
// mesh_io::Problem (mesh_tokens.hpp).
#pragma once
#include "core/meshfile/mesh_formats.hpp"

#include <string>

namespace sonarsim::mesh_io {

/// What a check learnt: the faces the file declares (OpenMesh must see as many).
struct Expect {
    long long faces = -1;   ///< faces with at least 3 distinct corners (-1: not known)
    std::string hint;       ///< added when OpenMesh refuses the file
    bool all_faces = false; ///< `faces` counts every face, zero-area ones included
};

/// Structural checks of the bytes (counts against the bytes there, indices in range, finite coordinates).
Expect check_obj(const std::string& text);
Expect check_ply(const std::string& bytes);
Expect check_stl(const std::string& bytes);

/// OpenMesh's reader for `extension` (".obj", ".ply", ".stl") on a file that passed its check; the faces
/// it reads are compared with `expect`.
TriMesh read_with_openmesh(const MeshFile& file, const std::string& extension, const Expect& expect);

/// The readers of the format table.
TriMesh read_obj(const MeshFile& file);
TriMesh read_ply(const MeshFile& file);
TriMesh read_stl(const MeshFile& file);
TriMesh read_off(const MeshFile& file);

} // namespace sonarsim::mesh_io
