#!/usr/bin/python3
"""Plots of the controller comparison written by vispmorph-bench.

Usage: vispmorph-bench-plots.py OUTDIR

Reads OUTDIR/runs.csv (one row per run) and OUTDIR/curves.csv (pose error against the simulator's truth at each
iteration of each run; absent after vispmorph-bench --no-curves) and writes into OUTDIR:
  success-rate.png        success rate per scenario set and controller (grouped bars)
  success-vs-rotation.png success rate against the initial |in-plane rotation|, 30 deg bins, one line per controller
  path-ratio.png          camera path / straight line of the successful runs, per set and controller (box plots)
  error-curves.png        median translation and rotation error against iteration, per set and controller (log)
  failures.png            failure reasons per controller (stacked bars)
Every file is written even when data are missing (a panel then says so). Run it with Debian's /usr/bin/python3
(python3-matplotlib); MPLBACKEND=Agg for headless machines.
"""

import math
import os
import sys
import warnings

import matplotlib

if not os.environ.get("MPLBACKEND"):
    matplotlib.use("Agg")  # files only: no window is ever opened
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from vispmorph_bench_files import CONTROLLERS, SETS, BenchFileError, number, ordered, success  # noqa: E402
from vispmorph_bench_files import read_csv as read_bench_csv  # noqa: E402

RUN_COLUMNS = [
    "set", "robot", "controller", "scenario", "seed", "object", "start_rotation_deg", "start_translation_mm",
    "start_tilt_deg", "start_depth_change", "success", "failure", "iterations", "converged_iteration",
    "path_length_m", "straight_line_m", "path_ratio", "final_t_mm", "final_r_deg", "final_tag_t_mm",
    "final_tag_r_deg", "recognized", "recognition_correct",
]
CURVE_COLUMNS = ["set", "robot", "controller", "scenario", "iteration", "t_mm", "r_deg"]

# Canonical order of the failure reasons (the sets' and the controllers' are in vispmorph_bench_files); names not
# listed here are appended in order of appearance.
FAILURES = ["out-of-view", "feature-lost", "joint-limit", "budget", "final-error", "diverged", "recognition",
            "unreachable", "lost-too-long", "too-many-replans", "target-mismatch"]

# One colour per controller in every figure (VISPMorph in blues, IBVS in reds/oranges, PBVS green, moments purple).
CONTROLLER_COLOURS = {
    "morph": "#1f4e9c",
    "morph-vpservo": "#5fa2e8",
    "ibvs-current": "#c0392b",
    "ibvs-desired": "#e67e22",
    "ibvs-mean": "#f4b41a",
    "pbvs": "#2e8b57",
    "moments": "#8e44ad",
    "moments-planar": "#c39bd3",
}
EXTRA_COLOURS = ["#7f7f7f", "#17becf", "#bcbd22", "#8c564b", "#e377c2"]
FAILURE_COLOURS = {
    "out-of-view": "#d62728",
    "feature-lost": "#ff7f0e",
    "joint-limit": "#8c564b",
    "budget": "#7f7f7f",
    "final-error": "#bcbd22",
    "diverged": "#9467bd",
    "recognition": "#17becf",
    "unreachable": "#e377c2",
}

# Success thresholds of the protocol (final pose error against the simulator's truth).
T_SUCCESS_MM = 1.0
R_SUCCESS_DEG = 0.5
# Floor of the log-scale error plots: an error of exactly 0 is drawn there.
LOG_FLOOR = 1e-4


def fail(msg):
    sys.stderr.write("vispmorph-bench-plots: " + msg + "\n")
    sys.exit(1)


def read_csv(path, columns):
    try:
        return read_bench_csv(path, columns)
    except BenchFileError as e:
        fail(str(e))


def colour_map(controllers):
    colours, extra = {}, 0
    for c in controllers:
        if c in CONTROLLER_COLOURS:
            colours[c] = CONTROLLER_COLOURS[c]
        else:
            colours[c] = EXTRA_COLOURS[extra % len(EXTRA_COLOURS)]
            extra += 1
    return colours


def save(fig, outdir, name, written):
    path = os.path.join(outdir, name)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    written.append(path)


def layered(k, n, marker=False):
    """Line style of the k-th of n controllers: controllers that behave alike draw the same line (morph and
    morph-planar on a planar start, every successful controller at 100 %), so the first listed is drawn on top and
    thinnest, the later ones under it and wider, and each stays visible."""
    share = k / max(1, n - 1)
    style = dict(zorder=2 + n - k, lw=1.2 + 1.6 * share)
    if marker:
        style["ms"] = 5 + 5 * share
    return style


