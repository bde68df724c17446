#!/usr/bin/python3
"""Figures of ddafrac run directories, drawn with matplotlib.

ddafrac calls this after a run; it can also be run by hand to redraw or restyle figures:

    ddafrac_plots.py run RUN_DIR [--times T1,T2,...] [--crack-interval S]
    ddafrac_plots.py sweep TABLE.csv --out DIR
    ddafrac_plots.py study-source STUDY_DIR [--times T1,T2,...]   (study_source_plots.py)
    ddafrac_plots.py study-sensitivity STUDY_DIR                  (study_sensitivity_plots.py)
    ddafrac_plots.py impact-series STUDY_DIR... --out FIGURE.png   (impact_series_plots.py)

It reads only the files a run writes (history.csv, gauges.csv, cracks.csv, vtk/run.pvd and the
snapshots it lists, summary.json) and writes PNG files into RUN_DIR/figures/, each whole
(temporary name, then rename).
"""

import argparse
import csv
import json
import os
import sys
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402

MICROSECONDS = 1e6  # µs per s
MEGAPASCAL = 1e-6  # MPa per Pa
DPI = 150
VTK_LINE = 3
CRACK_COLOURS = {1: "black", 2: "tab:blue"}  # crack_type 1 = tensile, 2 = shear
NO_JOINTS_GREY = "0.8"  # matplotlib grey level of blocks without virtual joints in the utilisation map
CRACK_NAMES = {1: "tensile", 2: "shear"}


def fail(message):
    print(f"ddafrac_plots: {message}", file=sys.stderr)
    sys.exit(2)


def read_columns(path):
    """A CSV file with a header row as a dict of column name -> list of strings."""
    with open(path, newline="") as handle:
        rows = list(csv.DictReader(handle))
    if not rows:
        return {}
    return {key: [row[key] for row in rows] for key in rows[0]}


def numbers(columns, key):
    return np.array([float(v) for v in columns[key]])


def save(figure, path):
    """Writes the figure whole: a temporary name, then rename."""
    temporary = os.path.join(os.path.dirname(path), "." + os.path.basename(path) + ".partial.png")
    figure.savefig(temporary, dpi=DPI, bbox_inches="tight")
    plt.close(figure)
    os.replace(temporary, path)
    print(f"wrote {path}")


# The energy ledger as stacked areas (stored, then dissipated), against the energy supplied.
LEDGER_STORED = (("kinetic_energy", "kinetic"), ("strain_energy", "strain"), ("contact_energy", "contact springs"),
                 ("support_energy", "support springs"))
LEDGER_DISSIPATED = (("friction_dissipation", "friction"), ("joint_break_loss", "joint breaks"),
                     ("numerical_dissipation", "time scheme"), ("damping_dissipation", "mass damping"))
LEDGER_WORK = ("work_gravity", "work_loads", "work_supports")
# Layers drawn only where a run has them: the column exists (runs written before it did not) and is not all zero.
LEDGER_OPTIONAL = ("damping_dissipation",)


def plot_energy(history, out_dir, title):
    t = numbers(history, "t") * MICROSECONDS
    if "balance_error" not in history:  # a run written before the ledger: energies alone
        figure, axes = plt.subplots(figsize=(7, 4))
        for key, label in LEDGER_STORED[:3]:
            if key in history:
                axes.plot(t, numbers(history, key), label=label)
        axes.set_xlabel("time (µs)")
        axes.set_ylabel("energy (J per m thickness)")
        axes.set_title(f"{title}: energies")
        axes.grid(alpha=0.3)
        axes.legend()
        save(figure, os.path.join(out_dir, "energy.png"))
        return
    dissipated = [(key, label) for key, label in LEDGER_DISSIPATED
                  if key in history and (key not in LEDGER_OPTIONAL or numbers(history, key).any())]
    layers = [numbers(history, key) for key, _ in LEDGER_STORED + tuple(dissipated)]
    labels = [label for _, label in LEDGER_STORED] + [f"dissipated: {label}" for _, label in dissipated]
    stored0 = sum(numbers(history, key)[0] for key, _ in LEDGER_STORED)
    supplied = stored0 + sum(numbers(history, key) for key in LEDGER_WORK)
    balance = numbers(history, "balance_error")
    figure, (axes, error_axes) = plt.subplots(2, 1, figsize=(7, 6), sharex=True,
                                              gridspec_kw={"height_ratios": [3, 1]})
    axes.stackplot(t, layers, labels=labels, alpha=0.85)
    axes.plot(t, supplied, "k--", linewidth=1.2, label="supplied: initial + work")
    axes.set_ylabel("energy (J per m thickness)")
    axes.set_title(f"{title}: energy ledger")
    axes.grid(alpha=0.3)
    axes.legend(fontsize=7, loc="lower left")
    error_axes.plot(t, 100.0 * balance, color="tab:red")
    error_axes.axhline(0.0, color="k", linewidth=0.6)
    error_axes.set_xlabel("time (µs)")
    error_axes.set_ylabel("balance error (%)")
    error_axes.grid(alpha=0.3)
    save(figure, os.path.join(out_dir, "energy.png"))


