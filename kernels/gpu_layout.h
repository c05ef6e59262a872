// GPU-visible layouts shared by every method: rays, triangles, hit records, the multipass ray
// state and counters, the common binding slots and the specialization-constant ids. Included by
// C++ (harness, methods, tests) and by GLSL (kernels/*.comp). Each structure adds its own layout
// header (structures/<structure>/<structure>_layout.h) with its buffers in the slots from
// kBindingStructure on. Never retype these in a shader.
// All structs use vec4/uvec4 or 4-byte scalars so that std430 and C++ agree byte for byte.
#ifndef RTBENCH_GPU_LAYOUT_H
#define RTBENCH_GPU_LAYOUT_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
namespace rtbench::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using uint = std::uint32_t;
using uint64 = std::uint64_t;
#define RTBENCH_CONST constexpr uint
#else
#define uint64 uint64_t
#define RTBENCH_CONST const uint
#endif

// ---- descriptor set 0 binding slots (all storage buffers) ----
RTBENCH_CONST kBindingRays = 0;         // Ray[rayCount]
RTBENCH_CONST kBindingHits = 1;         // HitRecord[rayCount]
RTBENCH_CONST kBindingPassCounters = 2; // PassCounters: oracle query + event counts of a pass
RTBENCH_CONST kBindingStrategy = 3;     // first of kStrategySlots slots a strategy may fill with its own buffers
RTBENCH_CONST kStrategySlots = 6;       // (GpuBuffers: zeroed; a slot the strategy leaves empty gets 4 bytes)
RTBENCH_CONST kBindingStructure = 9;    // first slot of the structure's own buffers

// Multipass's own slots (methods/multipass, multipassBuffers): the per-ray state Purcell's
// passes keep between them, then, with strategy.control = "device", the compacted lists and
// the oracle's block.
RTBENCH_CONST kBindingStencil = kBindingStrategy + 0u;      // uint8_t[rayCount]: ray state (kState*)
RTBENCH_CONST kBindingTraversal = kBindingStrategy + 1u;    // the structure's traversal state [rayCount]
RTBENCH_CONST kBindingHitState = kBindingStrategy + 2u;     // RayHitState[rayCount]: best hit so far
RTBENCH_CONST kBindingRayCounters = kBindingStrategy + 3u;  // RayCounters[rayCount]: per-ray work (instrumentation)
RTBENCH_CONST kBindingRayLists = kBindingStrategy + 4u;     // uint[4 * rayCount]: lists T0, T1, W0, W1 of ray indices
RTBENCH_CONST kBindingPassControl = kBindingStrategy + 5u;  // PassControl, then PassLogEntry[kPassLogEntries]
RTBENCH_CONST kPassLogEntries = 1024u;  // the pass log is a ring: pass p (from 1) at (p - 1) % kPassLogEntries

// The slots of the strategies that trace a whole path from the camera rays (strategies/whole_path.h:
// the wavefront, Laine, Karras & Aila 2013's queues, and the path megakernel). The wavefront's
// queue is the common rays and hits slots; the megakernel writes each path's batch ray to the
// made slots and its record to the hits slot, by path.
RTBENCH_CONST kBindingPathControl = kBindingStrategy + 0u;  // WholePathControl, then uint[workgroups of slots] (wavefront)
RTBENCH_CONST kBindingPathCamera = kBindingStrategy + 1u;   // Ray[camera rays]: generation 0, copied into the queue
RTBENCH_CONST kBindingPathQueue = kBindingStrategy + 2u;    // uvec4[queue]: each queued ray's parent, path, weight bits (wavefront)
RTBENCH_CONST kBindingPathMade = kBindingStrategy + 3u;     // Ray[slots]: the ray made in each slot (megakernel: each path's batch ray)
RTBENCH_CONST kBindingPathMadeInfo = kBindingStrategy + 4u; // uvec4[slots]: made (1 or 0), parent, path, weight bits
RTBENCH_CONST kBindingPathTriangles = kBindingStrategy + 5u;// Triangle[triangles]: the vertices the shading pass reads
RTBENCH_CONST kPathMaxPasses = 64u;  // shading passes of one path (reflection.iteration, path.bounce: at most 64)