def no_data(ax, text="no data"):
    ax.text(0.5, 0.5, text, ha="center", va="center", transform=ax.transAxes, color="0.4", fontsize=11)


def plot_success_rate(runs, sets, controllers, colours, outdir, written):
    fig, ax = plt.subplots(figsize=(max(8, 1.4 * len(sets) + 3), 5))
    if not sets or not controllers:
        no_data(ax, "no runs in runs.csv")
    width = 0.8 / max(1, len(controllers))
    for j, c in enumerate(controllers):
        xs, ys, missing = [], [], []
        for i, s in enumerate(sets):
            rows = [r for r in runs if r["set"] == s and r["controller"] == c]
            x = i - 0.4 + (j + 0.5) * width
            if rows:
                xs.append(x)
                ys.append(100.0 * sum(success(r) for r in rows) / len(rows))
            else:
                missing.append(x)
        ax.bar(xs, ys, width, color=colours[c], label=c)
        for x, y in zip(xs, ys):  # a 0 % bar has no height: label it so that it is not read as "no run"
            if y == 0:
                ax.text(x, 1, "0", ha="center", va="bottom", fontsize=7, color=colours[c], fontweight="bold")
        for x in missing:  # no run: say so rather than draw a 0 % bar
            ax.text(x, 1, "no run", ha="center", va="bottom", rotation=90, fontsize=7, color="0.4")
    ax.set_xticks(range(len(sets)))
    ax.set_xticklabels(sets)
    ax.set_ylim(0, 105)
    ax.set_xlabel("scenario set")
    ax.set_ylabel("success rate (%)")
    ax.set_title("Success rate per scenario set and controller\n(final error < %g mm and %g deg, target in view, "
                 "within budget; \"0\": all runs failed, \"no run\": none in the set)" % (T_SUCCESS_MM, R_SUCCESS_DEG))
    ax.grid(axis="y", alpha=0.3)
    if controllers:
        ax.legend(title="controller", fontsize=8, ncol=min(4, len(controllers)), loc="upper center",
                  bbox_to_anchor=(0.5, -0.12))
    fig.tight_layout()
    save(fig, outdir, "success-rate.png", written)


def plot_success_vs_rotation(runs, controllers, colours, outdir, written):
    edges = list(range(0, 181, 30))
    centres = [0.5 * (a + b) for a, b in zip(edges[:-1], edges[1:])]
    fig, ax = plt.subplots(figsize=(8, 5))
    drawn = False
    for i, c in enumerate(controllers):
        ys, ns = [], []
        for k, (a, b) in enumerate(zip(edges[:-1], edges[1:])):
            rows = []
            for r in runs:
                rot = number(r["start_rotation_deg"])
                if r["controller"] != c or rot is None:
                    continue
                rot = abs(rot)
                # Bins [a, b), the last one closed: 180 deg belongs to 150-180.
                if a <= rot < b or (k == len(edges) - 2 and rot == b):
                    rows.append(r)
            ns.append(len(rows))
            ys.append(100.0 * sum(success(r) for r in rows) / len(rows) if rows else np.nan)
        if all(n == 0 for n in ns):
            continue
        # An empty bin is a gap in the line.
        ax.plot(centres, ys, "o-", color=colours[c], label=c, **layered(i, len(controllers), marker=True))
        drawn = True
    if not drawn:
        no_data(ax, "no run with a start rotation")
    ax.set_xticks(centres)
    ax.set_xticklabels(["%d-%d" % (a, b) for a, b in zip(edges[:-1], edges[1:])])
    ax.set_xlim(0, 180)
    ax.set_ylim(-3, 103)
    ax.set_xlabel("initial |in-plane rotation| (deg)")
    ax.set_ylabel("success rate (%)")
    ax.set_title("Success rate against the initial rotation (all sets; gap: no run in the bin)")
    ax.grid(alpha=0.3)
    if drawn:
        ax.legend(title="controller", fontsize=8, loc="lower left")
    fig.tight_layout()
    save(fig, outdir, "success-vs-rotation.png", written)


def grid(n, max_cols=4):
    cols = max(1, min(max_cols, n))
    rows = max(1, int(math.ceil(n / float(cols))))
    return rows, cols


