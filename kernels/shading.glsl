// Rays after the first hit: ONE source for the shading pass and the CPU (rays/
// shading_reference.h compiles it as C++, as structures/shared_source_begin.h does a traversal), so
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

// v / |v|, the length and each quotient correctly rounded (rtSqrt, rtDivide).
vec3 rtNormalize(vec3 v) {
    float norm = rtSqrt(rtDot(v, v));
    return vec3(rtDivide(v.x, norm), rtDivide(v.y, norm), rtDivide(v.z, norm));
}

// The point of triangle (v0, v1, v2) at barycentrics (u, v) of v1 and v2, as the triangle tests
// report them.
vec3 rtSurfacePoint(vec3 v0, vec3 v1, vec3 v2, float u, float v) {
    precise vec3 p = v0 + (v1 - v0) * u + (v2 - v0) * v;
    return p;
}

// The scaled normal (rtScaledNormal) of triangle (v0, v1, v2) turned toward the side a ray with
// direction `incoming` came from: the side every secondary ray leaves on. Zero for a degenerate
// triangle.
vec3 rtFacingNormal(vec3 v0, vec3 v1, vec3 v2, vec3 incoming) {
    precise vec3 e1 = v1 - v0;
    precise vec3 e2 = v2 - v0;
    vec3 n = rtScaledNormal(e1, e2);
    return rtDot(n, incoming) > 0.0f ? -n : n;
}

// A shadow ray (any hit) from the hit of a ray with direction `incoming` on triangle
// (v0, v1, v2) at (u, v) toward the point light `light`: it leaves the surface on the side the
// ray came from, by rtOffsetRay, and ends at the light (direction light - origin, tMax 1: the
// light itself at t = 1 is not an occluder). False, and no ray, when the light lies on the other
// side of the surface (or in its plane): the point is unlit without a test.
bool rtShadowRay(vec3 v0, vec3 v1, vec3 v2, float u, float v, vec3 incoming, vec3 light, RT_OUT(Ray) shadow) {
    vec3 n = rtFacingNormal(v0, v1, v2, incoming);
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
    vec3 n = rtFacingNormal(v0, v1, v2, incoming);
    if (n.x == 0.0f && n.y == 0.0f && n.z == 0.0f) return false;
    vec3 origin = rtOffsetRay(rtSurfacePoint(v0, v1, v2, u, v), n);
    precise float scale = rtDivide(2.0f * rtDot(incoming, n), rtDot(n, n));
    precise vec3 direction = incoming - n * scale;
    reflected.originTMin = vec4(origin, 0.0f);
    reflected.directionTMax = vec4(direction, kNoHitT);
    return true;
}

// Refraction (Whitted 1980; pbrt-v3 §8.2) through a surface of index of refraction `ior` against
// 1 outside. The triangle's winding says which side is outside (e1 x e2 points out): a ray against
// it enters (eta = 1 / ior), one along it leaves (eta = ior). Snell's law on unit vectors, n the
// unit normal toward the incoming side and cos_i = -d.n: t = eta d + (eta cos_i - sqrt(k)) n with
// k = 1 - eta^2 (1 - cos_i^2); the ray leaves through the surface (rtOffsetRay to the far side),
// unit length, as far as a camera ray. `fresnel` gets the fraction reflected, Fresnel's equations
// for unpolarized light (pbrt-v3 §8.2.1 FrDielectric): the mean of r_par^2 and r_perp^2, with
// r_par = (cos_i - eta cos_t) / (cos_i + eta cos_t), r_perp = (eta cos_i - cos_t) / (eta cos_i + cos_t).
// Returns RT_TRANSMIT_NONE for a triangle with no normal, RT_TRANSMIT_TOTAL for total internal
// reflection (k < 0: no ray, fresnel 1), RT_TRANSMIT_RAY when `refracted` is made. Roots and
// quotients correctly rounded.
#define RT_TRANSMIT_NONE 0u
#define RT_TRANSMIT_TOTAL 1u
#define RT_TRANSMIT_RAY 2u
uint rtTransmit(vec3 v0, vec3 v1, vec3 v2, float u, float v, vec3 incoming, float ior, RT_OUT(Ray) refracted,
                RT_OUT(float) fresnel) {
    precise vec3 e1 = v1 - v0;
    precise vec3 e2 = v2 - v0;
    fresnel = 1.0f;
    vec3 outward = rtScaledNormal(e1, e2);
    if (outward.x == 0.0f && outward.y == 0.0f && outward.z == 0.0f) return RT_TRANSMIT_NONE;
    bool entering = rtDot(outward, incoming) < 0.0f;
    vec3 facing = entering ? outward : -outward;  // toward the side the ray came from
    vec3 n = rtNormalize(facing);
    vec3 d = rtNormalize(incoming);
    float eta = entering ? rtDivide(1.0f, ior) : ior;
    precise float cosI = -rtDot(d, n);
    precise float k = 1.0f - eta * eta * (1.0f - cosI * cosI);
    if (k < 0.0f) return RT_TRANSMIT_TOTAL;
    float cosT = rtSqrt(k);
    precise vec3 t = d * eta + n * (eta * cosI - cosT);
    refracted.originTMin = vec4(rtOffsetRay(rtSurfacePoint(v0, v1, v2, u, v), -facing), 0.0f);
    refracted.directionTMax = vec4(t, kNoHitT);
    precise float parallel = rtDivide(cosI - eta * cosT, cosI + eta * cosT);
    precise float perpendicular = rtDivide(eta * cosI - cosT, eta * cosI + cosT);
    precise float reflected = 0.5f * (parallel * parallel + perpendicular * perpendicular);
    fresnel = reflected;
    return RT_TRANSMIT_RAY;
}

