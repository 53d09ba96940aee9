#pragma once
// STL reader (ASCII and binary). Malformed files throw chutelab::InputError naming the file, the line
// (ASCII) or the byte offset (binary) and what is wrong.
#include <string>

#include "dem/walls/triangle_mesh.h"

namespace chutelab::dem {

// Reads an STL file; scale converts file units to metres (e.g. 1e-3 for millimetres).
TriangleMesh read_stl(const std::string& path, double scale = 1.0);
// Writes a binary STL (used by tests and to export meshes).
void write_stl_binary(const std::string& path, const TriangleMesh& mesh);

}  // namespace chutelab::dem
