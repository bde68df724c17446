"""Figures and analysis of `ddafrac study sensitivity` (registered by register() as a subcommand
of ddafrac_plots.py):

    ddafrac_plots.py study-sensitivity STUDY_DIR

reads STUDY_DIR/study.csv (case, series = its families joined by "+", run_dir) and each run's
summary.json, scene.resolved.toml, history.csv, gauges.csv and loading.csv, and writes

    analysis.md                 per family: a table of the crack measures against the varied
                                parameter, the observed convergence orders (mesh), the indirect
                                tensile strength of every Brazilian run, and computed verdicts
    figures/mesh.png            case 4's crack measures against its block count
    figures/mesh_patterns_case04.png, figures/mesh_patterns_flattened.png
                                the crack patterns over σ1 at the end of each mesh's run
    figures/penalty.png         case 4's crack measures and gauge σ1 peaks against kn/E
    figures/timestep.png        case 4's crack measures against dt_max
    figures/slot_tips.png       case 4's crack measures against the element size at the slot's ends
    figures/rate.png            the flattened disc's force-displacement curves per platen speed,
                                and the peak force against speed
    figures/penalty_theta.png   the θ series' crack counts and lengths at the scene's kn and at 10·E
    figures/penalty_theta_patterns_knXE.png
                                the θ series' crack patterns over σ1 at the end, per kn/E = X
    figures/damping.png         the flattened disc's force-displacement curves per mass damping η,
                                and the peak force against η beside the static run's
    figures/spread.png          case 4's cracks and crack length against time in each run of the
                                spread family (its impact speed changed by a few millionths)
    figures/spread_flattened.png
                                the same for the flattened disc (its platen speed changed alike),
                                with the platen force against travel

Only runs that completed are analysed; the others are listed as missing. Every PNG and
analysis.md are written whole (temporary name, then rename).
"""

import json
import math
import os
import tomllib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

MICROSECONDS = 1e6  # µs per s
MILLIMETRES = 1e3  # mm per m
KILONEWTONS = 1e-3  # kN per N
MEGAPASCAL = 1e-6  # MPa per Pa
PERCENT = 100.0
LOADED_BODY = "top_platen"  # the prescribed platen of the Brazilian scenes
FIXED_BODY = "bottom_platen"  # the fixed platen: its force is the disc's, without the top platen's drag
CENTRE_GAUGE = "centre"  # the Brazilian scenes' gauge at the disc's centre
GAUGE_CASE = "case04"  # the impact case the families vary
# Slot widths: mesh.slot_end_size of a scene that leaves it out (meshes::MeshControl); a resolved
# scene lists only the values its files set.
DEFAULT_SLOT_END_SIZE = 1.0
# A measure whose relative change between meshes is at most this is taken as unchanged.
UNCHANGED = 0.01
# The observed orders that can mean convergence. Above: the blocks carry constant strain, so
# stresses converge like h and energies like h² at best, and the time integration is second
# order in dt; a crack measure cannot converge faster than what it is computed from, and a larger
# p from three runs says only that the last change happened to be much smaller. Below: the change
# shrinks by less than a fifth when h shrinks by √2, less than the spread of one run's crack
# measures (±10–20%, docs/results/sensitivity.md).
PLAUSIBLE_ORDERS = (0.5, 3.0)
# A measure whose values across a family differ by at most this (relative) is drawn as flat.
FLAT_RANGE = 1e-9
# Spread family: a measure that moves by at most this (relative) across its runs is reproducible
# (the runs differ by millionths; a crack result that moves by less than 1% is the physics').
REPRODUCIBLE = 0.01
PPM = 1e6  # millionths per unit
SPREAD_WIDEST_LINE, SPREAD_NARROWEST_LINE = 5.0, 1.0  # points: the spread figure's runs, first to last
# A loading rate is quasi-static when its peak force is within this of the static run's.
QUASI_STATIC_TOLERANCE = 0.02
# The platen force's ringing is measured as the RMS of its departure from a straight line over
# this part of the platen's travel to the first crack (after the start, before any crack).
RINGING_WINDOW = (0.2, 0.9)
# The kinetic/strain ratio is read from this fraction of the time to the peak on (before it,
# the strain energy is still near zero and the ratio means nothing).
RATIO_START_FRACTION = 0.1
# Case 4's crack measures: (label, function of the run record -> value or None).
# The node-model family's models (docs/design.md §4.6, §5): (intact_nodes, fracture_load) -> name.
NODE_MODEL_NAMES = {
    ("contact", "joint_springs"): "node contacts",
    ("contact", "block_stress"): "node contacts, stress criterion",
    ("tie", "block_stress"): "ties, stress criterion",
}

MEASURES = (
    ("cracks tensile", lambda r: r["cracks"].get("tensile")),
    ("cracks shear", lambda r: r["cracks"].get("shear")),
    ("crack length (mm)", lambda r: r["length"] * MILLIMETRES if r["length"] is not None else None),
    ("fragments", lambda r: r["metrics"].get("fragments")),
    ("largest fragment (%)", lambda r: r["largest"] * PERCENT if r["largest"] is not None else None),
    ("first crack (µs)", lambda r: scaled(r["metrics"].get("first_crack_time"), MICROSECONDS)),
    ("through crack (µs)", lambda r: scaled(r["metrics"].get("first_through_crack_time"), MICROSECONDS)),
)


def scaled(value, factor):
    return value * factor if value is not None else None


def cell(value, form="{:.3g}"):
    if value is None:
        return "–"
    text = form.format(value)
    # A "g" format turns 1050 into 1.05e+03 once it has more digits than its precision; a table
    # reads the rounded number better.
    return f"{float(text):.0f}" if "e+" in text else text