// ---- specialization-constant ids ----
RTBENCH_CONST kSpecWorkgroupSize = 0;    // local_size_x of every kernel (default 64)
RTBENCH_CONST kSpecInstrument = 1;       // 1: count work and bytes; 0: timing runs
RTBENCH_CONST kSpecTraverseSteps = 2;    // multipass: traversal steps per traverse pass (K); every structure's mpTraverse reads it
RTBENCH_CONST kSpecIntersections = 3;    // multipass: triangle tests per intersect pass (M); every structure's mpIntersect reads it
RTBENCH_CONST kSpecSuppress = 4;         // multipass: 1 = rays done mid-pass skip the rest's reads (the structures' hooks)
RTBENCH_CONST kSpecTriangleTest = 5;     // kTriangleTest*: the ray-triangle test (intersection.test)
RTBENCH_CONST kSpecVertexBits = 6;       // 0: float vertices (Triangle); 1..16: packed (kPackedTriangleWords)
RTBENCH_CONST kSpecLatticeOriginX = 7;   // packed vertices: the lattice's origin (float bits) ...
RTBENCH_CONST kSpecLatticeOriginY = 8;
RTBENCH_CONST kSpecLatticeOriginZ = 9;
RTBENCH_CONST kSpecLatticeStep = 10;     // ... and its spacing, a power of two (float bits)
RTBENCH_CONST kSpecQuery = 11;           // kQuery*: what a ray asks of the scene
RTBENCH_CONST kSpecNativeDivision = 12;  // 1: rtDivide is the device's own division (OpFDiv, 2.5 ULP allowed): strategy plain
RTBENCH_CONST kSpecDivision = 13;        // kDivision*: how rtDivide rounds exactly (intersection.division)
RTBENCH_CONST kSpecMaxGroupsX = 14;      // kernels that size an indirect dispatch: maxComputeWorkGroupCount[0]
// A strategy numbers its own constants from here, in its folder (strategies/<name>/<name>_layout.h):
// each kernel is its own SPIR-V module, so two strategies may use the same ids.
RTBENCH_CONST kSpecStrategyFirst = 15;

// ---- queries (pbrt's Intersect and IntersectP; Embree's rtcIntersect and rtcOccluded) ----
RTBENCH_CONST kQueryClosest = 0;  // the nearest hit in [tMin, tMax)
RTBENCH_CONST kQueryAny = 1;      // whether anything is hit in [tMin, tMax): the first hit found ends
                                  // the walk (shadow rays); its record is that hit, not the nearest

// ---- shading passes (kernels/shading.comp, kernels/shading.glsl rtShade): the rays a
// generation's hits make, ShadingParams.pass.y ----
RTBENCH_CONST kShadeShadow = 0;    // an any-hit ray toward each point light (slot l: light l), from surfaces with a diffuse part
RTBENCH_CONST kShadeMirror = 1;    // one mirror reflection, every surface a mirror (Christen 2005 §5.2.1)
RTBENCH_CONST kShadeDiffuse = 2;   // cosine-weighted rays (path tracing, ambient occlusion), tMax values.x
RTBENCH_CONST kShadeRefract = 3;   // one refracted ray, every surface glass of index values.x (total internal reflection: mirror)
RTBENCH_CONST kShadeSpecular = 4;  // Whitted: by the surface's material, slot 0 its reflection, slot 1 its refraction

// ---- materials (Material.kind.x): what a surface does with light (Whitted ray tracing) ----
RTBENCH_CONST kMaterialDiffuse = 0;  // lit through shadow rays only
RTBENCH_CONST kMaterialMirror = 1;   // reflects a fraction optics.x, the rest diffuse (Christen 2005 eq. 5.1)
RTBENCH_CONST kMaterialGlass = 2;    // reflects and transmits by Fresnel's equations, index of refraction optics.y