def plot_crack_counts(history, crack_interval, out_dir, title):
    """Cumulative counts over time and the number of new cracks per interval."""
    t = numbers(history, "t")
    kinds = [k for k in ("cracks_total", "cracks_tensile", "cracks_shear") if k in history]
    figure, (cumulative, incremental) = plt.subplots(1, 2, figsize=(11, 4))
    edges = np.arange(0.0, t[-1] + crack_interval, crack_interval)
    width = crack_interval * MICROSECONDS / (len(kinds) + 1)
    for i, key in enumerate(kinds):
        counts = numbers(history, key)
        label = key.replace("cracks_", "")
        cumulative.plot(t * MICROSECONDS, counts, label=label)
        at_edges = np.interp(edges, t, counts, left=0.0)
        incremental.bar(edges[1:] * MICROSECONDS - crack_interval * MICROSECONDS + (i + 0.5) * width,
                        np.diff(at_edges), width=width, label=label, align="edge")
    cumulative.set_xlabel("time (µs)")
    cumulative.set_ylabel("cracks (broken virtual joints)")
    cumulative.set_title(f"{title}: cumulative cracks")
    incremental.set_xlabel("time (µs)")
    incremental.set_ylabel(f"new cracks per {crack_interval * MICROSECONDS:g} µs")
    incremental.set_title("incremental cracks")
    for axes in (cumulative, incremental):
        axes.grid(alpha=0.3)
        axes.legend()
    save(figure, os.path.join(out_dir, "crack_counts.png"))


def draw_gauge_lines(axes, gauges):
    """σ1 (MPa) against time (µs) of every gauge of a gauges.csv, one line each."""
    t = numbers(gauges, "t") * MICROSECONDS
    sigma1 = numbers(gauges, "sigma1") * MEGAPASCAL
    names = gauges["gauge"]
    for name in dict.fromkeys(names):  # in first-seen order
        mask = np.array([n == name for n in names])
        axes.plot(t[mask], sigma1[mask], label=name)


def plot_gauges(gauges, out_dir, title):
    figure, axes = plt.subplots(figsize=(8, 4.5))
    draw_gauge_lines(axes, gauges)
    axes.set_xlabel("time (µs)")
    axes.set_ylabel("σ1 (MPa, tension positive)")
    axes.set_title(f"{title}: maximum principal stress at the gauges")
    axes.grid(alpha=0.3)
    axes.legend(ncol=2)
    save(figure, os.path.join(out_dir, "gauges_sigma1.png"))


def read_snapshots(run_dir):
    """(time, path) of every snapshot listed in run.pvd (paths in it are relative to it)."""
    for pvd in (os.path.join(run_dir, "run.pvd"), os.path.join(run_dir, "vtk", "run.pvd")):
        if os.path.exists(pvd):
            root = ET.parse(pvd).getroot()
            return [(float(d.get("timestep")), os.path.join(os.path.dirname(pvd), d.get("file")))
                    for d in root.iter("DataSet")]
    return []


def read_vtu(path):
    """Points, cells (lists of point indices), VTK cell types and cell data arrays of an ASCII .vtu."""
    root = ET.parse(path).getroot()
    piece = root.find("UnstructuredGrid/Piece")

    def array(parent, name=None):
        for node in piece.find(parent).iter("DataArray"):
            if name is None or node.get("Name") == name:
                components = int(node.get("NumberOfComponents", "1"))
                values = np.array(node.text.split(), dtype=float)
                return values.reshape(-1, components) if components > 1 else values
        return None

    points = array("Points")[:, :2]
    connectivity = array("Cells", "connectivity").astype(int)
    offsets = array("Cells", "offsets").astype(int)
    types = array("Cells", "types").astype(int)
    starts = np.concatenate(([0], offsets[:-1]))
    cells = [connectivity[s:e] for s, e in zip(starts, offsets)]
    data = {node.get("Name"): node for node in piece.find("CellData").iter("DataArray")}
    cell_data = {name: array("CellData", name) for name in data}
    return points, cells, types, cell_data


