// A structure whose CPU reference is its kernels' own source compiled as C++ (methods/
// shared_kernels.h; the macros that open and close it: shared_source_begin.h and _end.h).
//
// Use: in a namespace with `using namespace glm; using namespace rtbench::gpu;`,
//   #include "structures/shared_source_begin.h"
//   struct XKernels : KernelConstants { <buffers as pointers>; XParams params;
//   #include "../../kernels/ray_math.glsl"  ... the structure's .glsl files ... };
//   #include "structures/shared_source_end.h"
// in structures/<x>/<x>_reference.h, list XKernels in structures/structure_kernels.h, and derive the
// structure from SharedSourceStructure<XKernels>.
#pragma once
#include <cstdint>
#include <cstring>
#include <vector>

#include "structures/shared_kernels.h"
#include "structures/structure.h"

namespace rtbench {

template <class Kernels>
class SharedSourceStructure : public Structure {
public:
    // The shared source over this structure's data.
    virtual Kernels kernels() const = 0;
    // ... with the constants every structure shares (the triangle test, the vertex lattice).
    Kernels configured() const {
        Kernels k = kernels();
        k.triangleTest = triangleTest();
        k.division = division();
        k.setLattice(vertexLattice());
        return k;
    }

    std::vector<std::uint8_t> params() const override {
        const auto p = kernels().params;
        std::vector<std::uint8_t> bytes(sizeof p);
        std::memcpy(bytes.data(), &p, sizeof p);
        return bytes;
    }
    StructureKernels cpuKernels() const override { return configured(); }
};

}  // namespace rtbench