def flattened_disc_factor(flat_angle_degrees):
    """k of σt = k·2P/(πD) for a flattened disc whose flats span the central angle 2α (Wang et
    al. 2004, Int. J. Rock Mech. Min. Sci. 41, 245–253): k = (2cos³α + cosα + sinα/α)² /
    (8(cosα + sinα/α)) · α/sinα; k → 1 as the flats vanish (the Brazilian formula)."""
    a = math.radians(flat_angle_degrees) / 2.0
    if a == 0.0:
        return 1.0
    s = math.sin(a) / a
    return (2.0 * math.cos(a) ** 3 + math.cos(a) + s) ** 2 / (8.0 * (math.cos(a) + s)) / s


def read_run(h, case, families, run_dir):
    """What the analysis needs of one completed run, or None."""
    summary_path = os.path.join(run_dir, "summary.json")
    scene_path = os.path.join(run_dir, "scene.resolved.toml")
    if not (os.path.exists(summary_path) and os.path.exists(scene_path)):
        return None
    with open(summary_path) as handle:
        summary = json.load(handle)
    if summary.get("exit", {}).get("reason") != "completed":
        return None
    with open(scene_path, "rb") as handle:
        scene = tomllib.load(handle)
    metrics = summary.get("crack_metrics", {})
    bodies = metrics.get("bodies", [])
    tensile, shear = metrics.get("crack_length_tensile"), metrics.get("crack_length_shear")
    disc = scene.get("bodies", {}).get("disc", {})
    joints = scene.get("joints", {}).get(disc.get("virtual_joints"), {})
    material = scene.get("materials", {}).get(disc.get("material"), {})
    return {
        "case": case,
        "families": families,
        "dir": run_dir,
        "scene": scene,
        "summary": summary,
        "blocks": summary["scene"]["blocks"],
        "dt_max": summary["scene"]["dt_max"],
        "slot_end_size": scene.get("mesh", {}).get("slot_end_size", DEFAULT_SLOT_END_SIZE),
        "mode": summary["scene"]["mode"],
        "young": material.get("young"),
        "kn": joints.get("normal_stiffness", scene.get("analysis", {}).get("penalty")),
        "sigma_t": joints.get("tensile_strength"),
        "cracks": summary.get("cracks", {}),
        "metrics": metrics,
        "length": tensile + shear if tensile is not None and shear is not None else None,
        "largest": bodies[0].get("largest_fragment_fraction") if len(bodies) == 1 else None,
        "wall": summary.get("wall_time", {}).get("total"),
        "balance": summary.get("energy", {}).get("largest_balance_error"),
        "eta": scene.get("analysis", {}).get("mass_damping", 0.0),
        # Runs written before these options had node contacts and the springs' criterion.
        "node_model": NODE_MODEL_NAMES.get((summary["scene"].get("intact_nodes", "contact"),
                                            summary["scene"].get("fracture_load", "joint_springs"))),
    }


def family_runs(h, study_dir):
    """{family: [run]} (completed runs) and the names of the cases not completed."""
    table = h.read_columns(os.path.join(study_dir, "study.csv"))
    if not table:
        h.fail(f"{study_dir}/study.csv: no cases")
    runs, missing = {}, []
    for case, series, run_dir in zip(table["case"], table["series"], table["run_dir"]):
        families = series.split("+")
        run = read_run(h, case, families, os.path.join(study_dir, run_dir))
        if run is None:
            missing.append(case)
            continue
        for family in families:
            runs.setdefault(family, []).append(run)
    return runs, missing


def measure_table(runs, parameter, value, form="{:.3g}"):
    """A markdown table: the parameter, every crack measure, the energy balance, the wall time."""
    labels = [label for label, _ in MEASURES]
    md = f"| case | {parameter} | " + " | ".join(labels) + " | balance error (%) | wall (s) |\n"
    md += "|---|--:|" + "--:|" * len(labels) + "--:|--:|\n"
    for r in runs:
        values = [cell(f(r)) for _, f in MEASURES]
        md += (f"| {r['case']} | {cell(value(r), form)} | " + " | ".join(values)
               + f" | {cell(scaled(r['balance'], PERCENT), '{:.2g}')} | {cell(r['wall'], '{:.0f}')} |\n")
    return md


def order_verdict(order):
    """What an observed order p of shrinking changes says (PLAUSIBLE_ORDERS)."""
    low, high = PLAUSIBLE_ORDERS
    if order > high:
        return (f"not shown: the last change is smaller, but p > {high:g} is beyond the "
                "method's order (not yet in the asymptotic range)")
    if order < low:
        return f"not shown: p < {low:g}, the changes barely shrink"
    return "converging"