def draw_pattern(axes, path, limit=None):
    """Blocks of a snapshot file coloured by σ1 (MPa) with the broken joints drawn over them
    (draw_snapshot); returns the blocks' collection (for a colour bar)."""
    return draw_snapshot(axes, read_vtu(path), limit)


def share_sigma1_scale(figure, axes, collections):
    """One σ1 colour scale for a grid of patterns (draw_pattern's collections), the widest of
    theirs, so that the panels compare; and its colour bar beside the grid."""
    limit = max(c.get_clim()[1] for c in collections)
    for c in collections:
        c.set_clim(-limit, limit)
    figure.colorbar(collections[0], ax=axes, shrink=0.6, label="σ1 (MPa, tension positive)")


def draw_snapshot(axes, snapshot, limit=None, field="sigma1"):
    """Blocks of a snapshot (read_vtu) coloured by a cell field with the broken joints drawn over
    them: σ1 (MPa, blue to red about zero up to `limit`, by default its 99th percentile) or
    joint_utilisation (0 to 1, the strength; grey where a block has no virtual joints). Returns the blocks' collection (for a colour bar)."""
    points, cells, types, cell_data = snapshot
    polygons = [points[c] for c, k in zip(cells, types) if k != VTK_LINE]
    polygon_index = [i for i, k in enumerate(types) if k != VTK_LINE]
    if field == "sigma1":
        values = cell_data["sigma1"][polygon_index] * MEGAPASCAL
        if limit is None:
            limit = max(1e-12, np.percentile(np.abs(values), 99))
        colours = {"cmap": "RdBu_r", "clim": (-limit, limit)}
    else:
        # A block without virtual joints (a platen) has no ratio: negative, drawn grey.
        values = np.ma.masked_less(cell_data[field][polygon_index], 0.0)
        cmap = plt.get_cmap("magma_r").copy()
        cmap.set_bad(NO_JOINTS_GREY)
        colours = {"cmap": cmap, "clim": (0.0, 1.0)}
    collection = PolyCollection(polygons, array=values, edgecolors="face", linewidths=0.2, **colours)
    axes.add_collection(collection)
    crack_index = [i for i, k in enumerate(types) if k == VTK_LINE]
    if crack_index:
        kinds = cell_data.get("crack_type")
        for kind, colour in CRACK_COLOURS.items():
            segments = [points[cells[i]] for i in crack_index if kinds is None or int(kinds[i]) == kind]
            if segments:
                axes.add_collection(LineCollection(segments, colors=colour, linewidths=1.2,
                                                   label=f"{CRACK_NAMES[kind]} ({len(segments)})"))
        axes.legend(loc="upper right", fontsize="small")
    axes.autoscale_view()
    axes.set_aspect("equal")
    return collection


def time_label(t):
    """A run's time for a title: µs, or s for a static run's load parameter (t ≥ 0.1 s)."""
    return f"{t:g} s" if t >= 0.1 else f"{t * MICROSECONDS:.0f} µs"


# The pictures of a snapshot at each figure time: the cell field, what the title calls it, the
# colour bar's label and the file name's stem.
SNAPSHOT_FIGURES = (
    ("sigma1", "cracks over σ1", "σ1 (MPa, tension positive)", "crack_pattern"),
    ("joint_utilisation", "joint utilisation", "max(r1, r2) of the block's intact joints (1: strength)",
     "utilisation"),
)


def plot_snapshot(snapshot_time, path, out_dir, title):
    """The snapshot's pictures (SNAPSHOT_FIGURES), blocks coloured by the field with the broken joints
    drawn over them; a field the snapshot does not carry (written before it existed) is skipped."""
    snapshot = read_vtu(path)
    for field, what, colour_label, stem in SNAPSHOT_FIGURES:
        if field not in snapshot[3]:
            continue
        figure, axes = plt.subplots(figsize=(7, 7))
        collection = draw_snapshot(axes, snapshot, field=field)
        figure.colorbar(collection, ax=axes, shrink=0.8, label=colour_label)
        axes.set_xlabel("x (m)")
        axes.set_ylabel("y (m)")
        axes.set_title(f"{title}: {what} at t = {time_label(snapshot_time)}")
        save(figure, os.path.join(out_dir, f"{stem}_{snapshot_time * MICROSECONDS:06.0f}us.png"))


