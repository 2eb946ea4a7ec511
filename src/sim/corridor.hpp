#pragma once
// Indoors: the path runs through a building's corridors and halls. Walls
// stand left and right of it at widths that change from stretch to stretch
// (a jog where they change), a ceiling covers it, and door niches, pillars
// and cabinets break the long walls up, as in the office and car-park scans
// where a corridor is nearly free along its axis.
#include <random>
#include <vector>

#include "hba/core/pose.hpp"
#include "hba/sim/terrain.hpp"
#include "mesh_builder.hpp"
#include "path_clearance.hpp"

namespace hba::sim {

// Appends the corridor around `path` to `mesh`. Walls that would stand
// closer to another stretch of the path than to their own (crossings,
// revisits) are left out.
void addCorridor(const std::vector<Pose>& path, const Terrain& terrain, const PathClearance& clearance,
                 std::mt19937_64& rng, MeshBuilder& mesh);

}  // namespace hba::sim