def observed_orders(runs, step, what):
    """Per measure, the relative change between successive runs (ordered coarse to fine) and,
    from the last three, the observed order p in the step h (`step` of a run: the block size
    ∝ blocks^(-1/2), or dt_max): p = ln(|f2 - f1| / |f3 - f2|) / ln(h1/h2)."""
    md = f"| measure | relative change between successive {what} | observed order p | verdict |\n|---|---|--:|---|\n"
    for label, f in MEASURES:
        values = [f(r) for r in runs]
        if any(v is None for v in values) or len(values) < 2:
            md += f"| {label} | – | – | not measured in every run |\n"
            continue
        changes = [abs(b - a) / max(abs(b), 1e-30) for a, b in zip(values, values[1:])]
        order = None
        verdict = (f"unchanged (within {UNCHANGED * PERCENT:g}%), two {what} only" if changes[-1] <= UNCHANGED
                   else f"two {what} only")
        if len(values) >= 3:
            d1, d2 = abs(values[-2] - values[-3]), abs(values[-1] - values[-2])
            ratio = step(runs[-3]) / step(runs[-2])
            if max(changes[-2:]) <= UNCHANGED:
                verdict = f"unchanged (within {UNCHANGED * PERCENT:g}%)"
            elif changes[-1] <= UNCHANGED:
                verdict = f"settled: the last change within {UNCHANGED * PERCENT:g}%"
            elif d2 < d1:
                order = math.log(d1 / d2) / math.log(ratio)
                verdict = order_verdict(order)
            else:
                verdict = "not converging (the last change is not smaller)"
        md += (f"| {label} | " + ", ".join(f"{c * PERCENT:.1f}%" for c in changes)
               + f" | {cell(order, '{:.2f}')} | {verdict} |\n")
    return md


def peak_force(run):
    peak = run["summary"].get("loading", {}).get("peak", {}).get(LOADED_BODY)
    return (peak["peak_abs_force_y"], peak["t"], abs(peak["displacement_y"])) if peak else None


def indirect_strength(run):
    """(σt from the peak force, k) for a Brazilian run, or None."""
    peak = peak_force(run)
    geometry = run["scene"].get("geometry", {})
    if peak is None or "diameter" not in geometry:
        return None
    k = flattened_disc_factor(geometry.get("flat_angle", 0.0))
    return k * 2.0 * peak[0] / (math.pi * geometry["diameter"]), k


def kinetic_ratio_to_peak(h, run):
    """Median and largest kinetic/strain energy ratio of the disc up to the peak force."""
    peak = peak_force(run)
    history = os.path.join(run["dir"], "history.csv")
    if peak is None or not os.path.exists(history):
        return None, None
    columns = h.read_columns(history)
    t, ratio = h.numbers(columns, "t"), h.numbers(columns, "kinetic_strain_ratio")
    window = (t >= RATIO_START_FRACTION * peak[1]) & (t <= peak[1])
    if not window.any():
        return None, None
    return float(np.median(ratio[window])), float(ratio[window].max())


def platen_speed(run):
    velocity = run["scene"].get("bodies", {}).get(LOADED_BODY, {}).get("prescribed_velocity", [0.0, 0.0])
    return abs(velocity[1])


def gauge_peaks(h, run):
    """{gauge: largest σ1 (Pa)} of a run's gauges.csv."""
    path = os.path.join(run["dir"], "gauges.csv")
    if not os.path.exists(path):
        return {}
    gauges = h.read_columns(path)
    sigma1 = h.numbers(gauges, "sigma1")
    names = np.array(gauges["gauge"])
    return {name: float(sigma1[names == name].max()) for name in dict.fromkeys(gauges["gauge"])}


def tick_label(value):
    """A run's value as a tick: a table's cell below 1 (the study's kn/E = 0.0332, not 0.0332384),
    larger values exact (11137 blocks, where a cell would round to 11100)."""
    return cell(value) if abs(value) < 1 else f"{value:g}"


def log_axis_at(axis, xs):
    """A log x axis ticked at the runs' own values `xs`: the default minor labels of a log axis
    over less than a decade run into one another."""
    axis.set_xscale("log")
    axis.set_xticks(xs, [tick_label(v) for v in xs])
    axis.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())


def draw_measures(runs, x, xlabel, logx, title, path, save):
    figure, axes = plt.subplots(2, 4, figsize=(15, 8))
    xs = [x(r) for r in runs]
    for axis, (label, f) in zip(axes.flat, MEASURES):
        ys = [f(r) for r in runs]
        points = [(a, b) for a, b in zip(xs, ys) if b is not None]
        if points:
            axis.plot(*zip(*points), "o-")
            axis.ticklabel_format(axis="y", useOffset=False)
            values = [b for _, b in points]
            if max(values) - min(values) <= FLAT_RANGE * max(1.0, abs(max(values))):
                axis.set_ylim(min(values) - 1.0, max(values) + 1.0)  # a flat line, not round-off
        else:
            axis.text(0.5, 0.5, "not reached in any run", ha="center", va="center", transform=axis.transAxes)
        axis.set_title(label, fontsize="medium")
        axis.set_xlabel(xlabel)
        if logx and points:
            log_axis_at(axis, xs)
        axis.grid(alpha=0.3)
    axes.flat[-1].axis("off")
    figure.suptitle(title)
    figure.tight_layout()
    save(figure, path)


def draw_end_patterns(h, runs, title, path, save, label=lambda run: f"{run['blocks']} blocks"):
    """A panel per run, in the order given: its crack pattern over σ1 at its last snapshot, one
    colour scale for all, so that what the mesh (or another parameter, named by `label`) changes in
    where cracks run shows at a glance."""
    panels = [(run, snapshots[-1]) for run, snapshots in ((r, h.read_snapshots(r["dir"])) for r in runs) if snapshots]
    if not panels:
        return
    figure, axes = plt.subplots(1, len(panels), figsize=(3.6 * len(panels), 4.0), squeeze=False)
    collections = []
    for a, (run, (time, snapshot)) in zip(axes[0], panels):
        a.set_xticks([])
        a.set_yticks([])
        a.set_title(f"{label(run)}, {h.time_label(time)}", fontsize="small")
        collections.append(h.draw_pattern(a, snapshot))
    figure.suptitle(title)
    h.share_sigma1_scale(figure, axes, collections)
    save(figure, path)


