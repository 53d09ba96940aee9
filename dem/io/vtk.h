#pragma once
// Legacy VTK (.vtk, ASCII POLYDATA) output that ParaView opens: particles as points with id, radius,
// velocity, angular velocity and force; walls (meshes and plane/cylinder patches) as polygons with the
// per-triangle force. Lengths in mm, as in every other file chutelab writes (the engine is SI inside);
// each array's name carries its unit and the file's title line says so.
#include <string>

#include "dem/world.h"

namespace chutelab::dem {

void write_vtk_particles(const std::string& path, const Particles& p);
void write_vtk_walls(const std::string& path, const std::vector<Wall>& walls);

}  // namespace chutelab::dem
