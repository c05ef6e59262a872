// A runs.csv column as the part of rtbench that computes it declares it: name, kind, unit and
// meaning. The kind says how a value may differ between two runs of the same config, and so how
// `rtbench check` compares it:
//   parameter  a config key or the run's identity: equal by construction;
//   count      deterministic: equal on every machine with the same device (checked exactly);
//   reference  derived from another library's floating point (Embree's ISA path): compared
//              within a declared tolerance, never as an exact count;
//   timing     seconds and rates: reported when outside a relative tolerance, never a failure;
//   context    where and when (commit, device, driver, Embree's threads and ISA): reported.
#pragma once
#include <map>
#include <string>
#include <vector>

namespace rtbench {

// Exact: deterministic, compared exactly (counts, and text such as status). Scheduled: decided by
// the device's scheduling (which subgroup fetched last), checked by the run against its range,
// reported by check and compare, never a failure. See docs/results-folder.md.
enum class ColumnKind { Parameter, Exact, Reference, Timing, Context, Scheduled };

const char* columnKindName(ColumnKind kind);

// What a column's cells hold, as readers type them (pandas: Int64, float64, boolean, string).
// A typed column (schema/column.h) has the type of its value. Inferred, for the few columns still
// declared as plain specs: from the unit, when the columns are gathered (harness/columns.cpp): an
// integer when the unit counts things and the column is not a mean or a per-something ratio,
// else a number.
enum class ColumnType { Inferred, Integer, Number, Boolean, Text };

struct ColumnSpec {
    std::string name;
    ColumnKind kind;
    std::string unit;  // "" for a dimensionless or text value
    std::string help;
    // Reference columns: the largest difference that still counts as the same result, absolute,
    // or as a fraction of the run's rays when perRay (mismatch counts).
    double tolerance = 0.0;
    bool perRay = false;
    // "section.key=value" conditions under which a run writes the column (a structure's or a
    // strategy's own columns, a key read only by some runs); empty: every run. A runs CSV may
    // leave the column out when no row meets them (a file from before the method existed).
    std::vector<std::string> appliesWhen = {};
    // The results schema (kSchemaVersion) that added the column: a runs CSV of an older schema
    // lacks it, and stays readable (harness/columns.h).
    int since = 1;
    ColumnType type = ColumnType::Inferred;
};

// The schema of a results folder: which columns its runs.csv holds. Recorded in context.json as
// "schema_version" from 5 on; older folders are known by their columns (harness/columns.cpp).
//   1  2026-11-28: results/nvidia-h200;
//   2  + the exact reference (exact_*, embree_exact_*), scene.scale/translate, intersection.test,
//        conservative grids;
//   3  + simplified and packed scenes (scene.simplify_*, intersection.vertex_bits), image_*;
//   4  + a run's identity: inputs_hash, input_files, cpu;
//   5  timing in rounds: samples.csv, spread and intervals, adaptive repetitions, the noise guard;
//   6  a 3-vector key (camera.position, scene.translate, ...) as three numeric columns <key>_x,
//      _y, _z instead of one "[x y z]" cell (readers split an older file's cells); columns.csv
//      gives each column's value type.
//   7  ray types (rays.type: primary, shadow) and the query they ask (the query column: closest or
//      any hit, Embree's rtcOccluded for any); the ray type's own keys and columns.
//   8  + reflection rays (reflection.iteration, reflection_*).
//   9  + the device's shading passes (shading_*), refraction rays (refraction.*), diffuse rays:
//        path tracing (path.*) and ambient occlusion (ao.*).
//  10  + Whitted ray tracing (whitted.*, whitted_*): materials and lights.
//  11  + branching's CPU lane model beside the device's ballots (lanes_model_*).
//  12  + persistent threads (strategy.persistent_workgroups, strategy.rays_per_fetch, rays_fetched,
//        rays_traced, persistent_rays_per_fetch); the scheduled megakernel (strategy.schedule,
//        megakernel_*); multipass in batches (strategy.batch_rays,
//        multipass_batch_rays); simd_efficiency and bytes_stencil of multipass count each
//        batch's rays.
//  13  + multipass with the oracle on the device (strategy.control, bytes_compaction,
//        kernel_ms_oracle); the oracle's threshold in fixed point (floor(t * 2^31)).
//  14  + the driver's acceleration structure and ray query (structure.type = driver, strategy.type =
//        ray_query, driver_*); cpu_reference_mismatches and the work columns empty where a method
//        counts no work; the two SIMD measures apart (simd_efficiency_purcell,
//        simd_lane_utilisation); strategy.oracle_basis.
//  15  + the plain twin of the branching kernel (strategy.type = plain, plain_cpu_differing).
//  16  + Purcell 2002 Fig. 9's texture cache (cache.* keys, cache_* columns).
//  17  + the instruction estimate (instructions_*), tiled rendering (camera.tile).
//  18  + intersection.division (double, as every run before it divided, or integer: no double).
//  19  + the wavefront (strategy.type = wavefront, wavefront_*, kernel_ms_trace, _shade, _queue);
//        a strategy that traces the whole path times Embree on every generation's rays, and its
//        rates count them all.
//  20  + strategy.list_partitions (multipass with the control on the device: each ray list in
//        partitions, 2 by default; before, one).
//  21  bytes_stack of multipass on a BVH counts the stack entries pushed and popped (its stack
//        stays in memory; before, every pass that served a ray moved the whole 128-byte stack,
//        and setup wrote it).
//  22  + persistent_max_fetches (persistent threads: the fetches a subgroup may make, bounded under
//        llvmpipe's loop limit; before, a subgroup fetched until the stream was done).
//  23  *_ms_ci_low/_high: the median's interval from the order statistics (empty below 6
//        repetitions), speed_ratio_ci_*: from the two medians' 97.5% intervals (before: percentile
//        bootstrap at any n); *_ms_std and _cv empty for one repetition (before: 0), and one
//        repetition is a timing_warning.
//  24  + retimed (rtbench retime re-times the runs with a timing warning).
//  25  kernel_ms_* of multipass with strategy.control = host: the live pass loop's host wall time,
//        the oracle's read-back after every pass (before: the replayed passes' GPU time, now
//        kernel_ms_replay).
//  26  + the control (strategy.type = control, control_cpu_differing): a plain grid ray caster
//        making its own camera rays, what the branching kernel's speed is judged against.
//  27  + build_rounds, structure_build_ms_median, embree_build_ms_median, build_ratio_vs_embree and
//        its interval (experiment.build_rounds: the two builds timed alternately).
//  28  the noise guard judges each method's median by its 95% interval (experiment.noise_ci) where
//        6 or more repetitions give one, the CV (experiment.noise_cv) only below 6 (before: the
//        CV at any count, which one slow repetition of ten inflates while the median stays).
//  29  + the sorted-rays branching variant (strategy.type = sorted: sorted_sort_ms, sorted_rays_moved);
//        + jittered camera rays (rays.type = jitter, jitter.seed; removed again without a schema of
//        its own: issue 46's example of a new ray type, which no config of record used).
constexpr int kSchemaVersion = 29;

// The CSV column of a config key: "structure.min_dim" -> "structure_min_dim".
std::string paramColumn(const std::string& key);

// One run's values by column name. Writing a column no part declared is an error (writeCsv).
using Row = std::map<std::string, std::string>;

// Shortest decimal with `significant` digits, as every numeric column is written.
std::string formatNumber(double value, int significant = 6);

}  // namespace rtbench