def mesh_section(h, runs, figures, save):
    impact = sorted([r for r in runs if r["case"].startswith(GAUGE_CASE)], key=lambda r: r["blocks"])
    discs = sorted([r for r in runs if not r["case"].startswith(GAUGE_CASE)], key=lambda r: r["blocks"])
    md = "## Mesh\n\n"
    if impact:
        md += "Case 4:\n\n" + measure_table(impact, "blocks", lambda r: r["blocks"], "{:.0f}") + "\n"
        md += observed_orders(impact, lambda r: r["blocks"] ** -0.5, "meshes") + "\n"
        draw_measures(impact, lambda r: r["blocks"], "blocks", True, "case 4 against its mesh",
                      os.path.join(figures, "mesh.png"), save)
        draw_end_patterns(h, impact, "case 4: cracks at the end, per mesh",
                          os.path.join(figures, "mesh_patterns_case04.png"), save)
    if discs:
        md += "Flattened disc:\n\n" + brazilian_table(h, discs, "blocks", lambda r: r["blocks"], "{:.0f}") + "\n"
        md += measure_table(discs, "blocks", lambda r: r["blocks"], "{:.0f}") + "\n"
        md += observed_orders(discs, lambda r: r["blocks"] ** -0.5, "meshes") + "\n"
        draw_end_patterns(h, discs, "flattened disc: cracks at the end, per mesh",
                          os.path.join(figures, "mesh_patterns_flattened.png"), save)
        for what, force in (("Peak force", lambda r: peak_force(r)[0] if peak_force(r) else None),
                            ("Largest force up to the first crack", lambda r: force_to_first_crack(h, r, first_crack(h, r)))):
            forces = [f for f in map(force, discs) if f is not None]
            if len(forces) >= 2:
                md += (f"{what} from the coarsest to the finest mesh: "
                       + " → ".join(f"{f * KILONEWTONS:.1f}" for f in forces)
                       + f" kN/m ({(forces[-1] / forces[0] - 1.0) * PERCENT:+.1f}%).\n\n")
    return md


def first_crack(h, run):
    """(type, distance from the disc's centre / its radius, time) of a run's first crack, or None.
    Brazilian runs give the time as the platen's travel (speed × time), which static mode's
    pseudo-time shares with the dynamic runs."""
    path = os.path.join(run["dir"], "cracks.csv")
    cracks = h.read_columns(path) if os.path.exists(path) else {}
    diameter = run["scene"].get("geometry", {}).get("diameter")
    if not cracks or not diameter:
        return None
    x, y = float(cracks["x"][0]), float(cracks["y"][0])
    return cracks["type"][0], math.hypot(x, y) / (diameter / 2.0), float(cracks["t"][0])


def force_to_first_crack(h, run, first):
    """The largest platen force (N/m) up to the first crack `first` (first_crack's answer: the
    crack-initiation load), or None. Unlike the peak force, which comes after cracking has begun,
    it does not depend on how the cracks grow on a given mesh."""
    path = os.path.join(run["dir"], "loading.csv")
    if first is None or not os.path.exists(path):
        return None
    loading = h.read_columns(path)
    mask = (np.array(loading["body"]) == LOADED_BODY) & (h.numbers(loading, "t") <= first[2])
    return float(np.abs(h.numbers(loading, "force_y")[mask]).max()) if mask.any() else None


def centre_sigma1_to_peak(h, run):
    """The largest σ1 (Pa) at the gauge named "centre" up to the peak force, or None."""
    peak = peak_force(run)
    path = os.path.join(run["dir"], "gauges.csv")
    if peak is None or not os.path.exists(path):
        return None
    gauges = h.read_columns(path)
    mask = (np.array(gauges["gauge"]) == CENTRE_GAUGE) & (h.numbers(gauges, "t") <= peak[1])
    return float(h.numbers(gauges, "sigma1")[mask].max()) if mask.any() else None


def brazilian_table(h, runs, parameter, value, form="{:.3g}"):
    md = (f"| case | {parameter} | peak force (kN/m) | platen travel at peak (mm) | k | σt indirect (MPa) "
          "| centre σ1 to the peak (MPa) | σt of the joints (MPa) | ratio | first crack: kind, r/R, travel (mm) "
          "| largest force to the first crack (kN/m) | kinetic/strain to the peak: median / max (%) | cracks T / S "
          "| crack length (mm) | wall (s) |\n|---|--:|--:|--:|--:|--:|--:|--:|--:|---|--:|--:|--:|--:|--:|\n")
    for r in runs:
        peak, strength, first = peak_force(r), indirect_strength(r), first_crack(h, r)
        median, largest = kinetic_ratio_to_peak(h, r)
        first_text = (f"{first[0]}, {first[1]:.2f}, {first[2] * platen_speed(r) * MILLIMETRES:.3f}" if first else "–")
        md += (f"| {r['case']} | {cell(value(r), form)} | {cell(scaled(peak[0], KILONEWTONS) if peak else None, '{:.1f}')}"
               f" | {cell(scaled(peak[2], MILLIMETRES) if peak else None, '{:.3f}')}"
               f" | {cell(strength[1] if strength else None, '{:.4f}')}"
               f" | {cell(scaled(strength[0], MEGAPASCAL) if strength else None, '{:.2f}')}"
               f" | {cell(scaled(centre_sigma1_to_peak(h, r), MEGAPASCAL), '{:.2f}')}"
               f" | {cell(scaled(r['sigma_t'], MEGAPASCAL), '{:.2f}')}"
               f" | {cell(strength[0] / r['sigma_t'] if strength and r['sigma_t'] else None, '{:.2f}')}"
               f" | {first_text}"
               f" | {cell(scaled(force_to_first_crack(h, r, first), KILONEWTONS), '{:.1f}')}"
               f" | {cell(scaled(median, PERCENT), '{:.2g}')} / {cell(scaled(largest, PERCENT), '{:.2g}')}"
               f" | {cell(r['cracks'].get('tensile'), '{:.0f}')} / {cell(r['cracks'].get('shear'), '{:.0f}')}"
               f" | {cell(scaled(r['length'], MILLIMETRES), '{:.1f}')} | {cell(r['wall'], '{:.0f}')} |\n")
    return md


