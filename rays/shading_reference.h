// The shading source (kernels/shading.glsl) compiled as C++, as a structure's traversal is
// (structures/shared_kernels.h): what makes the rays after the first hit on the CPU.
#pragma once
#include "structures/shared_kernels.h"

namespace rtbench {

namespace shadingref {
using namespace glm;
using namespace rtbench::gpu;
#include "structures/shared_source_begin.h"
struct ShadingKernels : KernelConstants {
#include "../kernels/ray_math.glsl"
#include "../kernels/shading.glsl"
};
#include "structures/shared_source_end.h"
}  // namespace shadingref

}  // namespace rtbench
