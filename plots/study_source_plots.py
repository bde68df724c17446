"""Figures of `ddafrac study source` (registered by register() as a subcommand of ddafrac_plots.py):

    ddafrac_plots.py study-source STUDY_DIR [--times 3e-4,9e-4,1.8e-3]

reads STUDY_DIR/study.csv (case, series, run_dir) and the runs' history.csv, crack_intervals.csv,
loading.csv and VTU snapshots, and writes into STUDY_DIR/figures/:

    cracks_<series>.png     per impact series: cumulative tensile and shear crack counts against
                            time, and the new ones per crack interval (crack_intervals.csv)
    patterns_<series>.png   per impact series: the crack pattern over σ1 of every case at the
                            given times (a panel stays empty where the run has no snapshot there)
    loading_<series>.png    per Brazilian series: the top platen's force against its displacement
    patterns_<series>.png   per Brazilian series: every case's crack pattern over σ1 at its peak
                            force and at its end (the snapshots nearest to those times)
    gauges_<case>.png       σ1 at every gauge of one case (--gauge-case, default case 4), with the
                            virtual joints' tensile strength from its scene.resolved.toml

and STUDY_DIR/analysis.md: the Brazilian discs' peak forces and indirect tensile strengths, and
the flattened disc's crack measures against its mesh with their observed convergence orders (the
sensitivity study's tables, study_sensitivity_plots.py, read from the runs that completed).

Every PNG and analysis.md are written whole (the caller's save(), a temporary name then rename).
"""

import os
import tomllib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import study_sensitivity_plots as sensitivity  # noqa: E402  (beside this script)

MICROSECONDS = 1e6  # µs per s
MILLIMETRES = 1e3  # mm per m
KILONEWTONS = 1e-3  # kN per N
MEGAPASCAL = 1e-6  # MPa per Pa
IMPACT_SERIES = ("impact-theta", "impact-gamma", "impact-v0")
BRAZILIAN_SERIES = ("flattened", "precracked")
LOADED_BODY = "top_platen"  # the prescribed platen of the Brazilian scenes
KINDS = (("tensile", "cracks_tensile"), ("shear", "cracks_shear"))
# A snapshot stands for a requested time when it is this close (relative to the snapshot spacing).
SNAPSHOT_MATCH = 0.5


def series_cases(h, study_dir):
    """{series: [(case, run_dir)]} in the table's order."""
    table = h.read_columns(os.path.join(study_dir, "study.csv"))
    if not table:
        h.fail(f"{study_dir}/study.csv: no cases")
    out = {}
    for case, series, run_dir in zip(table["case"], table["series"], table["run_dir"]):
        out.setdefault(series, []).append((case, os.path.join(study_dir, run_dir)))
    return out


def case_label(case, run_dir):
    """The case's name, and the run it shows where it repeats another case's scene (its run
    directory is that case's), e.g. "impact-case08 (= impact-case04)"."""
    run = os.path.basename(os.path.normpath(run_dir))
    return case if run == case else f"{case} (= {run})"


def run_table(h, run_dir, name):
    """A CSV file of a run as columns, or None if the run has not written it (or no rows yet)."""
    path = os.path.join(run_dir, name)
    return (h.read_columns(path) or None) if os.path.exists(path) else None


def draw_counts(h, series, cases, out_dir, save):
    figure, axes = plt.subplots(2, 2, figsize=(12, 8), sharex=True)
    width = None  # µs, the intervals' length (the series' cases share it); None: nothing drawn
    for case, run_dir in cases:
        history = run_table(h, run_dir, "history.csv")
        intervals = run_table(h, run_dir, "crack_intervals.csv")
        if history is None or intervals is None:
            continue  # not run (yet): the other cases of the series are still drawn
        t = h.numbers(history, "t") * MICROSECONDS
        edges = np.concatenate((h.numbers(intervals, "interval_start")[:1], h.numbers(intervals, "interval_end")))
        width = (edges[1] - edges[0]) * MICROSECONDS
        for column, (kind, key) in enumerate(KINDS):
            axes[0][column].plot(t, h.numbers(history, key), label=case_label(case, run_dir))
            axes[1][column].stairs(h.numbers(intervals, kind), edges * MICROSECONDS, label=case_label(case, run_dir))
    if width is None:
        plt.close(figure)
        return
    for column, (kind, _) in enumerate(KINDS):
        axes[0][column].set_title(f"{series}: cumulative {kind} cracks")
        axes[1][column].set_title(f"new {kind} cracks per {width:g} µs")
        axes[1][column].set_xlabel("time (µs)")
        axes[0][column].set_ylabel("cracks (broken virtual joints)")
        axes[1][column].set_ylabel("new cracks")
    for row in axes:
        for a in row:
            a.grid(alpha=0.3)
            a.legend(fontsize="small", ncol=2)
    save(figure, os.path.join(out_dir, f"cracks_{series}.png"))