def time_steps_line(runs, why):
    """A line listing each run's dt_max, and why they differ."""
    return f"dt_max of each run ({why}): " + ", ".join(f"{r['case']} {r['dt_max']:g} s" for r in runs) + "\n\n"


def penalty_section(h, runs, figures, save):
    runs = sorted(runs, key=lambda r: r["kn"] / r["young"])
    md = "## Joint stiffness (penalty)\n\n" + measure_table(runs, "kn/E", lambda r: r["kn"] / r["young"]) + "\n"
    md += time_steps_line(runs, "the stiffer joints need shorter steps to resolve the contact period")
    peaks = [gauge_peaks(h, r) for r in runs]
    names = list(dict.fromkeys(n for p in peaks for n in p))
    if names:
        md += "Peak σ1 at the gauges (MPa):\n\n| case | kn/E | " + " | ".join(names) + " |\n"
        md += "|---|--:|" + "--:|" * len(names) + "\n"
        for r, p in zip(runs, peaks):
            md += (f"| {r['case']} | {r['kn'] / r['young']:.3g} | "
                   + " | ".join(cell(scaled(p.get(n), MEGAPASCAL), "{:.1f}") for n in names) + " |\n")
        md += "\n"
    draw_measures(runs, lambda r: r["kn"] / r["young"], "kn / E", True, "case 4 against the joints' stiffness",
                  os.path.join(figures, "penalty.png"), save)
    return md


def timestep_section(runs, figures, save):
    runs = sorted(runs, key=lambda r: -r["dt_max"])
    md = "## Time step\n\n" + measure_table(runs, "dt_max (s)", lambda r: r["dt_max"]) + "\n"
    md += observed_orders(runs, lambda r: r["dt_max"], "time steps") + "\n"
    draw_measures(runs, lambda r: r["dt_max"], "dt_max (s)", True, "case 4 against the time step",
                  os.path.join(figures, "timestep.png"), save)
    return md


def slot_tips_section(runs, figures, save):
    runs = sorted(runs, key=lambda r: -r["slot_end_size"])
    md = "## Slot tips\n\n" + measure_table(runs, "slot-end size (slot widths)", lambda r: r["slot_end_size"]) + "\n"
    md += time_steps_line(runs, "smaller blocks at the tips may need shorter steps to resolve the contact period")
    md += observed_orders(runs, lambda r: r["slot_end_size"], "tip sizes") + "\n"
    draw_measures(runs, lambda r: r["slot_end_size"], "element size at the slot's ends (slot widths)", True,
                  "case 4 against the mesh at its slot's tips", os.path.join(figures, "slot_tips.png"), save)
    return md


def draw_platen_forces(h, dynamic, static, label, x, xlabel, logx, title, path, save):
    """Two panels: the top platen's force against its travel for every run (labelled by `label`,
    static mode as "static"), and the dynamic runs' peak force against x(run) beside the static
    run's as a line."""
    figure, (curves, peaks) = plt.subplots(1, 2, figsize=(13, 5))
    for r in dynamic + static:
        travel, force = platen_curve(h, r, LOADED_BODY)
        curves.plot(travel * MILLIMETRES, force * KILONEWTONS, label="static" if r["mode"] == "static" else label(r))
    curves.set_xlabel("platen travel (mm)")
    curves.set_ylabel("top platen force (kN/m)")
    curves.legend()
    curves.grid(alpha=0.3)
    points = [(x(r), peak_force(r)[0] * KILONEWTONS) for r in dynamic if peak_force(r)]
    if points:
        peaks.plot(*zip(*points), "o-", label="dynamic")
        if logx:
            log_axis_at(peaks, [value for value, _ in points])
    elif logx:
        peaks.set_xscale("log")
    if static and peak_force(static[0]):
        peaks.axhline(peak_force(static[0])[0] * KILONEWTONS, color="k", linestyle="--", label="static")
    peaks.set_xlabel(xlabel)
    peaks.set_ylabel("peak force (kN/m)")
    peaks.legend()
    peaks.grid(alpha=0.3)
    figure.suptitle(title)
    save(figure, path)


def split_static(runs, order):
    """(the static-mode runs, the dynamic runs sorted by order(run)) of a Brazilian family."""
    return ([r for r in runs if r["mode"] == "static"],
            sorted([r for r in runs if r["mode"] != "static"], key=order))


def against_static(dynamic, reference, name):
    """One sentence: each dynamic run's peak force (named by name(run)) against the static peak."""
    return "Peak force against the static run's: " + ", ".join(
        f"{name(r)} {(peak_force(r)[0] / reference - 1.0) * PERCENT:+.1f}%" for r in dynamic if peak_force(r)) + "."