def draw_run(args):
    run_dir = args.run_dir
    history_path = os.path.join(run_dir, "history.csv")
    if not os.path.exists(history_path):
        fail(f"{history_path}: no such file (is {run_dir} a ddafrac run directory?)")
    out_dir = os.path.join(run_dir, "figures")
    os.makedirs(out_dir, exist_ok=True)
    title = os.path.basename(os.path.normpath(run_dir))
    summary_path = os.path.join(run_dir, "summary.json")
    if os.path.exists(summary_path):
        with open(summary_path) as handle:
            title = json.load(handle).get("scene", {}).get("name", title)

    history = read_columns(history_path)
    if not history:
        fail(f"{history_path}: no rows")
    plot_energy(history, out_dir, title)
    if "cracks_total" in history:
        plot_crack_counts(history, args.crack_interval, out_dir, title)
    gauges_path = os.path.join(run_dir, "gauges.csv")
    if os.path.exists(gauges_path):
        gauges = read_columns(gauges_path)
        if gauges:
            plot_gauges(gauges, out_dir, title)
    snapshots = read_snapshots(run_dir)
    if snapshots:
        wanted = [float(t) for t in args.times.split(",") if t] if args.times else [snapshots[-1][0]]
        for t in wanted:
            snapshot_time, path = min(snapshots, key=lambda s: abs(s[0] - t))
            plot_snapshot(snapshot_time, path, out_dir, title)


def draw_sweep(args):
    """Cumulative and incremental crack counts of every case of a sweep, on shared axes."""
    table = read_columns(args.table)
    if not table:
        fail(f"{args.table}: no cases")
    os.makedirs(args.out, exist_ok=True)
    base = os.path.dirname(os.path.abspath(args.table))
    figure, (cumulative, incremental) = plt.subplots(1, 2, figsize=(12, 4.5))
    for case, run_dir in zip(table["case"], table["run_dir"]):
        history_path = os.path.join(base, run_dir, "history.csv")
        if not os.path.exists(history_path):
            continue
        history = read_columns(history_path)
        if "cracks_total" not in history:
            continue
        t = numbers(history, "t")
        total = numbers(history, "cracks_total")
        cumulative.plot(t * MICROSECONDS, total, label=case)
        edges = np.arange(0.0, t[-1] + args.crack_interval, args.crack_interval)
        at_edges = np.interp(edges, t, total, left=0.0)
        incremental.step(edges[1:] * MICROSECONDS, np.diff(at_edges), where="pre", label=case)
    cumulative.set_title("cumulative cracks")
    incremental.set_title(f"new cracks per {args.crack_interval * MICROSECONDS:g} µs")
    for axes in (cumulative, incremental):
        axes.set_xlabel("time (µs)")
        axes.grid(alpha=0.3)
        axes.legend(fontsize="small", ncol=2)
    save(figure, os.path.join(args.out, "sweep_cracks.png"))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    commands = parser.add_subparsers(dest="command", required=True)
    run = commands.add_parser("run", help="figures of one run directory")
    run.add_argument("run_dir")
    run.add_argument("--times", default="", help="comma-separated times (s) of crack-pattern pictures")
    run.add_argument("--crack-interval", type=float, default=150e-6, help="bin of incremental crack counts, s")
    run.set_defaults(draw=draw_run)
    sweep = commands.add_parser("sweep", help="comparison figures of a sweep table")
    sweep.add_argument("table")
    sweep.add_argument("--out", required=True)
    sweep.add_argument("--crack-interval", type=float, default=150e-6)
    sweep.set_defaults(draw=draw_sweep)
    import verify_plots  # noqa: E402  (beside this script)

    verify_plots.register(commands, save)
    import verify_dynamic_plots  # noqa: E402  (beside this script)

    verify_dynamic_plots.register(commands, save)
    import study_source_plots  # noqa: E402  (beside this script)

    study_source_plots.register(commands, sys.modules[__name__], save)
    import study_sensitivity_plots  # noqa: E402  (beside this script)

    study_sensitivity_plots.register(commands, sys.modules[__name__], save)
    import impact_series_plots  # noqa: E402  (beside this script)

    impact_series_plots.register(commands, sys.modules[__name__], save)
    args = parser.parse_args()
    args.draw(args)


if __name__ == "__main__":
    main()