def nearest_snapshot(snapshots, t):
    """The snapshot standing for time t, or None if the run has none near it."""
    if not snapshots:
        return None
    spacing = np.median(np.diff([s[0] for s in snapshots])) if len(snapshots) > 1 else 0.0
    time, path = min(snapshots, key=lambda s: abs(s[0] - t))
    return (time, path) if abs(time - t) <= SNAPSHOT_MATCH * spacing else None


def draw_patterns(h, series, cases, times, out_dir, save):
    figure, axes = plt.subplots(len(cases), len(times), figsize=(3.2 * len(times), 3.2 * len(cases)),
                                squeeze=False)
    collections = []
    for row, (case, run_dir) in enumerate(cases):
        snapshots = h.read_snapshots(run_dir)
        for column, t in enumerate(times):
            a = axes[row][column]
            a.set_xticks([])
            a.set_yticks([])
            if column == 0:
                a.set_ylabel(case_label(case, run_dir))
            if row == 0:
                a.set_title(f"{t * MICROSECONDS:.0f} µs")
            found = nearest_snapshot(snapshots, t)
            if found is None:
                a.text(0.5, 0.5, "no snapshot", ha="center", va="center", transform=a.transAxes)
                continue
            collections.append(h.draw_pattern(a, found[1]))
    if not collections:
        plt.close(figure)
        return
    h.share_sigma1_scale(figure, axes, collections)
    save(figure, os.path.join(out_dir, f"patterns_{series}.png"))


def draw_loading(h, series, cases, out_dir, save):
    figure, axes = plt.subplots(figsize=(7, 4.5))
    drawn = False
    for case, run_dir in cases:
        loading = run_table(h, run_dir, "loading.csv")
        if loading is None:
            continue
        mask = np.array([b == LOADED_BODY for b in loading["body"]])
        if not mask.any():
            continue
        drawn = True
        axes.plot(-h.numbers(loading, "displacement_y")[mask] * MILLIMETRES,
                  np.abs(h.numbers(loading, "force_y")[mask]) * KILONEWTONS, label=case)
    if not drawn:
        plt.close(figure)
        return
    axes.set_xlabel("platen displacement (mm)")
    axes.set_ylabel("platen force (kN per m thickness)")
    axes.set_title(f"{series}: force against displacement")
    axes.grid(alpha=0.3)
    axes.legend()
    save(figure, os.path.join(out_dir, f"loading_{series}.png"))


def tensile_strength(run_dir):
    """σt of the disc's virtual joints (Pa) as the run read its scene, or None."""
    path = os.path.join(run_dir, "scene.resolved.toml")
    if not os.path.exists(path):
        return None
    with open(path, "rb") as handle:
        scene = tomllib.load(handle)
    joint_set = scene.get("bodies", {}).get("disc", {}).get("virtual_joints")
    return scene.get("joints", {}).get(joint_set, {}).get("tensile_strength")


def draw_gauges(h, case, run_dir, out_dir, save):
    gauges = run_table(h, run_dir, "gauges.csv")
    if gauges is None:
        return
    figure, axes = plt.subplots(figsize=(8, 4.5))
    h.draw_gauge_lines(axes, gauges)
    strength = tensile_strength(run_dir)
    if strength is not None:
        axes.axhline(strength * MEGAPASCAL, color="k", linestyle="--", linewidth=1.0,
                     label=f"σt of the virtual joints ({strength * MEGAPASCAL:g} MPa)")
    axes.set_xlabel("time (µs)")
    axes.set_ylabel("σ1 (MPa, tension positive)")
    axes.set_title(f"{case}: maximum principal stress at the gauges")
    axes.grid(alpha=0.3)
    axes.legend(ncol=2, fontsize="small")
    save(figure, os.path.join(out_dir, f"gauges_{case}.png"))


def completed_runs(h, series, cases):
    """The completed runs of a series as the sensitivity study reads them (read_run)."""
    return [r for r in (sensitivity.read_run(h, case, [series], run_dir) for case, run_dir in cases) if r]


