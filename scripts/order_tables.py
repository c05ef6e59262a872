#!/usr/bin/python3
"""Table for an order results folder (configs/order.toml): the branching kernel over a batch as it
comes and sorted for coherence (strategy.type = sorted: direction octant, then the origin's Morton
code), per scene, ray type and structure: the lanes' utilisation each way, the rays the sort moved,
the host sort's time over the sorted kernel's, and both speeds against Embree with their 95%
intervals and whether they separate. Writes tables.md next to runs.csv.

usage: scripts/order_tables.py RESULTS_DIR
Uses Debian's python3-pandas only.
"""
import sys

from rtbench_results import (command_text, embree_speed_caption, failed_rows, fmt, interval_text, open_results,
                             sorted_beside_branching, speed_verdict, write_tables)


def main() -> int:
    folder, runs, failed, context, device = open_results(__doc__)
    pairs = sorted_beside_branching(runs)
    lines = [f"# Ray order alone — {device}, {context.get('cpu', '?')}", "",
             command_text(context) + f" {len(runs)} runs ok, {len(failed)} failed.",
             "lanes: the branching kernel's SIMD lane utilisation over the batch as it comes, and sorted (direction "
             "octant, then the origin's 30-bit Morton code; deterministic); moved: rays the sort put elsewhere; sort / "
             "kernel: the host sort's time (`sorted_sort_ms`, not in the kernel's) over the sorted kernel's median; " +
             embree_speed_caption(runs) + " In the same run, with its 95% interval; sorted: faster or slower only where "
             "the two intervals separate.", "",
             "| scene | rays | structure | batch | lanes | sorted lanes | × | moved | sort / kernel | × Embree [95%] | "
             "sorted × Embree [95%] | sorted |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in pairs.sort_values(["triangles", "rays_type", "structure"]).itertuples():
        lines.append(f"| {r.scene} | {r.rays_type} | {r.structure} | {int(r.rays):,} | {fmt(r.lanes)} | "
                     f"{fmt(r.sorted_lanes)} | {fmt(r.sorted_lanes / r.lanes, 3)} | {int(r.moved):,} | {fmt(r.sort_share, 3)} | "
                     f"{r.speed:.3g} {interval_text(r.speed_span)} | {r.sorted_speed:.3g} {interval_text(r.sorted_span)} | "
                     f"{speed_verdict(r.sorted_span, r.speed_span)} |")
    return write_tables(folder, lines + failed_rows(failed, "parameters", lambda r: r.label))


if __name__ == "__main__":
    sys.exit(main())
