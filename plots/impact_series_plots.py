"""The impact series' crack measures against θ, γ and v0, one line per study directory: how the
source study's trends move with the mesh, the penalty or the joints' law (registered by
register() as a subcommand of ddafrac_plots.py):

    ddafrac_plots.py impact-series STUDY_DIR[+STUDY_DIR...] ... --out FIGURE.png [--labels A,B,...]

Each STUDY_DIR is a `ddafrac study source` or `ddafrac study sensitivity` directory; every
completed run of an impact disc listed in its study.csv counts, whatever the case is called.
Directories joined by "+" make one line (e.g. a series whose case 4 ran in another study). A
run's series follows from its scene: the θ series holds γ and v0 at case 4's values (cases 1–7),
the γ series θ and v0 (cases 4, 9, 10), the v0 series θ and γ (cases 4, 11–15), so case 4 is in
all three. The figure has a row per series that some directory has and a column per measure:
cracks (tensile and shear), crack length, the first crack and the first through-going crack
(a cross at the run's end where the disc did not split). A line's label is the directory's
median block count and joint stiffness unless --labels names them.
"""

import os
import statistics

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import study_sensitivity_plots as sensitivity  # noqa: E402  (beside this script)

MICROSECONDS = 1e6  # µs per s
MILLIMETRES = 1e3  # mm per m
IMPACT_GENERATOR = "impact_disc"
# Case 4 of the source study, where the three series meet: θ (°), γ, v0 (m/s).
CASE4 = {"θ": 45.0, "γ": 0.25, "v0": 3.5}
SAME = 1e-9  # relative tolerance of "the same value" for a scene's θ, γ and v0
SERIES = (("θ", "joint angle θ (°)"), ("γ", "slot length γ (of the diameter)"), ("v0", "impact speed v0 (m/s)"))


def parameters(run):
    """θ (°), γ and v0 (m/s) of an impact run's scene."""
    geometry = run["scene"].get("geometry", {})
    vx, vy = run["scene"].get("bodies", {}).get("disc", {}).get("velocity", [0.0, 0.0])
    return {"θ": geometry.get("joint_angle"), "γ": geometry.get("connectivity"), "v0": (vx * vx + vy * vy) ** 0.5}


def same(a, b):
    return a is not None and abs(a - b) <= SAME * max(1.0, abs(b))


def in_series(values, varied):
    """Whether a run's θ, γ, v0 put it in the series that varies `varied`: the others at case 4's."""
    return all(same(values[k], CASE4[k]) for k in CASE4 if k != varied)


def study_runs(h, study_dir):
    """The completed impact runs of a study directory, each once (a repeated case ran in the
    directory of the case it repeats)."""
    table = h.read_columns(os.path.join(study_dir, "study.csv"))
    if not table:
        h.fail(f"{study_dir}/study.csv: no cases")
    runs, seen = [], set()
    for case, series, run_dir in zip(table["case"], table["series"], table["run_dir"]):
        path = os.path.join(study_dir, run_dir)
        if path in seen:
            continue
        run = sensitivity.read_run(h, case, series.split("+"), path)
        if run is None or run["scene"].get("geometry", {}).get("generator") != IMPACT_GENERATOR:
            continue
        seen.add(path)
        runs.append(run)
    return runs


def default_label(runs):
    blocks = statistics.median(r["blocks"] for r in runs)
    stiffness = {round(r["kn"] / r["young"], 4) for r in runs if r["kn"] and r["young"]}
    kn = f", kn = {stiffness.pop():.3g}·E" if len(stiffness) == 1 else ""
    return f"{blocks:.0f} blocks{kn}"


def draw_series_row(axes, studies, varied, xlabel):
    """One row: the series' measures against its parameter, a line per study."""
    cracks, length, first, through = axes
    for label, runs in studies:
        series = sorted(((parameters(r)[varied], r) for r in runs if in_series(parameters(r), varied)),
                        key=lambda pair: pair[0])
        if not series:
            continue
        xs = [x for x, _ in series]
        metrics = [r["metrics"] for _, r in series]
        line, = cracks.plot(xs, [r["cracks"].get("tensile") for _, r in series], "o-", label=f"{label}, tensile")
        colour = line.get_color()
        cracks.plot(xs, [r["cracks"].get("shear") for _, r in series], "s--", color=colour, label=f"{label}, shear")
        length.plot(xs, [sensitivity.scaled(r["length"], MILLIMETRES) for _, r in series], "o-", color=colour,
                    label=label)
        first_points = [(x, m.get("first_crack_time")) for x, m in zip(xs, metrics) if m.get("first_crack_time")]
        if first_points:
            first.plot([x for x, _ in first_points], [t * MICROSECONDS for _, t in first_points], "o-", color=colour,
                       label=label)
        split = [(x, m.get("first_through_crack_time")) for x, m in zip(xs, metrics)]
        through.plot([x for x, t in split if t], [t * MICROSECONDS for _, t in split if t], "o-", color=colour,
                     label=label)
        whole = [(x, r["summary"].get("simulated_time")) for (x, r), (_, t) in zip(series, split) if not t]
        if whole:
            through.plot([x for x, _ in whole], [t * MICROSECONDS for _, t in whole], "x", color=colour,
                         markersize=9, label=f"{label}: no split by the end")
    cracks.set_yscale("symlog", linthresh=1.0)  # counts span 0 to hundreds
    for axis, ylabel in zip(axes, ("cracks at the end", "crack length at the end (mm)", "first crack (µs)",
                                   "first through-going crack (µs)")):
        axis.set_xlabel(xlabel)
        axis.set_ylabel(ylabel)
        axis.grid(alpha=0.3)
    cracks.legend(fontsize="x-small")
    through.legend(fontsize="x-small")


def draw_impact_series(args, h, save):
    labels = args.labels.split(",") if args.labels else []
    if labels and len(labels) != len(args.study_dirs):
        h.fail(f"--labels names {len(labels)} lines for {len(args.study_dirs)} study directories")
    studies = []
    for k, line in enumerate(args.study_dirs):
        runs = [run for study_dir in line.split("+") for run in study_runs(h, study_dir)]
        if not runs:
            h.fail(f"{line}: no completed impact runs")
        studies.append((labels[k] if labels else default_label(runs), runs))
    rows = [(varied, xlabel) for varied, xlabel in SERIES
            if any(in_series(parameters(r), varied) and not same(parameters(r)[varied], CASE4[varied])
                   for _, runs in studies for r in runs)]
    if not rows:
        h.fail("no run varies θ, γ or v0 from case 4's")
    figure, axes = plt.subplots(len(rows), 4, figsize=(18, 4.2 * len(rows)), squeeze=False)
    for row, (varied, xlabel) in zip(axes, rows):
        draw_series_row(row, studies, varied, xlabel)
    figure.tight_layout()
    save(figure, args.out)


def register(commands, helpers, save):
    """helpers: the ddafrac_plots module (read_columns, fail)."""
    series = commands.add_parser("impact-series",
                                 help="the impact series' crack measures against θ, γ, v0, a line per study directory")
    series.add_argument("study_dirs", nargs="+", metavar="STUDY_DIR[+STUDY_DIR...]",
                        help="study directories, one line each; directories joined by + make one line")
    series.add_argument("--out", required=True, help="the figure (PNG)")
    series.add_argument("--labels", default="", help="comma-separated names of the lines, one per STUDY_DIR")
    series.set_defaults(draw=lambda args: draw_impact_series(args, helpers, save))