// Every surface glass (rays.type = refraction): the refracted ray, or past the critical angle
// rtReflectRay's mirror ray. False for a triangle with no normal.
bool rtRefractRay(vec3 v0, vec3 v1, vec3 v2, float u, float v, vec3 incoming, float ior, RT_OUT(Ray) refracted) {
    float fresnel;
    uint transmitted = rtTransmit(v0, v1, v2, u, v, incoming, ior, refracted, fresnel);
    if (transmitted == RT_TRANSMIT_TOTAL) return rtReflectRay(v0, v1, v2, u, v, incoming, refracted);
    return transmitted == RT_TRANSMIT_RAY;
}

// ---- Whitted ray tracing (Whitted 1980; Purcell et al. 2002 Fig. 3c): by the surface's material,
// each hit makes a shadow ray per light (rtShadowRay) and its reflection and refraction, each ray
// carrying the weight its radiance adds to the pixel with, instead of a recursion (Christen 2005
// §5.2.1's iteration buffer R) ----

// Of a ray's weight, the part its hit's direct light adds with (what its shadow rays carry): all of it on a
// diffuse surface, 1 - r on a mirror of reflectance r (Christen 2005 eq. 5.1's M_j (1 - r_j)),
// none on glass.
float rtDiffusePart(Material m) {
    if (m.kind.x == kMaterialDiffuse) return 1.0f;
    if (m.kind.x == kMaterialMirror) {
        precise float rest = 1.0f - m.optics.x;
        return rest;
    }
    return 0.0f;
}

// Slot 0: the reflection (a mirror: weight times its reflectance; glass: times Fresnel's fraction,
// all of it past the critical angle); slot 1: glass's refraction (weight times 1 - Fresnel's).
// A diffuse surface makes neither. False: no ray.
bool rtSpecularRay(Material m, vec3 v0, vec3 v1, vec3 v2, float u, float v, vec3 incoming, uint slot, float weight,
                   RT_OUT(Ray) made, RT_OUT(float) madeWeight) {
    madeWeight = 0.0f;
    if (m.kind.x == kMaterialMirror) {
        precise float w = weight * m.optics.x;
        madeWeight = w;
        return slot == 0u && rtReflectRay(v0, v1, v2, u, v, incoming, made);
    }
    if (m.kind.x != kMaterialGlass) return false;
    Ray refracted;
    float fresnel;
    uint transmitted = rtTransmit(v0, v1, v2, u, v, incoming, m.optics.y, refracted, fresnel);
    if (transmitted == RT_TRANSMIT_NONE) return false;
    if (slot == 1u) {
        precise float w = weight * (1.0f - fresnel);
        madeWeight = w;
        if (transmitted != RT_TRANSMIT_RAY) return false;
        made = refracted;
        return true;
    }
    precise float w = weight * fresnel;
    madeWeight = w;
    return rtReflectRay(v0, v1, v2, u, v, incoming, made);
}

// ---- random numbers and directions for diffuse rays (path tracing, ambient occlusion) ----

// Jarzynski & Olano 2020, "Hash Functions for GPU Rendering" (JCGT 9(3)): PCG's state step and
// output permutation as a 32-bit hash. Integer arithmetic: the same bits on every device.
uint rtPcgHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// A counter-based random number in [0, 1): the chained hash of key = (seed, path, bounce) and
// draw, its top 24 bits times 2^-24 (exact). No state is carried from ray to ray, so the CPU
// and every device draw the same number for the same ray.
float rtRandom(uvec3 key, uint draw) {
    uint h = rtPcgHash(key.x);
    h = rtPcgHash(h + key.y);
    h = rtPcgHash(h + key.z);
    h = rtPcgHash(h + draw);
    return float(h >> 8u) * (1.0f / 16777216.0f);
}

