"""Figures of the contact-free impact comparison (DDA twin vs FEM) and of the penalty study.

Subcommands of ddafrac_plots.py (registered by register()):

    ddafrac_plots.py verify-impact DIR      DIR/impact_gauges.csv -> impact_gauges_syy.png, impact_gauges_s1.png
                                            (`verify DIR` does the same when DIR holds impact_gauges.csv)
    ddafrac_plots.py penalty-study DIR      DIR/penalty_study.csv -> penalty_study.png

Every PNG is written whole (temporary name, then rename) by the caller's save().
"""

import csv
import os
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

MICROSECONDS = 1e6
MEGAPASCAL = 1e-6
STYLES = {  # model label in impact_gauges.csv -> line style
    "FEM": dict(color="black", linewidth=1.6, label="FEM P2, Newmark (¼, ½)"),
    "DDA": dict(color="tab:red", linewidth=1.2, label="DDA twin"),
    "FEM-half-one": dict(color="tab:blue", linewidth=0.9, linestyle="--", label="FEM, Newmark (½, 1) at the DDA's dt"),
}


def read_histories(path):
    """impact_gauges.csv -> {(model, gauge): (t, syy, s1)} in the order of the file."""
    columns = defaultdict(lambda: ([], [], []))
    gauges = []
    with open(path, newline="") as handle:
        for row in csv.DictReader(handle):
            key = (row["model"], row["gauge"])
            if row["gauge"] not in gauges:
                gauges.append(row["gauge"])
            t, syy, s1 = columns[key]
            t.append(float(row["t"]))
            syy.append(float(row["syy"]))
            s1.append(float(row["s1"]))
    return {k: tuple(np.array(c) for c in v) for k, v in columns.items()}, gauges


def draw_overlay(histories, gauges, component, title, path, save):
    index = {"syy": 1, "s1": 2}[component]
    columns = 4
    rows = (len(gauges) + columns - 1) // columns
    figure, axes = plt.subplots(rows, columns, figsize=(3.3 * columns, 2.6 * rows), sharex=True, squeeze=False)
    models = [m for m in STYLES if any(k[0] == m for k in histories)]
    for n, gauge in enumerate(gauges):
        ax = axes[n // columns][n % columns]
        for model in models:
            if (model, gauge) not in histories:
                continue
            series = histories[(model, gauge)]
            ax.plot(series[0] * MICROSECONDS, series[index] * MEGAPASCAL, **STYLES[model])
        ax.set_title(f"gauge {gauge}", fontsize="medium")
        ax.grid(alpha=0.3)
        if n % columns == 0:
            ax.set_ylabel(f"{title} (MPa)")
        if n // columns == rows - 1:
            ax.set_xlabel("time (µs)")
    for n in range(len(gauges), rows * columns):
        axes[n // columns][n % columns].axis("off")
    handles, labels = axes[0][0].get_legend_handles_labels()
    figure.legend(handles, labels, loc="upper center", ncol=len(labels), fontsize="small", bbox_to_anchor=(0.5, 1.03))
    figure.tight_layout()
    save(figure, path)


def draw_verify_impact(args, save):
    path = os.path.join(args.dir, "impact_gauges.csv")
    histories, gauges = read_histories(path)
    draw_overlay(histories, gauges, "syy", "σyy", os.path.join(args.dir, "impact_gauges_syy.png"), save)
    draw_overlay(histories, gauges, "s1", "σ1", os.path.join(args.dir, "impact_gauges_s1.png"), save)


def draw_penalty_study(args, save):
    """penalty_study.csv: one row per (kn/E, dt): errors against the FEM, CG iterations, wall time."""
    with open(os.path.join(args.dir, "penalty_study.csv"), newline="") as handle:
        rows = list(csv.DictReader(handle))
    by_dt = defaultdict(list)
    for row in rows:
        by_dt[float(row["dt"])].append(row)
    figure, axes = plt.subplots(1, 5, figsize=(21, 3.8))
    panels = [
        ("mean_rms_over_peak", "mean RMS/peak σyy over gauges", False),
        ("mean_abs_peak_error", "mean |peak σyy error| over gauges", False),
        ("max_abs_arrival_error", "largest |arrival error| (checked gauges)", False),
        ("cg_per_step", "CG iterations per step", True),
        ("dda_wall", "DDA wall time (s)", True),
    ]
    for dt in sorted(by_dt):
        series = sorted(by_dt[dt], key=lambda r: float(r["kn_over_E"]))
        ratio = np.array([float(r["kn_over_E"]) for r in series])
        for ax, (key, _, _) in zip(axes, panels):
            ax.plot(ratio, [float(r[key]) for r in series], marker="o", label=f"dt = {dt:.0e} s")
    for ax, (key, label, log_y) in zip(axes, panels):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("kn / E")
        ax.set_title(label, fontsize="medium")
        ax.grid(alpha=0.3, which="both")
        ax.axvline(0.35e9 / 10.53e9, color="grey", linestyle=":", linewidth=1)
    axes[0].text(0.35e9 / 10.53e9, axes[0].get_ylim()[0], " study's kn", color="grey", fontsize="small",
                 rotation=90, va="bottom")
    axes[0].legend(fontsize="small")
    figure.tight_layout()
    save(figure, os.path.join(args.dir, "penalty_study.png"))


def register(commands, save):
    """Adds the subcommands to ddafrac_plots.py's argparse subparsers; save(figure, path) writes whole.

    `verify DIR` (registered before this, by verify_plots) draws the impact overlays instead of the
    static profiles when DIR holds impact_gauges.csv: `ddafrac verify` calls it for every scene."""
    static_verify = commands.choices.get("verify")
    if static_verify is not None:
        draw_static = static_verify.get_default("draw")

        def draw_any(args):
            if os.path.exists(os.path.join(args.dir, "impact_gauges.csv")):
                draw_verify_impact(args, save)
            else:
                draw_static(args)

        static_verify.set_defaults(draw=draw_any)
    verify = commands.add_parser("verify-impact", help="DDA twin vs FEM gauge overlays of a verify run")
    verify.add_argument("dir")
    verify.set_defaults(draw=lambda args: draw_verify_impact(args, save))
    penalty = commands.add_parser("penalty-study", help="figure of a penalty/time-step study table")
    penalty.add_argument("dir")
    penalty.set_defaults(draw=lambda args: draw_penalty_study(args, save))