def rate_section(h, runs, figures, save):
    static, dynamic = split_static(runs, lambda r: -platen_speed(r))
    md = "## Loading rate (flattened disc)\n\n"
    md += brazilian_table(h, dynamic + static, "platen speed (m/s)",
                          lambda r: platen_speed(r) if r["mode"] != "static" else None) + "\n"
    if static and peak_force(static[0]):
        reference = peak_force(static[0])[0]
        within = [platen_speed(r) for r in dynamic
                  if peak_force(r) and abs(peak_force(r)[0] / reference - 1.0) <= QUASI_STATIC_TOLERANCE]
        md += against_static(dynamic, reference, lambda r: f"{platen_speed(r):g} m/s") + "\n"
        md += (f"Verdict: quasi-static to within {QUASI_STATIC_TOLERANCE * PERCENT:g}% of the static peak at "
               + (f"{max(within):g} m/s and slower.\n\n" if within else "none of the speeds run.\n\n"))
    draw_platen_forces(h, dynamic, static, lambda r: f"{platen_speed(r):g} m/s", platen_speed, "platen speed (m/s)",
                       True, "flattened disc against the loading rate", os.path.join(figures, "rate.png"), save)
    return md


def platen_curve(h, run, body):
    """(travel of the top platen (m), |force_y| of `body` (N/m)) of a Brazilian run, in time order."""
    loading = h.read_columns(os.path.join(run["dir"], "loading.csv"))
    bodies = np.array(loading["body"])
    travel = np.abs(h.numbers(loading, "displacement_y")[bodies == LOADED_BODY])
    return travel, np.abs(h.numbers(loading, "force_y")[bodies == body])


def ringing(h, run, first):
    """RMS (N/m) of the top platen force about a straight line fitted over RINGING_WINDOW of the
    travel to the first crack, or None."""
    if first is None:
        return None
    travel, force = platen_curve(h, run, LOADED_BODY)
    end = first[2] * platen_speed(run)
    window = (travel >= RINGING_WINDOW[0] * end) & (travel <= RINGING_WINDOW[1] * end)
    if window.sum() < 3:
        return None
    line = np.polyval(np.polyfit(travel[window], force[window], 1), travel[window])
    return float(np.sqrt(np.mean((force[window] - line) ** 2)))


def damping_share_to_peak(h, run):
    """What the mass damping took out up to the peak force, as a fraction of the platen's work."""
    peak = peak_force(run)
    columns = h.read_columns(os.path.join(run["dir"], "history.csv"))
    if peak is None or "damping_dissipation" not in columns:
        return None
    t = h.numbers(columns, "t")
    at = max(int(np.searchsorted(t, peak[1])) - 1, 0)
    work = h.numbers(columns, "work_supports")[at]
    return h.numbers(columns, "damping_dissipation")[at] / work if work > 0 else None


def damping_section(h, runs, figures, save):
    static, dynamic = split_static(runs, lambda r: r["eta"])
    md = "## Mass damping of the platen's ringing (flattened disc)\n\n"
    md += brazilian_table(h, dynamic + static, "η (1/s)", lambda r: r["eta"] if r["mode"] != "static" else None)
    md += ("\n| case | η (1/s) | ringing of the top platen's force to the first crack, RMS (kN/m) "
           "| peak force of the bottom (fixed) platen (kN/m) | damping's share of the platen's work to the peak (%) |\n"
           "|---|--:|--:|--:|--:|\n")
    for r in dynamic:
        first = first_crack(h, r)
        bottom = platen_curve(h, r, FIXED_BODY)[1]
        md += (f"| {r['case']} | {r['eta']:g} | {cell(scaled(ringing(h, r, first), KILONEWTONS), '{:.1f}')}"
               f" | {cell(float(bottom.max()) * KILONEWTONS if len(bottom) else None, '{:.1f}')}"
               f" | {cell(scaled(damping_share_to_peak(h, r), PERCENT), '{:.2g}')} |\n")
    md += "\n"
    if static and peak_force(static[0]):
        md += against_static(dynamic, peak_force(static[0])[0], lambda r: f"η = {r['eta']:g} 1/s") + "\n\n"
    draw_platen_forces(h, dynamic, static, lambda r: f"η = {r['eta']:g} 1/s", lambda r: r["eta"],
                       "mass damping η (1/s)", False, "flattened disc against mass damping",
                       os.path.join(figures, "damping.png"), save)
    return md


def node_model_section(h, runs, figures, save):
    """Case 4 and the flattened disc (dynamic and static) under each node model: a table each and
    one figure of crack counts per model."""
    order = list(NODE_MODEL_NAMES.values())
    rank = lambda r: order.index(r["node_model"]) if r["node_model"] in order else len(order)  # noqa: E731
    model = lambda r: r["node_model"] or "?"  # noqa: E731
    impact = sorted([r for r in runs if r["case"].startswith("case")], key=rank)
    brazilian = [r for r in runs if not r["case"].startswith("case")]
    static, dynamic = split_static(brazilian, rank)
    static = sorted(static, key=rank)
    md = ("## Node model: node contacts or ties, and what the fracture criterion judges\n\n"
          "Models: " + "; ".join(f"{name}: intact_nodes = {nodes}, fracture_load = {load}"
                                 for (nodes, load), name in NODE_MODEL_NAMES.items()) + ".\n\n")
    groups = [(title, series) for title, series in
              (("case 4", impact), ("flattened disc, dynamic", dynamic), ("flattened disc, static", static)) if series]
    for title, series in groups:
        md += f"### {title}\n\n"
        if series is impact:
            md += measure_table(series, "node model", model, "{}") + "\n"
        else:
            md += brazilian_table(h, series, "node model", model, "{}") + "\n"
    if groups:
        figure, axes = plt.subplots(1, len(groups), figsize=(5 * len(groups), 4.5), squeeze=False)
        for axis, (title, series) in zip(axes[0], groups):
            names = [model(r).replace(", ", ",\n") for r in series]
            x = np.arange(len(series))
            tensile = [r["cracks"].get("tensile") or 0 for r in series]
            shear = [r["cracks"].get("shear") or 0 for r in series]
            axis.bar(x, tensile, label="tensile")
            axis.bar(x, shear, bottom=tensile, label="shear")
            axis.set_xticks(x, names)
            axis.set_ylabel("cracks at the end")
            axis.set_title(title)
            axis.legend()
            axis.grid(alpha=0.3, axis="y")
        figure.suptitle("crack counts against the node model")
        save(figure, os.path.join(figures, "node_model.png"))
    return md