def plot_path_ratio(runs, sets, controllers, colours, outdir, written):
    rows_, cols = grid(len(sets))
    fig, axes = plt.subplots(rows_, cols, figsize=(max(10.0, 4.2 * cols + 0.5), 3.8 * rows_ + 0.8), squeeze=False)
    for ax in axes.flat[len(sets):]:
        ax.set_visible(False)
    if not sets:
        axes[0][0].set_visible(True)
        no_data(axes[0][0], "no runs in runs.csv")
    for ax, s in zip(axes.flat, sets):
        # Every controller keeps its place (and colour) in every panel; n = successful runs with a ratio.
        data, pos, cs, labels = [], [], [], []
        for i, c in enumerate(controllers):
            vals = [number(r["path_ratio"]) for r in runs if r["set"] == s and r["controller"] == c and success(r)]
            vals = [v for v in vals if v is not None]
            labels.append("%s (n=%d)" % (c, len(vals)))
            if vals:
                data.append(vals)
                pos.append(i)
                cs.append(colours[c])
        if data:
            bp = ax.boxplot(data, positions=pos, patch_artist=True, widths=0.6, showfliers=False)
            for patch, col in zip(bp["boxes"], cs):
                patch.set_facecolor(col)
                patch.set_alpha(0.45)
            for med in bp["medians"]:
                med.set_color("black")
            for x, vals, col in zip(pos, data, cs):  # the runs themselves: visible even when n is 1
                jitter = np.linspace(-0.15, 0.15, len(vals)) if len(vals) > 1 else [0.0]
                ax.scatter(np.asarray(jitter) + x, vals, s=14, color=col, edgecolors="black", linewidths=0.4,
                           zorder=3)
            ax.axhline(1.0, color="0.3", lw=0.8, ls="--")
            ax.set_ylim(bottom=min(0.95, min(min(d) for d in data) - 0.02))
        else:
            no_data(ax, "no successful run\nwith a path ratio")
        ax.set_xticks(range(len(controllers)))
        ax.set_xticklabels(labels, rotation=35, ha="right", fontsize=7)
        ax.set_xlim(-0.6, len(controllers) - 0.4)
        ax.set_title(s)
        ax.set_ylabel("path / straight line")
        ax.grid(axis="y", alpha=0.3)
    fig.suptitle("Camera path length over the straight-line distance, successful runs (box: quartiles; dots: "
                 "runs; dashed: 1 = straight)")
    fig.tight_layout(rect=(0, 0, 1, 1 - 0.45 / fig.get_size_inches()[1]))
    save(fig, outdir, "path-ratio.png", written)


def median_curves(curves):
    """{(set, controller): (iterations, median t_mm, median r_deg)}; a run that stopped keeps its last error."""
    runs = {}
    for r in curves:
        it, t, rd = number(r["iteration"]), number(r["t_mm"]), number(r["r_deg"])
        if it is None or t is None or rd is None:
            continue
        key = (r["set"], r["controller"], r["robot"], r["scenario"])
        runs.setdefault(key, []).append((int(it), t, rd))
    grouped = {}
    for (s, c, _, _), pts in runs.items():
        pts.sort()
        grouped.setdefault((s, c), []).append(pts)
    out = {}
    for key, series in grouped.items():
        last = max(p[-1][0] for p in series)
        first = min(p[0][0] for p in series)
        its = np.arange(first, last + 1)
        T = np.full((len(series), len(its)), np.nan)
        R = np.full((len(series), len(its)), np.nan)
        for k, pts in enumerate(series):
            j, cur = 0, None
            for col, it in enumerate(its):
                while j < len(pts) and pts[j][0] <= it:
                    cur = pts[j]
                    j += 1
                if cur is not None:
                    T[k, col], R[k, col] = cur[1], cur[2]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # all-NaN columns before every run's first point
            out[key] = (its, np.nanmedian(T, axis=0), np.nanmedian(R, axis=0), len(series))
    return out


