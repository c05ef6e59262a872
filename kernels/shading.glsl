// Rays after the first hit: ONE source for the shading pass and the CPU (workloads/
// shading_reference.h compiles it as C++, as methods/shared_source_begin.h does a traversal), so
// every method, Embree and the exact reference trace the same float rays, bit for bit.
// Include after kernels/ray_math.glsl. The rule every secondary ray leaves a surface by is
// rtOffsetRay's, whatever the method.
#ifndef RT_SHADING_GLSL
#define RT_SHADING_GLSL

// Wachter & Binder 2019, "A Fast and Robust Method for Avoiding Self-Intersection" (Ray Tracing
// Gems, ch. 6): p moved off the surface along n by an integer offset of its float bits (a few
// hundred ulps of its own size, so it scales with the scene), or by a fixed small distance near
// the origin, where ulps are tiny. `n` has its largest component +-1 (rtScaledNormal): the offset
// is at most 256 ulps along the normal's main axis. Integer arithmetic on the bits and a product
// by a power of two: exact on every device.
vec3 rtOffsetRay(vec3 p, vec3 n) {
    const float originBand = 1.0f / 32.0f;
    const float floatScale = 1.0f / 65536.0f;
    const float intScale = 256.0f;
    precise vec3 moved;
    for (int a = 0; a < 3; ++a) {
        int offset = int(intScale * n[a]);  // truncation toward zero, as C++'s conversion
        float bits = intBitsToFloat(floatBitsToInt(p[a]) + (p[a] < 0.0f ? -offset : offset));
        precise float near = p[a] + floatScale * n[a];
        moved[a] = abs(p[a]) < originBand ? near : bits;
    }
    return moved;
}

// The triangle's normal (e1 x e2) divided by its largest absolute component, so that no square
// root is needed (Vulkan does not round one exactly); zero for a degenerate triangle.
vec3 rtScaledNormal(vec3 e1, vec3 e2) {
    vec3 n = rtCross(e1, e2);
    float m = max(abs(n.x), max(abs(n.y), abs(n.z)));
    if (m == 0.0f) return vec3(0.0f);
    return vec3(rtDivide(n.x, m), rtDivide(n.y, m), rtDivide(n.z, m));
}

// The point of triangle (v0, v1, v2) at barycentrics (u, v) of v1 and v2, as the triangle tests
// report them.
vec3 rtSurfacePoint(vec3 v0, vec3 v1, vec3 v2, float u, float v) {
    precise vec3 p = v0 + (v1 - v0) * u + (v2 - v0) * v;
    return p;
}

// A shadow ray (any hit) from the hit of a ray with direction `incoming` on triangle
// (v0, v1, v2) at (u, v) toward the point light `light`: it leaves the surface on the side the
// ray came from, by rtOffsetRay, and ends at the light (direction light - origin, tMax 1: the
// light itself at t = 1 is not an occluder). False, and no ray, when the light lies on the other
// side of the surface (or in its plane): the point is unlit without a test.
bool rtShadowRay(vec3 v0, vec3 v1, vec3 v2, float u, float v, vec3 incoming, vec3 light, RT_OUT(Ray) shadow) {
    precise vec3 e1 = v1 - v0;
    precise vec3 e2 = v2 - v0;
    vec3 n = rtScaledNormal(e1, e2);
    if (rtDot(n, incoming) > 0.0f) n = -n;  // toward the side the ray came from
    vec3 p = rtSurfacePoint(v0, v1, v2, u, v);
    precise vec3 toLight = light - p;
    if (!(rtDot(n, toLight) > 0.0f)) return false;
    vec3 origin = rtOffsetRay(p, n);
    precise vec3 direction = light - origin;
    shadow.originTMin = vec4(origin, 0.0f);
    shadow.directionTMax = vec4(direction, 1.0f);
    return true;
}

// Mirror reflection, Christen 2005 §5.2.1's iterations: the ray with direction `incoming` that hit
// triangle (v0, v1, v2) at (u, v) leaves on the side it came from, by rtOffsetRay, in the mirror
// direction d - 2 (d.n / n.n) n (n the scaled normal, so no square root; the length of d is kept),
// closest hit, as far as a camera ray. False, and no ray, for a triangle with no normal.
bool rtReflectRay(vec3 v0, vec3 v1, vec3 v2, float u, float v, vec3 incoming, RT_OUT(Ray) reflected) {
    precise vec3 e1 = v1 - v0;
    precise vec3 e2 = v2 - v0;
    vec3 n = rtScaledNormal(e1, e2);
    if (n.x == 0.0f && n.y == 0.0f && n.z == 0.0f) return false;
    if (rtDot(n, incoming) > 0.0f) n = -n;  // toward the side the ray came from
    vec3 origin = rtOffsetRay(rtSurfacePoint(v0, v1, v2, u, v), n);
    precise float scale = rtDivide(2.0f * rtDot(incoming, n), rtDot(n, n));
    precise vec3 direction = incoming - n * scale;
    reflected.originTMin = vec4(origin, 0.0f);
    reflected.directionTMax = vec4(direction, kNoHitT);
    return true;
}

#endif  // RT_SHADING_GLSL
