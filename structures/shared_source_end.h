// Closes what structures/shared_source_begin.h opened.
#undef precise
#undef RT_ON_INNER
#undef RT_ON_OUTER
#undef RT_INOUT
#undef RT_OUT
#pragma GCC diagnostic pop
// The shared sources' include guards, so that the next structure's kernels include them again
// (structures/structure_kernels.h holds every structure's in one translation unit).
#undef RT_RAY_MATH_GLSL
#undef RT_TRAVERSAL_COMMON_GLSL
#undef RT_MULTIPASS_INTERSECT_GLSL
#undef RT_SHADING_GLSL
