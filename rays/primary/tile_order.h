// Purcell et al. 2002 §5.3's tiled rendering: "break the image into small tiles, each tile
// rendered to completion before proceeding to the next", so that a tile's working set fits the
// cache. camera.tile hands a method its camera rays tile by tile (a permutation of the batch:
// strategies/ray_batch.h inOrder) and puts its records back in the batch's order (inBatchOrder), so every check, image and comparison reads them as
// without tiles. Multipass renders a tile to completion when its batches are tiles
// (strategy.batch_rays = tile x tile).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "kernels/gpu_layout.h"
#include "strategies/ray_batch.h"
#include "core/error.h"

namespace rtbench {

// The pixels of a width x height image in tile order: tiles of tile x tile pixels row by row, each
// tile's pixels row by row. Empty for tile 0 (row by row: no permutation). Throws rtbench::Error
// when a side is not a multiple of the tile.
inline std::vector<std::uint32_t> tileOrder(unsigned width, unsigned height, unsigned tile) {
    if (tile == 0) return {};
    if (width % tile || height % tile)
        throw Error("camera.tile = " + std::to_string(tile) + ": the image (" + std::to_string(width) + " x " +
                    std::to_string(height) + ") is not a whole number of tiles");
    std::vector<std::uint32_t> order;
    order.reserve(std::size_t(width) * height);
    for (unsigned ty = 0; ty < height; ty += tile)
        for (unsigned tx = 0; tx < width; tx += tile)
            for (unsigned y = ty; y < ty + tile; ++y)
                for (unsigned x = tx; x < tx + tile; ++x) order.push_back(y * width + x);
    return order;
}

}  // namespace rtbench
