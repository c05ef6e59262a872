// Ray arithmetic shared by every structure's traversal: ONE source for the GPU kernels and the
// CPU references (each includes it inside a C++ struct, see structures/uniform_grid/grid_reference.h), so
// both run the very same arithmetic, operation by operation.
// Rules that keep the two bit-identical: float literals carry an `f`; every division through
// rtDivide; dot/cross written out (the driver's built-ins may fuse to FMA); results marked
// `precise` (no contraction in SPIR-V; the C++ side builds with -ffp-contract=off). Vulkan makes
// float add, subtract, multiply, conversions, min/max/floor exact; division it does not.
// Algorithms: slab test (Kay & Kajiya 1986); ray-triangle tests of Moller & Trumbore 1997 and
// the watertight test of Woop, Benthin & Wald 2013, chosen by the specialization constant
// `triangleTest` (intersection.test).
#ifndef RT_RAY_MATH_GLSL
#define RT_RAY_MATH_GLSL

// a / b correctly rounded through a double quotient (intersection.division = "double"). Vulkan
// allows OpFDiv an error of 2.5 ULP, and NVIDIA's driver uses it: on an H200 about 3% of the
// bunny's rays came back with other bits than the CPU's. The double quotient is within 2.5 double
// ULP (2^-50.7 relative) of a / b, while a quotient of two floats lies at least about 2^-49
// (relative) from any midpoint between floats, so rounding it to float gives the correctly rounded
// float quotient (double rounding is innocuous for division when 53 >= 2 * 24 + 2; Figueroa 1995).
// Needs shaderFloat64. A quotient at or past FLT_MAX + half an ulp (0x7f7fffff + 2^103) overflows
// to infinity, as IEEE's float division does (and as converting it would not: undefined in C++).
// A zero divisor is written out (IEEE: +-infinity, NaN for 0/0 and NaN/0), since C++ leaves x / 0
// undefined and the CPU reference runs this source; no kernel divides by zero (callers test first).
float rtDivideByDouble(float a, float b) {
    if (b == 0.0f) {
        if (a == 0.0f || a != a) return uintBitsToFloat(0x7fc00000u);  // NaN
        return uintBitsToFloat(((floatBitsToUint(a) ^ floatBitsToUint(b)) & 0x80000000u) | 0x7f800000u);
    }
    precise double q = double(a) / double(b);
    precise double overflow = double(uintBitsToFloat(0x7f7fffffu)) + double(uintBitsToFloat(0x73000000u));
    if (abs(q) >= overflow) return uintBitsToFloat(q > 0.0 ? 0x7f800000u : 0xff800000u);  // +-infinity
    return float(q);
}

// Q = round(A 2^s / B) for 24-bit significands A and B (2^23 <= A, B < 2^24) and s = 23 when
// A >= B, else 24, so that 2^23 <= Q < 2^24 (never 2^24: A 2^s / B <= 2^24 - 1 either way), from
// a guess within 127 of it and `reciprocal`, 2^23 / B within a few ULP, in straight-line 32-bit
// integer arithmetic. The guess's remainder A 2^s - guess B is below 2^31 in magnitude, so its
// low 32 bits (wrapping products) are it, exactly; remainder * reciprocal * 2^-23 is within 1/2
// of remainder / B (off by 2^-14 at most), so rounding it errs by one at most, which the last step
// corrects: Q is right iff -B < 2 (A 2^s - Q B) < B. Neither side is ever equal (A 2^(s+1) is a
// multiple of 2^24, a larger power of two than divides B), so a quotient never sits on a
// midpoint and there is no tie to break.
uint rtQuotientSignificand(uint A, uint B, uint s, uint guess, float reciprocal) {
    int remainder = int((A << s) - guess * B);
    precise float estimate = float(remainder) * reciprocal * uintBitsToFloat(0x34000000u);  // * 2^-23
    int correction = int(floor(estimate + 0.5f));
    remainder -= correction * int(B);
    if (2 * remainder > int(B)) correction += 1;
    if (2 * remainder < -int(B)) correction -= 1;
    return uint(int(guess) + correction);
}