def theta_section(h, runs, figures, save):
    """The θ series at each kn the family ran (the scene's and 10·E, or one kn where --set gave
    both the same), one table, one line and one row of crack patterns each."""
    angle = lambda r: r["scene"].get("geometry", {}).get("joint_angle")  # noqa: E731
    stiffness = lambda r: r["kn"] / r["young"]  # noqa: E731
    by_stiffness = {}
    seen = set()  # a case whose scene repeats another's ran once, in the other's directory
    for r in sorted(runs, key=lambda r: (stiffness(r), angle(r) or 0.0)):
        if r["dir"] not in seen:
            seen.add(r["dir"])
            by_stiffness.setdefault(stiffness(r), []).append(r)
    md = "## The θ series against the joints' stiffness\n\n"
    figure, (counts, lengths) = plt.subplots(1, 2, figsize=(13, 4.5))
    for ratio, series in by_stiffness.items():
        label = f"kn = {ratio:.3g}·E"
        md += f"### {label}\n\n" + measure_table(series, "θ (°)", angle) + "\n"
        angles = [angle(r) for r in series]
        line, = counts.plot(angles, [r["cracks"].get("tensile") for r in series], "o-", label=f"{label}, tensile")
        counts.plot(angles, [r["cracks"].get("shear") for r in series], "s--", color=line.get_color(),
                    label=f"{label}, shear")
        lengths.plot(angles, [scaled(r["length"], MILLIMETRES) for r in series], "o-", label=label)
        draw_end_patterns(h, series, f"the θ series at {label}: cracks at the end",
                          os.path.join(figures, f"penalty_theta_patterns_kn{ratio:.3g}E.png"), save,
                          label=lambda r: f"θ = {angle(r):g}°")
    counts.set_ylabel("cracks at the end")
    lengths.set_ylabel("crack length at the end (mm)")
    for axes in (counts, lengths):
        # A disc as stiff as its rock breaks tens of times more joints: a log scale that keeps 0.
        axes.set_yscale("symlog", linthresh=1.0)
        axes.set_xlabel("joint angle θ (°)")
        axes.legend()
        axes.grid(alpha=0.3)
    figure.suptitle("the θ series (cases 1–7) against the joints' stiffness, one mesh size")
    save(figure, os.path.join(figures, "penalty_theta.png"))
    return md


def impact_speed(run):
    """The disc's impact speed (m/s) from the run's resolved scene."""
    velocity = run["scene"].get("bodies", {}).get("disc", {}).get("velocity", [0.0, 0.0])
    return math.hypot(*velocity)


def scatter_line(label, values, runs):
    """One row of the spread table: a measure's mean, range and relative spread over the runs that
    reached it, and a verdict (REPRODUCIBLE)."""
    reached = [v for v in values if v is not None]
    if not reached:
        return f"| {label} | – | – | – | – | not reached in any run |\n"
    mean = sum(reached) / len(reached)
    low, high = min(reached), max(reached)
    spread = (high - low) / abs(mean) if mean else 0.0
    deviation = float(np.std(reached, ddof=1)) if len(reached) > 1 else 0.0
    if len(reached) < len(runs):
        verdict = f"reached in {len(reached)} of {len(runs)} runs"
    elif spread == 0.0:
        verdict = "the same in every run"
    elif spread <= REPRODUCIBLE:
        verdict = f"reproducible (within {REPRODUCIBLE * PERCENT:g}%)"
    else:
        verdict = "scatters: a difference below the range is not resolved by one run"
    return (f"| {label} | {cell(mean)} | {cell(low)} – {cell(high)} | {cell(deviation, '{:.2g}')} | "
            f"{spread * PERCENT:.1f} | {verdict} |\n")


def is_brazilian(run):
    """Whether the run loads a disc between platens (the flattened disc), not by an impact."""
    return LOADED_BODY in run["scene"].get("bodies", {})


def spread_runs_figure(h, runs, change, legend_title, title, path, save):
    """Cracks and crack length against time in every run of a spread group, each line narrower
    than the one before (runs that agree draw over each other, and all stay visible); a Brazilian
    group gets a first panel with the top platen's force against its travel."""
    brazilian = is_brazilian(runs[0])
    figure, axes = plt.subplots(1, 3 if brazilian else 2, figsize=(19 if brazilian else 13, 4.5))
    forces, counts, lengths = axes if brazilian else (None, *axes)
    widths = np.linspace(SPREAD_WIDEST_LINE, SPREAD_NARROWEST_LINE, len(runs))
    for r, width in zip(runs, widths):
        label = f"+{change(r):.0f}·10⁻⁶" if change(r) > 0 else "as specified"
        if forces is not None:
            travel, force = platen_curve(h, r, LOADED_BODY)
            forces.plot(travel * MILLIMETRES, force * KILONEWTONS, linewidth=width, label=label)
        history = h.read_columns(os.path.join(r["dir"], "history.csv"))
        counts.step(h.numbers(history, "t") * MICROSECONDS, h.numbers(history, "cracks_total"), where="post",
                    linewidth=width, label=label)
        fragments = h.read_columns(os.path.join(r["dir"], "fragments.csv"))
        length = h.numbers(fragments, "crack_length_tensile") + h.numbers(fragments, "crack_length_shear")
        lengths.plot(h.numbers(fragments, "t") * MICROSECONDS, length * MILLIMETRES, linewidth=width, label=label)
    if forces is not None:
        forces.set_xlabel("platen travel (mm)")
        forces.set_ylabel("top platen force (kN/m)")
    counts.set_ylabel("cracks")
    lengths.set_ylabel("crack length (mm)")
    for panel in (counts, lengths):
        panel.set_xlabel("time (µs)")
    for panel in axes:
        panel.legend(title=legend_title)
        panel.grid(alpha=0.3)
    figure.suptitle(title)
    save(figure, path)


