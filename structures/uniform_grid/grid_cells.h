// The cells of a uniform grid: which voxels each triangle meets (pass 1, on every core; a large
// triangle row by row, voxel_row.h), and the per-voxel triangle lists in Purcell et al. 2002
// Fig. 4's layout (pass 2, a counting sort).
#pragma once
#include "uniform_grid.h"

namespace rtbench {

// Fills grid.cellOffsets, grid.triangleList and grid.stats' counts from grid.params and
// grid.triangles. A voxel lists every triangle that meets its closed box widened by voxelMargin,
// as CGAL's exact test decides (a float filter first, where it is sure), in ascending id order,
// whatever the scheduling. Throws rtbench::Error when the lists would overflow their 32-bit offsets.
void fillCellLists(UniformGrid& grid, float voxelMargin);

}  // namespace rtbench
