// Ray arithmetic shared by every structure's traversal: ONE source for the GPU kernels and the
// CPU references (each includes it inside a C++ struct, see methods/grid/grid_reference.h), so
// both run the very same arithmetic, operation by operation.
// Rules that keep the two bit-identical: float literals carry an `f`; every division through
// rtDivide; dot/cross written out (the driver's built-ins may fuse to FMA); results marked
// `precise` (no contraction in SPIR-V; the C++ side builds with -ffp-contract=off). Vulkan makes
// float add, subtract, multiply, conversions, min/max/floor exact; division it does not.
// Algorithms: slab test (Kay & Kajiya 1986); ray-triangle test of Moller & Trumbore 1997.
#ifndef RT_RAY_MATH_GLSL
#define RT_RAY_MATH_GLSL

// a / b correctly rounded, as IEEE float division on the CPU gives it. Vulkan allows OpFDiv an
// error of 2.5 ULP, and NVIDIA's driver uses it: on an H200 about 3% of the bunny's rays came back
// with other bits than the CPU's. The double quotient is within 2.5 double ULP (2^-50.7 relative)
// of a / b, while a quotient of two floats lies at least about 2^-49 (relative) from any midpoint
// between floats, so rounding it to float gives the correctly rounded float quotient (double
// rounding is innocuous for division when 53 >= 2 * 24 + 2; Figueroa 1995). Needs shaderFloat64.
float rtDivide(float a, float b) {
    precise double q = double(a) / double(b);
    return float(q);
}

float rtDot(vec3 a, vec3 b) {
    precise float r = a.x * b.x + a.y * b.y + a.z * b.z;
    return r;
}

vec3 rtCross(vec3 a, vec3 b) {
    precise vec3 r = vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
    return r;
}

// Per-axis reciprocal of the direction; zero components are never used through it.
vec3 rtInverseDirection(vec3 d) {
    precise vec3 r = vec3(d.x != 0.0f ? rtDivide(1.0f, d.x) : 0.0f, d.y != 0.0f ? rtDivide(1.0f, d.y) : 0.0f,
                          d.z != 0.0f ? rtDivide(1.0f, d.z) : 0.0f);
    return r;
}

// Clips [tMin, tMax] of the ray to the box; false when it misses. Axis-parallel rays (a zero
// direction component) are inside that slab iff the origin is within it (closed interval).
// One axis of the slab test: narrows [tEnter, tLeave]; false when the ray misses the slab.
bool rtClipSlab(float o, float d, float invD, float lo, float hi, RT_INOUT(float) tEnter, RT_INOUT(float) tLeave) {
    if (d == 0.0f) return !(o < lo || o > hi);
    precise float t0 = (lo - o) * invD;
    precise float t1 = (hi - o) * invD;
    tEnter = max(tEnter, min(t0, t1));
    tLeave = min(tLeave, max(t0, t1));
    return true;
}

// The axes are written out rather than looped over: a device may count loop iterations against a
// limit (llvmpipe: 65,535 per invocation, see methods/branching/lane_counts.h), and the BVH clips
// two boxes per node.
bool rtClipToBox(vec3 o, vec3 d, vec3 invD, float tMin, float tMax, vec3 boxMin, vec3 boxMax,
                 RT_OUT(float) tEnter, RT_OUT(float) tLeave) {
    tEnter = tMin;
    tLeave = tMax;
    if (!rtClipSlab(o.x, d.x, invD.x, boxMin.x, boxMax.x, tEnter, tLeave)) return false;
    if (!rtClipSlab(o.y, d.y, invD.y, boxMin.y, boxMax.y, tEnter, tLeave)) return false;
    if (!rtClipSlab(o.z, d.z, invD.z, boxMin.z, boxMax.z, tEnter, tLeave)) return false;
    return tEnter <= tLeave;
}

// Moller-Trumbore. Updates (tBest, u, v) when the triangle is hit in [tMin, tBest).
// A degenerate (zero-area) triangle has det == 0 for every ray and is never hit.
bool rtIntersectTriangle(vec3 o, vec3 d, float tMin, vec3 v0, vec3 v1, vec3 v2,
                         RT_INOUT(float) tBest, RT_INOUT(float) uBest, RT_INOUT(float) vBest) {
    precise vec3 e1 = v1 - v0;
    precise vec3 e2 = v2 - v0;
    precise vec3 p = rtCross(d, e2);
    precise float det = rtDot(e1, p);
    if (det == 0.0f) return false;
    precise float invDet = rtDivide(1.0f, det);
    precise vec3 s = o - v0;
    precise float u = rtDot(s, p) * invDet;
    if (u < 0.0f || u > 1.0f) return false;
    precise vec3 q = rtCross(s, e1);
    precise float v = rtDot(d, q) * invDet;
    if (v < 0.0f || u + v > 1.0f) return false;
    precise float t = rtDot(e2, q) * invDet;
    if (t < tMin || t >= tBest) return false;
    tBest = t;
    uBest = u;
    vBest = v;
    return true;
}

#endif  // RT_RAY_MATH_GLSL