def spread_group(h, runs, speed, subject, speed_name, table, first_rows, path, save):
    """The spread section of one group of runs (`subject` with its `speed_name` changed), sorted by
    speed(run): their table (table(runs, change)), the scatter of first_rows(runs) (label, values)
    and of the crack measures, and the figure."""
    runs = sorted(runs, key=speed)
    reference = speed(runs[0])
    change = lambda r: (speed(r) / reference - 1.0) * PPM  # noqa: E731
    md = (f"## Spread: {subject} with its {speed_name} changed by a few millionths\n\n"
          f"{speed_name.capitalize()} {reference:g} m/s and that × (1 + n·10⁻⁶); what moves is how one run's choices "
          "fall (which state a contact inside the open–close band settles in, which joint breaks first), not the "
          "physics.\n\n")
    md += table(runs, change) + "\n"
    md += ("| measure | mean | range | standard deviation | range / mean (%) | verdict |\n"
           "|---|--:|--:|--:|--:|---|\n")
    rows = first_rows(runs) + [(label, [f(r) for r in runs]) for label, f in MEASURES]
    rows.append(("cracks (all)", [r["cracks"].get("total") for r in runs]))
    for label, values in rows:
        md += scatter_line(label, values, runs)
    spread_runs_figure(h, runs, change, speed_name,
                       f"{subject}: the same run with its {speed_name} changed by a few millionths", path, save)
    return md + "\n"


def spread_section(h, runs, figures, save):
    """Case 4 with its impact speed and the flattened disc with its platen speed changed by a few
    millionths: every run's measures, their scatter, and every run's cracks against time."""
    md = ""
    impact = [r for r in runs if not is_brazilian(r)]
    if impact:
        md += spread_group(h, impact, impact_speed, "case 4", "impact speed",
                           lambda group, change: measure_table(group, "speed change (10⁻⁶)", change, "{:.2g}"),
                           lambda group: [], os.path.join(figures, "spread.png"), save)
    brazilian = [r for r in runs if is_brazilian(r)]
    if brazilian:
        def peaks(group):
            found = [peak_force(r) for r in group]
            return [("peak force (kN/m)", [scaled(p[0], KILONEWTONS) if p else None for p in found]),
                    ("platen travel at peak (mm)", [scaled(p[2], MILLIMETRES) if p else None for p in found])]
        md += spread_group(h, brazilian, platen_speed, "the flattened disc", "platen speed",
                           lambda group, change: brazilian_table(h, group, "speed change (10⁻⁶)", change, "{:.2g}"),
                           peaks, os.path.join(figures, "spread_flattened.png"), save)
    return md


def write_whole(path, text):
    temporary = os.path.join(os.path.dirname(path), "." + os.path.basename(path) + ".partial")
    with open(temporary, "w") as handle:
        handle.write(text)
    os.replace(temporary, path)
    print(f"wrote {path}")


def draw_study(args, h, save):
    figures = os.path.join(args.study_dir, "figures")
    os.makedirs(figures, exist_ok=True)
    runs, missing = family_runs(h, args.study_dir)
    md = "# Sensitivity study: analysis\n\n"
    md += ("Read from the completed runs' summary.json, history.csv, gauges.csv and loading.csv by "
           "`ddafrac_plots.py study-sensitivity`. Indirect tensile strength: σt = k·2P/(πD) per unit thickness, "
           "k the flattened-disc factor of Wang et al. (2004, Int. J. Rock Mech. Min. Sci. 41, 245–253) for the "
           "flats' central angle (k = 1: the Brazilian formula).\n\n")
    if missing:
        md += "Not completed (left out): " + ", ".join(missing) + ".\n\n"
    if "mesh" in runs:
        md += mesh_section(h, runs["mesh"], figures, save)
    if "penalty" in runs:
        md += penalty_section(h, runs["penalty"], figures, save)
    if "timestep" in runs:
        md += timestep_section(runs["timestep"], figures, save)
    if "slot-tips" in runs:
        md += slot_tips_section(runs["slot-tips"], figures, save)
    if "rate" in runs:
        md += rate_section(h, runs["rate"], figures, save)
    if "penalty-theta" in runs:
        md += theta_section(h, runs["penalty-theta"], figures, save)
    if "damping" in runs:
        md += damping_section(h, runs["damping"], figures, save)
    if "node-model" in runs:
        md += node_model_section(h, runs["node-model"], figures, save)
    if "spread" in runs:
        md += spread_section(h, runs["spread"], figures, save)
    write_whole(os.path.join(args.study_dir, "analysis.md"), md)


def register(commands, helpers, save):
    """helpers: the ddafrac_plots module (read_columns, numbers, fail)."""
    study = commands.add_parser("study-sensitivity", help="figures and analysis of ddafrac study sensitivity")
    study.add_argument("study_dir")
    study.set_defaults(draw=lambda args: draw_study(args, helpers, save))
