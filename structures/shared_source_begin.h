// Opens a structure's shared GLSL as C++ (see structures/shared_kernels.h); close with
// structures/shared_source_end.h. No include guard: it is meant to be included once per structure.
#define RT_OUT(T) T&
#define RT_INOUT(T) T&
#define RT_ON_OUTER() \
    if (loopLog) loopLog->push_back(0);
#define RT_ON_INNER() \
    if (loopLog) ++loopLog->back();
#define precise
// Some structures' GLSL functions leave a parameter of the common signature unused.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