def draw_brazilian_patterns(h, series, runs, out_dir, save):
    """Per completed run: the pattern at the snapshot nearest its peak force and at its last one."""
    rows = []
    for run in runs:
        snapshots = h.read_snapshots(run["dir"])
        peak = sensitivity.peak_force(run)
        if not snapshots or peak is None:
            continue
        at_peak = min(snapshots, key=lambda s: abs(s[0] - peak[1]))
        rows.append((run["case"], sensitivity.platen_speed(run), ((at_peak, "peak"), (snapshots[-1], "end"))))
    if not rows:
        return
    figure, axes = plt.subplots(len(rows), 2, figsize=(8.0, 3.8 * len(rows)), squeeze=False)
    collections = []
    for row, (case, speed, panels) in enumerate(rows):
        for column, ((time, path), label) in enumerate(panels):
            a = axes[row][column]
            a.set_xticks([])
            a.set_yticks([])
            a.set_title(f"{case}, {label}\n{time * MICROSECONDS:.0f} µs, platen travel "
                        f"{speed * time * MILLIMETRES:.3f} mm", fontsize="small")
            collections.append(h.draw_pattern(a, path))
    h.share_sigma1_scale(figure, axes, collections)
    save(figure, os.path.join(out_dir, f"patterns_{series}.png"))


def slit_angle(run):
    return run["scene"].get("geometry", {}).get("slit_angle")


def brazilian_analysis(h, groups, runs, study_dir, out_dir, save):
    """analysis.md of the Brazilian series (groups: {series: [(case, run_dir)]}, runs: {series:
    [completed run]}); written whatever has run, as study.md links it."""
    md = "# The source study: Brazilian discs\n\n"
    if not any(runs.values()):
        sensitivity.write_whole(os.path.join(study_dir, "analysis.md"),
                                md + "No Brazilian disc of this study has completed yet.\n")
        return
    md += ("Read from the completed runs by `ddafrac_plots.py study-source`. Indirect tensile strength: "
           "σt = k·2P/(πD) per unit thickness, k the flattened-disc factor of Wang et al. (2004, Int. J. Rock "
           "Mech. Min. Sci. 41, 245–253) for the flats' central angle (k = 1: the Brazilian formula); the "
           "pre-cracked discs' σt is the same formula applied to a disc with a slit, for comparison only.\n\n")
    missing = [case for series, cases in groups.items() if series in BRAZILIAN_SERIES for case, _ in cases
               if case not in {r["case"] for r in runs[series]}]
    if missing:
        md += "Not completed (left out): " + ", ".join(missing) + ".\n\n"
    if runs.get("flattened"):
        md += sensitivity.mesh_section(h, runs["flattened"], out_dir, save)
    if runs.get("precracked"):
        precracked = sorted(runs["precracked"], key=lambda r: slit_angle(r) or 0.0)
        md += "## Pre-cracked discs\n\n" + sensitivity.brazilian_table(h, precracked, "slit angle (°)", slit_angle,
                                                                         "{:.0f}") + "\n"
    sensitivity.write_whole(os.path.join(study_dir, "analysis.md"), md)


def draw_study(args, h, save):
    out_dir = os.path.join(args.study_dir, "figures")
    os.makedirs(out_dir, exist_ok=True)
    times = [float(t) for t in args.times.split(",") if t]
    groups = series_cases(h, args.study_dir)
    brazilian = {series: completed_runs(h, series, cases) for series, cases in groups.items()
                 if series in BRAZILIAN_SERIES}
    for series, cases in groups.items():
        if series in IMPACT_SERIES:
            draw_counts(h, series, cases, out_dir, save)
            draw_patterns(h, series, cases, times, out_dir, save)
        elif series in BRAZILIAN_SERIES:
            draw_loading(h, series, cases, out_dir, save)
            draw_brazilian_patterns(h, series, brazilian[series], out_dir, save)
        for case, run_dir in cases:
            if case == args.gauge_case:
                draw_gauges(h, case, run_dir, out_dir, save)
    brazilian_analysis(h, groups, brazilian, args.study_dir, out_dir, save)


def register(commands, helpers, save):
    """helpers: the ddafrac_plots module (read_columns, numbers, read_snapshots, draw_pattern,
    draw_gauge_lines, fail)."""
    study = commands.add_parser("study-source", help="figures of ddafrac study source")
    study.add_argument("study_dir")
    study.add_argument("--times", default="3e-4,9e-4,1.8e-3", help="comma-separated times (s) of the pattern grids")
    study.add_argument("--gauge-case", default="impact-case04", help="the case whose gauge σ1 histories are drawn")
    study.set_defaults(draw=lambda args: draw_study(args, helpers, save))
