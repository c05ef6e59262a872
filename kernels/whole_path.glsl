// What the kernels that trace a whole path from the camera rays share (strategies/whole_path.h: the
// wavefront's and the path megakernel's): the control block with the passes, the camera rays and
// the vertices the shading passes read. Include after gpu_layout.h.
#ifndef RT_WHOLE_PATH_GLSL
#define RT_WHOLE_PATH_GLSL

layout(std430, set = 0, binding = kBindingPathControl) buffer WholePathControlBuffer {
    WholePathControl control;
    // The wavefront's, per workgroup of the shading grid: the rays it made (wavefront_shade.comp),
    // then the queue position of its first (wavefront_scan.comp), which the compaction reads.
    uint groupSums[];
};
layout(std430, set = 0, binding = kBindingPathCamera) readonly buffer CameraBuffer { Ray cameraRays[]; };
layout(std430, set = 0, binding = kBindingPathTriangles) readonly buffer PathTriangleBuffer { Triangle pathTriangles[]; };

// The fan-out of pass g (0 past the last pass: the batch is shaded by none).
uint wpFanOut(uint g) { return g < control.limits.z ? control.passes[g].pass.z : 0u; }

#ifdef RT_SHADING_GLSL
// Pass g's ray `slot` from ray `parent` (its path and weight) and its hit `h`, by kernels/shading.glsl
// rtShade over the path's one material; false: no ray (a miss makes none).
bool wpShade(uint g, Ray parent, HitRecord h, uint path, uint slot, float weight, out Ray made, out float madeWeight) {
    madeWeight = 0.0f;
    if (h.primitive == kNoHit) return false;
    Triangle t = pathTriangles[h.primitive];
    return rtShade(control.passes[g], control.material, vec3(0.0f), t.v0.xyz, t.v1.xyz, t.v2.xyz, h.u, h.v,
                   parent.directionTMax.xyz, path, slot, weight, made, madeWeight);
}
#endif

#endif  // RT_WHOLE_PATH_GLSL
