// Opens a layout header's declarations for C++ and GLSL alike (each structure's and strategy's
// <name>_layout.h): kernels/gpu_layout.h, then in C++ namespace rtbench::gpu with RTBENCH_CONST a
// constexpr uint, in GLSL a const uint. Close with kernels/layout_end.h, C++-only lines (the
// static_asserts of the structs' sizes) before it in #ifdef __cplusplus. No include guard: each
// layout header includes it once, inside its own guard.
#include "gpu_layout.h"

#ifdef __cplusplus
namespace rtbench::gpu {
#define RTBENCH_CONST constexpr uint
#else
#define RTBENCH_CONST const uint
#endif