// Duff et al. 2017, "Building an Orthonormal Basis, Revisited" (JCGT 6(1)), listing 3: two unit
// tangents t, b of the unit vector n, with (t, b, n) right-handed. No square root.
void rtBasis(vec3 n, RT_OUT(vec3) t, RT_OUT(vec3) b) {
    float side = n.z >= 0.0f ? 1.0f : -1.0f;
    precise float a = rtDivide(-1.0f, side + n.z);
    precise float c = n.x * n.y * a;
    precise vec3 tangent = vec3(1.0f + side * n.x * n.x * a, side * c, -side * n.x);
    precise vec3 bitangent = vec3(c, side + n.y * n.y * a, -n.y);
    t = tangent;
    b = bitangent;
}

// A cosine-weighted direction about the unit vector n (Malley's method, pbrt-v3 §13.6.3): a point
// uniform in the unit disk, by rejection from the square (no sine or cosine: Vulkan rounds
// neither exactly), lifted to the hemisphere, z = sqrt(1 - x^2 - y^2). Up to 16 tries, each two
// draws of `key`; (0, 0) after them (straight along n; a chance of 2^-35). Unit length up to rounding.
vec3 rtCosineDirection(vec3 n, uvec3 key) {
    float x = 0.0f;
    float y = 0.0f;
    for (uint attempt = 0u; attempt < 16u; ++attempt) {
        precise float cx = 2.0f * rtRandom(key, 2u * attempt) - 1.0f;
        precise float cy = 2.0f * rtRandom(key, 2u * attempt + 1u) - 1.0f;
        precise float r2 = cx * cx + cy * cy;
        if (r2 < 1.0f) {
            x = cx;
            y = cy;
            break;
        }
    }
    precise float z2 = 1.0f - (x * x + y * y);
    float z = rtSqrt(z2);
    vec3 t;
    vec3 b;
    rtBasis(n, t, b);
    precise vec3 d = t * x + b * y + n * z;
    return d;
}

// A diffuse ray: from the hit of a ray with direction `incoming` on triangle (v0, v1, v2) at
// (u, v), it leaves on the side the ray came from, by rtOffsetRay, in a cosine-weighted direction
// about the unit normal (random key `key`), up to tMax (kNoHitT: a path-tracing bounce; a radius:
// an ambient-occlusion ray). False, and no ray, for a triangle with no normal.
bool rtDiffuseRay(vec3 v0, vec3 v1, vec3 v2, float u, float v, vec3 incoming, uvec3 key, float tMax,
                  RT_OUT(Ray) diffuse) {
    vec3 n = rtFacingNormal(v0, v1, v2, incoming);
    if (n.x == 0.0f && n.y == 0.0f && n.z == 0.0f) return false;
    vec3 origin = rtOffsetRay(rtSurfacePoint(v0, v1, v2, u, v), n);
    diffuse.originTMin = vec4(origin, 0.0f);
    diffuse.directionTMax = vec4(rtCosineDirection(rtNormalize(n), key), tMax);
    return true;
}

// ---- the shading pass: one rule for the kernel (kernels/shading.comp) and the CPU ----

// Ray `slot` (of params.pass.z) made by a hit at (u, v) of triangle (v0, v1, v2) of material `m`,
// of the ray with direction `incoming` and weight `weight` on path `path`, by the rule
// params.pass.y (kShade*); `light` is the slot's light (kShadeShadow). A diffuse ray's random key
// is (seed, path * fan-out + slot, bounce): the path the new ray starts. `madeWeight` gets the new
// ray's weight: the parent's, times what the rule passes on (shadow and specular rays). False: no
// ray, also for a weight below the smallest normal float (2^-126): it would add nothing, and a
// device may flush such a product to 0 where the CPU keeps it, so the cut is the same everywhere.
bool rtShade(ShadingParams params, Material m, vec3 light, vec3 v0, vec3 v1, vec3 v2, float u, float v, vec3 incoming,
             uint path, uint slot, float weight, RT_OUT(Ray) made, RT_OUT(float) madeWeight) {
    uint rule = params.pass.y;
    bool ok;
    madeWeight = weight;
    if (rule == kShadeShadow) {
        precise float w = weight * rtDiffusePart(m);
        madeWeight = w;
        ok = rtShadowRay(v0, v1, v2, u, v, incoming, light, made);
    } else if (rule == kShadeMirror) {
        ok = rtReflectRay(v0, v1, v2, u, v, incoming, made);
    } else if (rule == kShadeRefract) {
        ok = rtRefractRay(v0, v1, v2, u, v, incoming, params.values.x, made);
    } else if (rule == kShadeSpecular) {
        ok = rtSpecularRay(m, v0, v1, v2, u, v, incoming, slot, weight, made, madeWeight);
    } else {
        uvec3 key = uvec3(params.seed.x, path * params.pass.z + slot, params.pass.w);
        ok = rtDiffuseRay(v0, v1, v2, u, v, incoming, key, params.values.x, made);
    }
    return ok && madeWeight >= 1.17549435e-38f;
}

#endif  // RT_SHADING_GLSL