// ---- shading-pass binding slots (a descriptor set of its own, all storage buffers) ----
RTBENCH_CONST kShadingBindingParents = 0;    // Ray[parents]: the generation's rays
RTBENCH_CONST kShadingBindingHits = 1;       // HitRecord[parents]: their hits
RTBENCH_CONST kShadingBindingPaths = 2;      // uint[parents]: each ray's path (random-number key)
RTBENCH_CONST kShadingBindingTriangles = 3;  // Triangle[triangles]: the scene's vertices
RTBENCH_CONST kShadingBindingRays = 4;       // Ray[parents * fan-out]: slot parent * fan-out + s
RTBENCH_CONST kShadingBindingMade = 5;       // uint[parents * fan-out]: 1 where the slot made a ray
RTBENCH_CONST kShadingBindingMaterialOf = 6; // uint[triangles]: each triangle's material
RTBENCH_CONST kShadingBindingMaterials = 7;  // Material[materials]
RTBENCH_CONST kShadingBindingLights = 8;     // vec4[lights] (at least one): the point lights, xyz
RTBENCH_CONST kShadingBindingWeights = 9;    // float[parents]: each parent ray's weight
RTBENCH_CONST kShadingBindingMadeWeights = 10;  // float[parents * fan-out]: each ray made's weight
RTBENCH_CONST kShadingBindingCount = 11;

// ---- exact division (kernels/ray_math.glsl rtDivide): both give IEEE's correctly rounded quotient ----
RTBENCH_CONST kDivisionDouble = 0;   // the double quotient rounded to float (one double division)
RTBENCH_CONST kDivisionInteger = 1;  // the device's quotient corrected with 32-bit integer products (no double)

// ---- ray-triangle tests (kernels/ray_math.glsl) ----
RTBENCH_CONST kTriangleTestMollerTrumbore = 0;  // Moller & Trumbore 1997
RTBENCH_CONST kTriangleTestWatertight = 1;      // Woop, Benthin & Wald 2013

// ---- multipass ray states: the one-byte "stencil" (Purcell et al. 2002 §3.2) ----
RTBENCH_CONST kStateTraversing = 0;  // active: step through the structure
RTBENCH_CONST kStateWaiting = 1;     // active: triangles of the current voxel or leaf to intersect
RTBENCH_CONST kStateDoneHit = 2;     // done: nearest hit found
RTBENCH_CONST kStateLeftStructure = 3;    // done: left the structure without a hit
RTBENCH_CONST kStateMissedBox = 4;   // done: never entered the structure's box

// ---- multipass pass kinds (strategies/multipass/multipass_schedule.h PassKind) ----
RTBENCH_CONST kPassSetup = 0;
RTBENCH_CONST kPassTraverse = 1;
RTBENCH_CONST kPassIntersect = 2;
RTBENCH_CONST kPassWrite = 3;

// ---- PassCounters.counts indices (64-bit, summed over a dispatch) ----
RTBENCH_CONST kCountTraversing = 0;     // rays traversing after the pass (oracle; always on)
RTBENCH_CONST kCountWaiting = 1;        // rays waiting after the pass (oracle; always on)
RTBENCH_CONST kCountUsefulRays = 2;     // rays whose state the kernel serves (did useful work)
RTBENCH_CONST kCountStencilWrites = 3;  // ray-state bytes written (state changed)
RTBENCH_CONST kCountStructureReads = 4; // structure records read (grid: cell offsets; BVH: nodes)
RTBENCH_CONST kCountTriangleReads = 5;  // triangle-list entries read, each with its vertices
RTBENCH_CONST kCountStackEntries = 6;   // node-stack entries pushed or popped in memory (multipass on a BVH)
RTBENCH_CONST kCountActiveLanes = 7;    // kernels with subgroup ballots: sum of active lanes over them
RTBENCH_CONST kCountLaneSlots = 8;      // the same: sum of subgroup size over subgroup ballots
// A strategy numbers its own counters from here, in its folder (strategies/<name>/<name>_layout.h),
// below kCountSlots; only its own kernels and host code read them.
RTBENCH_CONST kCountStrategyFirst = 9;
RTBENCH_CONST kCountSlots = 13;
RTBENCH_CONST kPassLogSums = 8;         // the PassCounters slots a pass log entry keeps: kCountTraversing..kCountStackEntries and one more

// A ray as generated once on the host and traced by every method (Embree included).
struct Ray {
    vec4 originTMin;     // byte 0: xyz origin, w = tMin
    vec4 directionTMax;  // byte 16: xyz direction (not normalised), w = tMax
};

