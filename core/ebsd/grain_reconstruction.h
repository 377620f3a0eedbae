#pragma once
// Grains of an EBSD map, reconstructed from misorientation, and within each grain the clusters of
// points whose orientations agree to within a tolerance (what the renderer evaluates once).
//
// Grains: a flood fill over the grid's neighbours (4 on a square grid, 6 on a hexagonal one): two
// neighbours of one phase belong to one grain when their misorientation, the smallest rotation
// angle of g₁⁻¹·g₂·s over the Laue class's rotations s (core/ebsd/laue_rotations.h), is at most
// boundary_deg (10° by default: MTEX calcGrains' default threshold, the usual high-angle grain
// boundary criterion, Humphreys, J. Mater. Sci. 36 (2001) 3833–3854). Points of different phases
// or non-indexed are never joined. A point joining a grain takes the symmetric variant g·s
// nearest its neighbour's (the same crystal, so its optics are unchanged): inside a grain all
// orientations are then comparable without symmetry.
//
// Clusters: leader clustering in flood order. A point joins the cluster of the neighbour it was
// reached from, or one of its grain's most recent clusters, whose leader (first point) is within
// cluster_deg of it, else it starts a cluster: every point is within cluster_deg of its
// cluster's orientation, which is the leader's.
#include <cstdint>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "core/ebsd/orientation_map.h"

namespace pmsim {

struct GrainReconstructionOptions {
  double boundary_deg = 10.0;
  double cluster_deg = 0.5;
};

struct MapGrains {
  std::vector<std::int32_t> grain_of_point;    // −1: not in a grain (non-indexed or excluded)
  std::vector<std::int32_t> cluster_of_point;  // global cluster index, −1 as above
  std::vector<std::uint8_t> grain_phase;       // per grain: its points' phase id
  std::vector<std::int32_t> grain_first_cluster;  // per grain: its clusters are consecutive from here
  std::vector<std::int32_t> grain_clusters;       // per grain: how many
  std::vector<std::int64_t> grain_points;         // per grain: how many points
  std::vector<glm::quat> cluster_orientation;     // per cluster: crystal → section (its leader's)
  std::vector<std::int64_t> cluster_points;       // per cluster: how many points
};

// `orientation[i]`: point i's crystal-to-section rotation (unit quaternion, pmsim's frames);
// `in_grain[i]`: whether point i takes part (indexed, of a phase that forms grains);
// `symmetry[p]`: the rotations of phase id p (index 0 unused; empty: the identity only).
// Clusters are numbered grain by grain, grains in the order of their first point.
MapGrains reconstruct_grains(const OrientationMap& map, const std::vector<glm::quat>& orientation,
                             const std::vector<std::uint8_t>& in_grain,
                             const std::vector<std::vector<glm::dquat>>& symmetry,
                             const GrainReconstructionOptions& options = {});

// The neighbours of point i on the map's grid (4 on a square grid, 6 on a hexagonal one); returns
// how many it wrote to `out` (at most 6).
int grid_neighbours(const OrientationMap& map, std::size_t i, std::size_t out[6]);

}  // namespace pmsim
