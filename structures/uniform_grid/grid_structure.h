// The uniform grid as a method's structure (structures/structure.h): Purcell et al. 2002's grid at a
// chosen resolution rule, its keys and columns.
#pragma once
#include <array>

#include "structures/structure.h"

namespace rtbench {

const StructureType& gridStructureType();

struct UniformGrid;
// A built grid as a Structure (tests run strategies on grids they build themselves).
std::unique_ptr<Structure> gridStructure(UniformGrid grid);

// The grid's buffers (Purcell Fig. 4): cell offsets, triangle list, triangle vertices (packed
// when the lattice has bits).
std::vector<BufferSize> gridBufferSizes(const std::array<unsigned, 3>& resolution, std::uint64_t references,
                                        std::uint64_t triangles, const VertexLattice& lattice);

}  // namespace rtbench