// a / b correctly rounded with no double arithmetic on its common path (intersection.division =
// "integer"; issue 18 §2: double runs at 1/64 rate on consumer GPUs, and the Moller-Trumbore test
// divides once per triangle). For normal a = A 2^(ea-23) and b = B 2^(eb-23) the quotient is
// Q 2^(ea-eb-s) with Q from rtQuotientSignificand; scaling by a power of two does not change a
// rounding while the result stays normal, so only the significands are divided. The guess is the
// dividend's significand times the device's own reciprocal of the divisor's (OpFDiv, within 2.5
// ULP, then one rounding: at most 8 units of Q off); one division, its reciprocal used twice.
// No loop: a loop at each of a kernel's divisions made lavapipe's LLVM compile a kernel for minutes.
// A zero dividend gives a signed zero; other zero, subnormal, infinite or NaN operands and a
// subnormal quotient go through rtDivideByDouble (rare: none on the common path); a quotient
// past FLT_MAX is infinity, as IEEE's overflow gives.
float rtDivideByIntegers(float a, float b) {
    uint ua = floatBitsToUint(a);
    uint ub = floatBitsToUint(b);
    uint ea = (ua >> 23u) & 0xffu;
    uint eb = (ub >> 23u) & 0xffu;
    uint sign = (ua ^ ub) & 0x80000000u;
    if (eb == 0u || eb == 255u || ea == 255u) return rtDivideByDouble(a, b);
    if (ea == 0u) return (ua & 0x7fffffffu) == 0u ? uintBitsToFloat(sign) : rtDivideByDouble(a, b);
    uint A = (ua & 0x007fffffu) | 0x00800000u;
    uint B = (ub & 0x007fffffu) | 0x00800000u;
    uint s = A >= B ? 23u : 24u;
    int exponent = int(ea) - int(eb) + 150 - int(s);  // the quotient's biased exponent
    if (exponent <= 0) return rtDivideByDouble(a, b);  // subnormal or zero
    if (exponent >= 255) return uintBitsToFloat(sign | 0x7f800000u);  // +-infinity
    precise float reciprocal = 1.0f / uintBitsToFloat(B | 0x3f000000u);  // 2^23 / B, one OpFDiv
    precise float guess = uintBitsToFloat(A | 0x3f000000u) * reciprocal;
    precise float scaled = guess * uintBitsToFloat(s == 23u ? 0x4b000000u : 0x4b800000u);  // * 2^s, exact
    uint q = rtQuotientSignificand(A, B, s, uint(scaled), reciprocal);
    return uintBitsToFloat(sign | (uint(exponent) << 23u) | (q - 0x00800000u));
}

// a / b correctly rounded, as IEEE float division on the CPU gives it (intersection.division), or
// the device's own (nativeDivision != 0: the plain strategy, which measures what exactness costs;
// its hits are judged by the exact reference alone).
float rtDivide(float a, float b) {
    if (nativeDivision != 0u) return a / b;
    if (division == kDivisionDouble) return rtDivideByDouble(a, b);
    return rtDivideByIntegers(a, b);
}

// The correctly rounded sqrt(x), for x > 0 finite, from a guess within 4 ulps of it: the midpoint
// m between the guess and a neighbour has at most 25 significant bits, so m * m (at most 50) is
// exact in double, and comparing x with it says on which side of m the root lies (never on it: a
// float x is never the square of such a midpoint). Needs shaderFloat64, as rtDivide does.
float rtSqrtFromGuess(float x, float s) {
    for (int i = 0; i < 4; ++i) {  // up
        float next = intBitsToFloat(floatBitsToInt(s) + 1);
        precise double m = (double(s) + double(next)) * 0.5;
        precise double square = m * m;
        if (!(square < double(x))) break;
        s = next;
    }
    for (int i = 0; i < 4; ++i) {  // down
        float previous = intBitsToFloat(floatBitsToInt(s) - 1);
        precise double m = (double(s) + double(previous)) * 0.5;
        precise double square = m * m;
        if (!(square > double(x))) break;
        s = previous;
    }
    return s;
}