// One triangle's vertices (Purcell Fig. 4 "triangle vertices"), w unused (0).
struct Triangle {
    vec4 v0;  // byte 0
    vec4 v1;  // byte 16
    vec4 v2;  // byte 32
};

// Packed vertices (intersection.vertex_bits < 32, structures/triangle_store.h): every vertex is a
// point of one lattice over the scene's box, origin + q * step with q < 2^16 per axis and step a
// power of two, so the product is exact and the sum rounds once (no FMA can change it).
// Triangle i is 5 words from word 5i:
// (v0.x | v0.y << 16), (v0.z | v1.x << 16), (v1.y | v1.z << 16), (v2.x | v2.y << 16), v2.z.
// 20 bytes read per triangle instead of Triangle's 48.
RTBENCH_CONST kPackedTriangleWords = 5;

// Nearest hit of one ray plus the work it took.
struct HitRecord {
    float t;              // byte 0: hit distance along direction; kNoHitT when none
    uint primitive;       // byte 4: triangle id, kNoHit when none
    float u;              // byte 8: barycentric of v1
    float v;              // byte 12: barycentric of v2
    uint cellsVisited;    // byte 16: grid voxels entered / BVH nodes visited (0: box missed)
    uint trianglesTested; // byte 20: ray-triangle tests executed
    uint traversalSteps;  // byte 24: traversal step attempts (grid: DDA steps; BVH: references visited)
    uint pad;             // byte 28
};

// Push constants common to every kernel, followed by the structure's own parameters.
struct StreamParams {
    uvec4 stream;  // byte 0: x = ray count, yzw unused
};

// Multipass best hit so far (Purcell's "hit" texture).
struct RayHitState {
    float t;         // byte 0: ray tMax until a hit
    uint primitive;  // byte 4: kNoHit until a hit
    float u;         // byte 8
    float v;         // byte 12
};

// Push constants of a shading pass: which rays a generation's hits make.
struct ShadingParams {
    uvec4 pass;   // byte 0: x = parent rays, y = kShade*, z = rays per parent (fan-out), w = bounce
    uvec4 seed;   // byte 16: x = the random numbers' seed (kShadeDiffuse), yzw unused (0)
    vec4 values;  // byte 32: x = tMax (kShadeDiffuse) or the index of refraction (kShadeRefract), yzw unused
};

// A surface's material (kernels/shading.glsl, Whitted ray tracing).
struct Material {
    uvec4 kind;   // byte 0: x = kMaterial*, yzw unused
    vec4 colour;  // byte 16: rgb = the diffuse colour (images only), a unused
    vec4 optics;  // byte 32: x = reflectance (kMaterialMirror), y = index of refraction (kMaterialGlass), zw unused
};

// Per-ray work, kept only by instrumented kernels (not charged as bandwidth).
struct RayCounters {
    uint cellsVisited;     // byte 0
    uint trianglesTested;  // byte 4
    uint traversalSteps;   // byte 8: traversal step attempts (each traverse iteration that did work)
    uint pad;              // byte 12
};

struct PassCounters {
    uint64 counts[kCountSlots];  // byte 0 + 8 * kCount*
};

RTBENCH_CONST kMaxListPartitions = 8;

// A list's length, alone in its 64-byte cache line: the passes' appends update two lengths with
// atomics while every invocation reads PassControl's first line, so on a CPU device (lavapipe)
// sharing a line would send it from core to core on every append (false sharing).
struct ListCount {
    uint count;     // byte 0: entries in the list
    uint pad[15];   // byte 4
};

// Multipass with the oracle on the device: what the oracle kernel keeps between passes. All
// zeros is the state before the setup pass. Lists: 0, 1 hold traversing rays, 2, 3 waiting ones;
// a pass reads the current list of its state and files the rays it leaves active in the other
// list of that pair (its own state) or appends them to the current list of the other state.
// Bytes 0-63 are written by the oracle kernel only (read by every pass); the lengths follow.
struct PassControl {
    uvec4 traverseGroups;   // byte 0: the next traverse pass's workgroups x, y, z (VkDispatchIndirectCommand), w unused
    uvec4 intersectGroups;  // byte 16: the same for the next intersect pass; the pass not chosen gets 0 groups
    uvec4 current;          // byte 32: x, y: the current traversing and waiting list (0 or 1 of each pair);
                            //          z: the last pass's kPass*; w: passes run before it
    uvec4 status;           // byte 48: x: the naive schedule's phase (kPass*); y: 1 when the loop has ended;
                            //          z: 1 when it ended at the pass cap; w: 1 when a list held more rays
                            //          than the stream (a kernel bug: the loop ends, the run fails)
    ListCount lists[4 * kMaxListPartitions];  // byte 64 + 64 * (kMaxListPartitions * l + p): the length of partition p of list l
};