def plot_error_curves(curves, sets, controllers, colours, outdir, written, why_none="no curves in curves.csv"):
    med = median_curves(curves)
    curve_sets = ordered([s for s, _ in med] + list(sets), SETS)
    curve_sets = [s for s in curve_sets if any(k[0] == s for k in med)] or sets
    n = max(1, len(curve_sets))
    fig, axes = plt.subplots(n, 2, figsize=(11, 2.9 * n + 0.9), squeeze=False)
    if not med:
        no_data(axes[0][0], why_none)
        no_data(axes[0][1], why_none)
    for i, s in enumerate(curve_sets):
        axt, axr = axes[i]
        any_line = False
        for k, c in enumerate(controllers):
            if (s, c) not in med:
                continue
            its, T, R, count = med[(s, c)]
            style = dict(layered(k, len(controllers)), color=colours[c], label="%s (%d)" % (c, count))
            axt.plot(its, np.maximum(T, LOG_FLOOR), **style)
            axr.plot(its, np.maximum(R, LOG_FLOOR), **style)
            any_line = True
        for ax, thr, unit in ((axt, T_SUCCESS_MM, "mm"), (axr, R_SUCCESS_DEG, "deg")):
            ax.axhline(thr, color="black", ls="--", lw=0.9, label="success %g %s" % (thr, unit))
            ax.set_yscale("log")
            ax.set_xlabel("iteration")
            ax.grid(alpha=0.3, which="both")
        axt.set_ylabel("translation error (mm)")
        axr.set_ylabel("rotation error (deg)")
        axt.set_title("%s: median translation error" % s)
        axr.set_title("%s: median rotation error" % s)
        if any_line:
            axr.legend(fontsize=7, loc="upper right", title="controller (runs)", title_fontsize=7)
        elif med:
            no_data(axt)
            no_data(axr)
    height = fig.get_size_inches()[1]
    fig.suptitle("Pose error against the simulator's truth (median over runs; a run that stopped keeps its last "
                 "error; dashed: success thresholds)")
    fig.tight_layout(rect=(0, 0, 1, 1 - 0.45 / height))  # room for the title whatever the number of sets
    save(fig, outdir, "error-curves.png", written)


def failure_reason(row):
    """Failure word of a failed run ("unknown" when empty or "none" although the run failed)."""
    reason = (row.get("failure") or "").strip()
    return reason if reason and reason != "none" else "unknown"


def plot_failures(runs, controllers, outdir, written):
    reasons = ordered([failure_reason(r) for r in runs if not success(r)], FAILURES)
    fig, ax = plt.subplots(figsize=(max(7, 1.1 * len(controllers) + 3), 5))
    bottom = np.zeros(len(controllers))
    for k, f in enumerate(reasons):
        counts = []
        for c in controllers:
            counts.append(sum(1 for r in runs if r["controller"] == c and not success(r) and failure_reason(r) == f))
        col = FAILURE_COLOURS.get(f, EXTRA_COLOURS[k % len(EXTRA_COLOURS)])
        ax.bar(range(len(controllers)), counts, 0.6, bottom=bottom, color=col, label=f)
        bottom += np.array(counts)
    for i, c in enumerate(controllers):
        total = sum(1 for r in runs if r["controller"] == c)
        ax.text(i, bottom[i], "%d/%d" % (bottom[i], total), ha="center", va="bottom", fontsize=8)
    if not controllers:
        no_data(ax, "no runs in runs.csv")
    elif not reasons:
        no_data(ax, "no failed run")
    ax.set_xticks(range(len(controllers)))
    ax.set_xticklabels(controllers, rotation=20, ha="right")
    ax.set_xlabel("controller")
    ax.set_ylabel("failed runs (all sets)")
    ax.set_ylim(0, max(1.0, float(bottom.max()) if len(bottom) else 1.0) * 1.15)
    ax.set_title("Failure reasons per controller (label: failed/all runs)")
    ax.grid(axis="y", alpha=0.3)
    if reasons:
        ax.legend(title="failure", fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    save(fig, outdir, "failures.png", written)


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        sys.stderr.write(__doc__)
        return 0 if len(argv) == 2 else 2
    outdir = argv[1]
    runs = read_csv(os.path.join(outdir, "runs.csv"), RUN_COLUMNS)
    curves_path = os.path.join(outdir, "curves.csv")
    has_curves = os.path.exists(curves_path)
    curves = read_csv(curves_path, CURVE_COLUMNS) if has_curves else []
    sets = ordered([r["set"] for r in runs], SETS)
    controllers = ordered([r["controller"] for r in runs] + [r["controller"] for r in curves], CONTROLLERS)
    colours = colour_map(controllers)
    written = []
    plot_success_rate(runs, sets, controllers, colours, outdir, written)
    plot_success_vs_rotation(runs, controllers, colours, outdir, written)
    plot_path_ratio(runs, sets, controllers, colours, outdir, written)
    plot_error_curves(curves, sets, controllers, colours, outdir, written,
                      "no curves in curves.csv" if has_curves else "no curves.csv (a run with --no-curves)")
    plot_failures(runs, controllers, outdir, written)
    for path in written:
        print("wrote " + path)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