// sqrt(x) correctly rounded, as IEEE float sqrt on the CPU gives it (0, infinity and NaN give x;
// x < 0 gives NaN). Vulkan's sqrt is not exact (its precision is inversesqrt's): the root of the
// double is only the guess rtSqrtFromGuess corrects.
float rtSqrt(float x) {
    if (!(x > 0.0f) || x == uintBitsToFloat(0x7f800000u)) return x < 0.0f ? uintBitsToFloat(0x7fc00000u) : x;
    return rtSqrtFromGuess(x, float(sqrt(double(x))));
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
// limit (llvmpipe: 65,535 per invocation, see strategies/branching/lane_counts.h), and the BVH clips
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

// The ray as the triangle tests see it: origin, direction, tMin, and for the watertight test the
// per-ray shear (Woop et al. 2013 §3.1): axes kx, ky, kz with kz the direction's largest
// component (kx, ky swapped when it is negative, to keep the winding), and Sx, Sy, Sz.
struct RtTriangleRay {
    vec3 o;
    vec3 d;
    float tMin;
    ivec3 axes;
    vec3 shear;
};

RtTriangleRay rtTriangleRay(Ray ray) {
    RtTriangleRay r;
    r.o = vec3(ray.originTMin);
    r.d = vec3(ray.directionTMax);
    r.tMin = ray.originTMin.w;
    r.axes = ivec3(0, 1, 2);
    r.shear = vec3(0.0f);
    if (triangleTest == kTriangleTestWatertight) {
        vec3 a = abs(r.d);
        int kz = 0;
        if (a.y > a[kz]) kz = 1;
        if (a.z > a[kz]) kz = 2;
        int kx = kz == 2 ? 0 : kz + 1;
        int ky = kx == 2 ? 0 : kx + 1;
        if (r.d[kz] < 0.0f) {
            int swap = kx;
            kx = ky;
            ky = swap;
        }
        r.axes = ivec3(kx, ky, kz);
        r.shear = vec3(rtDivide(r.d[kx], r.d[kz]), rtDivide(r.d[ky], r.d[kz]), rtDivide(1.0f, r.d[kz]));
    }
    return r;
}

// Watertight ray-triangle test (Woop, Benthin & Wald 2013, JCGT 2(1), §3): the vertices are
// sheared into the ray's frame and the three 2D edge functions decide the hit; an edge function
// that is exactly 0 is recomputed in double, so a ray through a shared edge or vertex hits at
// least one of the triangles. Updates (tBest, u, v) when hit in [tMin, tBest), like Moller-Trumbore.
bool rtIntersectWatertight(RtTriangleRay r, vec3 v0, vec3 v1, vec3 v2,
                           RT_INOUT(float) tBest, RT_INOUT(float) uBest, RT_INOUT(float) vBest) {
    int kx = r.axes.x;
    int ky = r.axes.y;
    int kz = r.axes.z;
    precise vec3 a = v0 - r.o;
    precise vec3 b = v1 - r.o;
    precise vec3 c = v2 - r.o;
    precise float ax = a[kx] - r.shear.x * a[kz];
    precise float ay = a[ky] - r.shear.y * a[kz];
    precise float bx = b[kx] - r.shear.x * b[kz];
    precise float by = b[ky] - r.shear.y * b[kz];
    precise float cx = c[kx] - r.shear.x * c[kz];
    precise float cy = c[ky] - r.shear.y * c[kz];
    precise float eu = cx * by - cy * bx;  // scaled barycentric of v0
    precise float ev = ax * cy - ay * cx;  // of v1
    precise float ew = bx * ay - by * ax;  // of v2
    if (eu == 0.0f || ev == 0.0f || ew == 0.0f) {  // products of floats are exact in double
        precise double du = double(cx) * double(by) - double(cy) * double(bx);
        precise double dv = double(ax) * double(cy) - double(ay) * double(cx);
        precise double dw = double(bx) * double(ay) - double(by) * double(ax);
        eu = float(du);
        ev = float(dv);
        ew = float(dw);
    }
    if ((eu < 0.0f || ev < 0.0f || ew < 0.0f) && (eu > 0.0f || ev > 0.0f || ew > 0.0f)) return false;
    precise float det = eu + ev + ew;
    if (det == 0.0f) return false;
    precise float az = r.shear.z * a[kz];
    precise float bz = r.shear.z * b[kz];
    precise float cz = r.shear.z * c[kz];
    precise float scaledT = eu * az + ev * bz + ew * cz;
    float t = rtDivide(scaledT, det);
    if (t < r.tMin || t >= tBest) return false;
    tBest = t;
    uBest = rtDivide(ev, det);
    vBest = rtDivide(ew, det);
    return true;
}

// The configured test (intersection.test): Moller-Trumbore or watertight.
bool rtIntersect(RtTriangleRay r, vec3 v0, vec3 v1, vec3 v2, RT_INOUT(float) tBest, RT_INOUT(float) uBest,
                 RT_INOUT(float) vBest) {
    if (triangleTest == kTriangleTestWatertight) return rtIntersectWatertight(r, v0, v1, v2, tBest, uBest, vBest);
    return rtIntersectTriangle(r.o, r.d, r.tMin, v0, v1, v2, tBest, uBest, vBest);
}

#endif  // RT_RAY_MATH_GLSL