// One pass of the device-controlled loop, logged by the oracle after it.
struct PassLogEntry {
    uint64 sums[kPassLogSums];  // byte 0: PassCounters slots 0..kPassLogSums - 1 (instrumented runs)
    uvec4 kindLists;  // byte 64: x: kPass*; y, z: rays on the current traversing and waiting lists after it;
                      //          w: rays the pass was dispatched for (its input list; setup: the stream)
};

// A whole path's passes and state on the device (strategies/whole_path.h). The wavefront hands it on
// between its kernels: the queue of the generation being traced, the slots its shading pass fills
// (queue rays x fan-out). All but `passes`, `material` and `limits.xyz` are the wavefront's,
// written on the device (wavefront_setup.comp, wavefront_scan.comp); the megakernel reads the rest.
struct WholePathControl {
    uvec4 traceGroups;  // byte 0: the trace over the queue: workgroups x, y, z (VkDispatchIndirectCommand)
    uvec4 slotGroups;   // byte 16: the shading and compaction over the queue's slots, the same
    uvec4 queue;        // byte 32: x = rays in the queue, y = its generation (0: the camera rays),
                        //          z = its slots (rays x the next pass's fan-out; 0 after the last)
    uvec4 compactGroups;// byte 48: the compaction over the slots just shaded: its workgroups (the shading's
                        //          grid), w = those slots
    uvec4 limits;       // byte 64: x = queue capacity, y = slot capacity, z = passes, w = 1 when a
                        //          generation outgrew a capacity (its slots are not shaded: the run fails)
    Material material;  // byte 80: every surface's (the wavefront traces scenes of one material)
    ShadingParams passes[kPathMaxPasses];  // byte 128: passes[g] makes generation g + 1 from generation g
};

// The driver's ray query (strategies/ray_query/kernels/ray_query.comp): binds kBindingRays and
// kBindingHits only; its push constants.
struct RayQueryParams {
    uvec4 stream;      // byte 0: x = ray count, y = kQuery*, zw unused
    uint64 topLevel;   // byte 16: the top-level acceleration structure's device address
    uint64 unused;     // byte 24
};

RTBENCH_CONST kNoHit = 0xFFFFFFFFu;

#ifdef __cplusplus
constexpr float kNoHitT = 3.402823466e38f;  // FLT_MAX
static_assert(sizeof(Ray) == 32);
static_assert(sizeof(Triangle) == 48);
static_assert(sizeof(HitRecord) == 32);
static_assert(sizeof(StreamParams) == 16);
static_assert(sizeof(RayHitState) == 16);
static_assert(sizeof(RayCounters) == 16);
static_assert(sizeof(ShadingParams) == 48);
static_assert(sizeof(Material) == 48);
static_assert(sizeof(PassCounters) == 104);
static_assert(sizeof(ListCount) == 64);
static_assert(sizeof(PassControl) == 64 + 4 * kMaxListPartitions * 64);
static_assert(sizeof(PassLogEntry) == 80 && kCountStackEntries < kPassLogSums);
static_assert(sizeof(WholePathControl) == 128 + 48 * kPathMaxPasses && offsetof(WholePathControl, passes) == 128);
static_assert(sizeof(RayQueryParams) == 32 && offsetof(RayQueryParams, topLevel) == 16);
static_assert(offsetof(PassControl, current) == 32 && offsetof(PassControl, status) == 48 &&
              offsetof(PassControl, lists) == 64 && offsetof(PassLogEntry, kindLists) == 64);
}  // namespace rtbench::gpu
#else
const float kNoHitT = 3.402823466e38;
#undef uint64
#endif
#undef RTBENCH_CONST

#endif  // RTBENCH_GPU_LAYOUT_H
