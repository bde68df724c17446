#!/usr/bin/env python3
"""How long a set of cases takes on a cluster, from measured costs.

Reads a sweep.csv (`ddafrac sweep`, or `ddafrac sweep --collect` on a folder of cases not yet
run: it lists every case with its expected_block_steps = blocks x end_time / dt_max), prices each
case at a measured cost per block-step, adds extra runs priced like one of the cases (a
sensitivity study's), and schedules them as the sweep does over MPI: longest first, each to the
first free slot (one slot per core at one thread per case). Prints the constants it used.

    scaling_estimate.py PLANNED.csv --us-per-block-step 11.6 --extra-runs 60 --extra-like impact-case04 \\
        --nodes 16 --cores-per-node 32

A measured sweep.csv (cases done) can give the cost per block-step instead:
    scaling_estimate.py --measured MEASURED.csv ...   (median of run_time_s / expected_block_steps)
"""

import argparse
import csv
import heapq
import statistics
import sys

SECONDS_PER_HOUR = 3600.0
MICROSECONDS = 1e6


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows or "expected_block_steps" not in rows[0]:
        sys.exit(f"{path}: no expected_block_steps column (written by ddafrac sweep and --collect)")
    return rows


def measured_us_per_block_step(path):
    done = [r for r in read_rows(path) if r.get("state") == "done"]
    if not done:
        sys.exit(f"{path}: no case is done")
    return statistics.median(float(r["run_time_s"]) / float(r["expected_block_steps"]) for r in done) * MICROSECONDS


def makespan(case_seconds, slots):
    """Longest first, each case to the slot that frees first (the sweep's dispatch)."""
    free_at = [0.0] * slots
    for seconds in sorted(case_seconds, reverse=True):
        heapq.heappush(free_at, heapq.heappop(free_at) + seconds)
    return max(free_at)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("planned", help="sweep.csv listing the cases to run")
    cost = parser.add_mutually_exclusive_group(required=True)
    cost.add_argument("--us-per-block-step", type=float, help="measured cost of one block-step on one thread (µs)")
    cost.add_argument("--measured", help="a sweep.csv of cases done: the median of their costs per block-step")
    parser.add_argument("--extra-runs", type=int, default=0, help="more runs, each priced like --extra-like")
    parser.add_argument("--extra-like", help="the case of PLANNED whose cost each extra run has")
    parser.add_argument("--nodes", type=int, nargs="+", default=[16])
    parser.add_argument("--cores-per-node", type=int, default=32)
    args = parser.parse_args()

    rows = read_rows(args.planned)
    us = args.us_per_block_step if args.us_per_block_step else measured_us_per_block_step(args.measured)
    block_steps = {r["case"]: float(r["expected_block_steps"]) for r in rows}
    cases = list(block_steps.values())
    if args.extra_runs:
        if args.extra_like not in block_steps:
            sys.exit(f"--extra-like: no case named {args.extra_like!r} in {args.planned}")
        cases += [block_steps[args.extra_like]] * args.extra_runs
    seconds = [b * us / MICROSECONDS for b in cases]
    longest = max(block_steps, key=block_steps.get)

    print(f"cost per block-step, one thread: {us:.2f} µs")
    print(f"cases: {len(rows)} from {args.planned}"
          + (f" + {args.extra_runs} like {args.extra_like} ({block_steps[args.extra_like]:.3g} block-steps)"
             if args.extra_runs else ""))
    print(f"total: {sum(cases):.3g} block-steps = {sum(seconds) / SECONDS_PER_HOUR:.1f} core-hours")
    print(f"longest case: {longest}, {block_steps[longest]:.3g} block-steps = "
          f"{max(seconds) / SECONDS_PER_HOUR:.2f} h on one thread")
    print(f"{'nodes':>6} {'cores':>6} {'wall (h)':>9} {'cases/hour':>11}")
    for nodes in args.nodes:
        slots = nodes * args.cores_per_node
        wall = makespan(seconds, slots)
        print(f"{nodes:>6} {slots:>6} {wall / SECONDS_PER_HOUR:>9.2f} {len(cases) / (wall / SECONDS_PER_HOUR):>11.1f}")


if __name__ == "__main__":
    main()
