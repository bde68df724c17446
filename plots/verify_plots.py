"""Figures of the static Brazilian-disc comparison (DDA twin vs FEM vs Hondros) and of the
mesh-convergence study.

Subcommands of ddafrac_plots.py (registered by register()):

    ddafrac_plots.py verify DIR               DIR/profiles.csv -> profile_loaded.png, profile_horizontal.png
    ddafrac_plots.py convergence CSV PNG      convergence.csv -> log-log error against DDA wall time

Every PNG is written whole (temporary name, then rename) by the caller's save().
"""

import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

MILLIMETRE = 1e3
MEGAPASCAL = 1e-6
SOURCES = [  # column prefix in profiles.csv -> style
    ("fem", dict(color="black", linewidth=1.5, label="FEM")),
    ("ana", dict(color="tab:blue", linewidth=1.0, linestyle="--", label="Hondros (analytic)")),
    ("dda", dict(color="tab:red", linewidth=1.0, drawstyle="steps-mid", label="DDA (block stress)")),
]


def read_rows(path):
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


def draw_profiles(args, save):
    rows = read_rows(os.path.join(args.dir, "profiles.csv"))
    if not rows:
        raise SystemExit(f"ddafrac_plots: {args.dir}/profiles.csv is empty")
    for profile, axis_name in (("loaded", "y (mm), along the loaded diameter x = 0"),
                               ("horizontal", "x (mm), along the horizontal diameter y = 0")):
        part = [r for r in rows if r["profile"] == profile]
        if not part:
            continue
        s = np.array([float(r["s"]) for r in part]) * MILLIMETRE
        figure, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharex=True)
        for ax, component, title in ((axes[0], "sxx", "σxx"), (axes[1], "syy", "σyy")):
            for prefix, style in SOURCES:
                values = np.array([float(r[f"{prefix}_{component}"]) for r in part]) * MEGAPASCAL
                if np.all(np.isnan(values)):
                    continue  # no analytic solution for this geometry
                ax.plot(s, values, **style)
            ax.set_xlabel(axis_name)
            ax.set_ylabel(f"{title} (MPa)")
            ax.set_title(f"{title}, {profile} diameter")
            ax.grid(True, alpha=0.3)
        axes[0].legend(fontsize="small")
        save(figure, os.path.join(args.dir, f"profile_{profile}.png"))


def draw_convergence(args, save):
    rows = read_rows(args.table)
    if not rows:
        raise SystemExit(f"ddafrac_plots: {args.table} is empty")
    fixed = {"target", "blocks", "steps", "dda_wall", "fem_refine", "fem_dofs", "fem_wall", "fem_l2_vs_analytic", "passed"}
    errors = [k for k in rows[0] if k not in fixed]
    wall = np.array([float(r["dda_wall"]) for r in rows])
    blocks = np.array([float(r["blocks"]) for r in rows])
    figure, axes = plt.subplots(1, 2, figsize=(11, 4.4))
    for name in errors:
        values = np.array([float(r[name]) for r in rows])
        good = values > 0
        if good.sum() < 1:
            continue
        line, = axes[0].loglog(wall[good], values[good], marker="o", label=name)
        h = 1.0 / np.sqrt(blocks[good])
        axes[1].loglog(h, values[good], marker="o", color=line.get_color(), label=name)
        if good.sum() >= 2:
            rate = np.polyfit(np.log(h), np.log(values[good]), 1)[0]
            line.set_label(f"{name} (rate {rate:.2f} in h)")
    fem = np.array([float(r.get("fem_l2_vs_analytic", "nan")) for r in rows])
    if np.any(fem > 0):
        fem_wall = np.array([float(r["fem_wall"]) for r in rows])
        axes[0].loglog(fem_wall[fem > 0], fem[fem > 0], color="black", linestyle="--", marker="s",
                       label="FEM vs analytic field L2 (against FEM wall time)")
    for b, w in zip(blocks, wall):
        axes[0].annotate(f"{int(b)}", (w, axes[0].get_ylim()[0]), fontsize="x-small", alpha=0.6,
                         textcoords="offset points", xytext=(0, 3), ha="center")
    axes[0].set_xlabel("wall time (s): DDA (circles), FEM (squares)")
    axes[0].set_ylabel("relative error")
    axes[0].set_title("error against run time (labels: blocks)")
    axes[1].set_xlabel("h ~ 1/sqrt(blocks)")
    axes[1].set_ylabel("relative error")
    axes[1].set_title("error against block size")
    for ax in axes:
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize="x-small")
    save(figure, args.png)


def register(commands, save):
    verify = commands.add_parser("verify", help="profiles of a static comparison (ddafrac verify)")
    verify.add_argument("dir")
    verify.set_defaults(draw=lambda args: draw_profiles(args, save))
    convergence = commands.add_parser("convergence", help="error against run time of ddafrac study convergence")
    convergence.add_argument("table")
    convergence.add_argument("png")
    convergence.set_defaults(draw=lambda args: draw_convergence(args, save))

