#!/usr/bin/python3
"""One controller's results over several vispmorph-bench runs (robots, seeds) as one markdown table, or every
controller's side by side.

Usage: vispmorph-bench-table.py [--controller NAME] OUTDIR [OUTDIR ...]
       vispmorph-bench-table.py --by-controller OUTDIR [OUTDIR ...]
       vispmorph-bench-table.py --report OUTDIR [OUTDIR ...]

Reads each OUTDIR/runs.csv (and OUTDIR/summary.json when present, for the machine yardstick) and prints, per set:
the successes of each OUTDIR (a column each, headed by its robot and seed), all of them together, the median path
ratio of the successful runs, the mean compute time per iteration (measure + control, CPU ms, over the runs that
measured) and its ratio to each run's machine yardstick, and issue 5's target for the set, met or not over all the
OUTDIRs given. With --by-controller: a row per set and a column per controller (all the runs of the OUTDIRs given,
which may hold different controllers: one run of the stock ones, another of VISPMorph's), each cell the successes
over the runs and, in brackets, the median final error of the successful ones (mm / deg, simulator truth). The table
is computed from the files only: what it says is what the runs did. With --report: a table per robot of every set
and controller: success with its 95 % interval (Wilson's; 3 / n for none) over the runs that could be set up and whose
pose the taught view bounds, the false convergences, the views apart (unobservable: their runs, successes and false
convergences; symmetric, scored modulo their symmetry), the set-up failures, the median final error, the compute
a period (median and 95th percentile, ms and over each run's machine yardstick; from timings.csv) and the mean CPU
time of a whole run (rendering included: what a sweep costs).
Above each table, the commit its runs were measured at (summary.json's meta; "commit not recorded" for older runs).
"""

import math
import os
import statistics
import sys

from vispmorph_bench_files import (CONTROLLERS, SETS, BenchFileError, commit_stamp, interval, number, ordered, read_csv,
                                   read_meta, read_runs, success, yardstick)

# Issue 5's targets for morph: (least success rate, largest median path ratio or None).
TARGETS = {
    "planar": (1.0, 1.1),
    "planar-hard": (1.0, None),
    "calib": (0.95, None),
    "noise": (0.95, None),
    "occlusion": (0.95, None),
    "deformable": (0.95, None),
}
COMPUTE_TARGET_MS = 2.0


def fail(message):
    sys.stderr.write("vispmorph-bench-table: " + message + "\n")
    sys.exit(2)


def stamp(paths):
    """The "Measured at" line of the runs in \a paths."""
    return commit_stamp([(p, read_meta(p).get("commit")) for p in paths])


def read_dir(path, controller):
    columns = ("set", "robot", "controller", "success", "path_ratio", "measure_ms", "control_ms")
    try:
        rows = [r for r in read_runs(path, columns) if r["controller"] == controller]
    except BenchFileError as e:
        fail(str(e))
    meta = read_meta(path)  # {} without a summary: no yardstick, the directory's name for the seed
    # runs.csv's seed column is each scenario's own seed: the set seed is in the summary.
    robots = "/".join(sorted({r["robot"] for r in rows})) or "?"
    seed = meta.get("seed")
    label = "%s seed %s" % (robots, seed) if seed else "%s (%s)" % (robots, os.path.basename(os.path.normpath(path)))
    return {"label": label, "rows": rows, "yardstick": yardstick(meta)}


def ordered_sets(dirs):
    return ordered([r["set"] for d in dirs for r in d["rows"]], SETS)


def table(dirs, controller):
    out = []
    head = ["set"] + [d["label"] for d in dirs] + ["all", "median path ratio", "compute (ms)", "compute / yardstick",
                                                  "issue 5 target"]
    out.append("| " + " | ".join(head) + " |")
    out.append("|" + "---|" * len(head))
    for s in ordered_sets(dirs):
        cells, successes, runs, ratios, compute, per_yardstick = [s], 0, 0, [], [], []
        for d in dirs:
            rows = [r for r in d["rows"] if r["set"] == s]
            ok = sum(1 for r in rows if success(r))
            cells.append("%d/%d" % (ok, len(rows)) if rows else "-")
            successes += ok
            runs += len(rows)
            for r in rows:
                ratio = number(r["path_ratio"])
                if success(r) and ratio is not None:
                    ratios.append(ratio)
                m, c = number(r["measure_ms"]), number(r["control_ms"])
                if m is not None and c is not None and m > 0:
                    compute.append(m + c)
                    if d["yardstick"]:
                        per_yardstick.append((m + c) / d["yardstick"])
        rate = successes / runs if runs else 0.0
        cells.append("%d/%d (%.0f %%)" % (successes, runs, 100 * rate))
        median_ratio = statistics.median(ratios) if ratios else None
        cells.append("%.2f" % median_ratio if median_ratio is not None else "-")
        mean_compute = statistics.mean(compute) if compute else None
        cells.append("%.2f" % mean_compute if mean_compute is not None else "-")
        cells.append("%.1f" % statistics.mean(per_yardstick) if per_yardstick else "-")
        cells.append(target(s, controller, rate, median_ratio, mean_compute))
        out.append("| " + " | ".join(cells) + " |")
    return "\n".join(out)


def by_controller(paths):
    """Successes per set and controller over all the runs of \a paths, with the successes' median final error."""
    columns = ("set", "controller", "success", "final_t_mm", "final_r_deg")
    rows = []
    for p in paths:
        try:
            rows += read_csv(os.path.join(p, "runs.csv"), columns)
        except BenchFileError as e:
            fail(str(e))
    if not rows:
        fail("no run in " + ", ".join(paths))
    controllers = ordered([r["controller"] for r in rows], CONTROLLERS)
    out = ["| set | " + " | ".join(controllers) + " |", "|" + "---|" * (len(controllers) + 1)]
    for s in ordered([r["set"] for r in rows], SETS):
        cells = [s]
        for c in controllers:
            runs = [r for r in rows if r["set"] == s and r["controller"] == c]
            ok = [r for r in runs if success(r)]
            if not runs:
                cells.append("-")
                continue
            t = [v for v in (number(r["final_t_mm"]) for r in ok) if v is not None]
            d = [v for v in (number(r["final_r_deg"]) for r in ok) if v is not None]
            error = " (%.3g / %.3g)" % (statistics.median(t), statistics.median(d)) if t and d else ""
            cells.append("%d/%d%s" % (len(ok), len(runs), error))
        out.append("| " + " | ".join(cells) + " |")
    return "\n".join(out)


def quantile(values, q):
    """The q-quantile by nearest rank, as the bench computes it (None for none)."""
    if not values:
        return None
    v = sorted(values)
    return v[max(0, min(len(v) - 1, math.ceil(q * len(v)) - 1))]


def report(paths):
    """One table per robot: every set and controller, success with its 95 % interval, the successes that declared
    convergence, false convergences, the views apart (unobservable: their successes and false convergences;
    symmetric), the set-up failures, the median final error and the compute per period (median / p95 and over the
    yardstick), from the runs and timings of \a paths."""
    columns = ("set", "robot", "controller", "success", "failure", "iterations", "final_t_mm", "final_r_deg",
               "converged", "false_converged", "unobservable", "symmetry", "period_ms", "yardstick_ms", "run_cpu_s")
    rows = []
    dirs_of = {}  # robot -> the paths with its runs
    for p in paths:
        try:
            mine = read_runs(p, columns)
        except BenchFileError as e:
            fail(str(e))
        rows += mine
        for robot in ordered([r["robot"] for r in mine], []):
            dirs_of.setdefault(robot, []).append(p)
    if not rows:
        fail("no run in " + ", ".join(paths))
    out = []
    for robot in ordered([r["robot"] for r in rows], []):
        out += ["", "**%s**" % robot, "", stamp(dirs_of[robot]), "",
                "| set | controller | success (95 % interval) | declared converged | false-converged | unobservable: "
                "runs (successes, false-converged) | symmetric | set-up failures | median final error (mm / deg) | "
                "compute a period, median / p95 (ms) | over the yardstick, median / p95 | CPU a run (s) |",
                "|---|---|---|---|---|---|---|---|---|---|---|---|"]
        mine = [r for r in rows if r["robot"] == robot]
        for s in ordered([r["set"] for r in mine], SETS):
            for c in ordered([r["controller"] for r in mine if r["set"] == s], CONTROLLERS):
                runs = [r for r in mine if r["set"] == s and r["controller"] == c]
                setup = [r for r in runs if r["failure"] == "setup"]
                apart = [r for r in runs if r["unobservable"] and r not in setup]
                main = [r for r in runs if r not in setup and r not in apart]
                ok = sum(1 for r in main if success(r))
                false = sum(1 for r in main if r["false_converged"] == "1")
                declared = sum(1 for r in main if success(r) and r["converged"] == "1")
                lo, hi = interval(ok, len(main))
                _, false_hi = interval(false, len(main))
                started = [r for r in main if (number(r["iterations"]) or 0) > 0]
                t = [v for v in (number(r["final_t_mm"]) for r in started) if v is not None]
                d = [v for v in (number(r["final_r_deg"]) for r in started) if v is not None]
                periods, ratios = [], []
                for r in runs:
                    y = number(r.get("yardstick_ms"))
                    for x in (r.get("period_ms") or "").split():
                        v = number(x)
                        if v is not None:
                            periods.append(v)
                            if y:
                                ratios.append(v / y)

                def pair(a, b, fmt):
                    return "%s / %s" % (fmt % a if a is not None else "-", fmt % b if b is not None else "-")
                cpu = [v for v in (number(r.get("run_cpu_s")) for r in runs) if v is not None]
                out.append("| %s | %s | %s | %s | %s | %s | %d | %d | %s | %s | %s | %s |" % (
                    s, c,
                    "%d/%d (%.0f %%, %.0f-%.0f)" % (ok, len(main), 100.0 * ok / len(main), 100 * lo, 100 * hi)
                    if main else "-",
                    "%d/%d" % (declared, ok) if main else "-",
                    "%d (<= %.1f %%)" % (false, 100 * false_hi) if main else "-",
                    "%d (%d, %d)" % (len(apart), sum(1 for r in apart if success(r)),
                                     sum(1 for r in apart if r["false_converged"] == "1")) if apart else "0",
                    sum(1 for r in main if (number(r["symmetry"]) or 1) != 1), len(setup),
                    pair(statistics.median(t) if t else None, statistics.median(d) if d else None, "%.3g"),
                    pair(quantile(periods, 0.5), quantile(periods, 0.95), "%.2f"),
                    pair(quantile(ratios, 0.5), quantile(ratios, 0.95), "%.2f"),
                    "%.2f" % statistics.mean(cpu) if cpu else "-"))
    return "\n".join(out[1:])


def target(set_name, controller, rate, median_ratio, mean_compute):
    if controller != "morph":
        return "(for morph)"
    notes, met = [], True
    if set_name in TARGETS:
        least, largest_ratio = TARGETS[set_name]
        notes.append(">= %.0f %%" % (100 * least))
        met &= rate >= least
        if largest_ratio is not None:
            notes.append("ratio <= %.1f" % largest_ratio)
            met &= median_ratio is not None and median_ratio <= largest_ratio
    notes.append("< %.0f ms" % COMPUTE_TARGET_MS)
    met &= mean_compute is not None and mean_compute < COMPUTE_TARGET_MS
    return "%s: %s" % (", ".join(notes), "met" if met else "not met")


def main(argv):
    controller, dirs, side_by_side, full = "morph", [], False, False
    i = 1
    while i < len(argv):
        if argv[i] == "--by-controller":
            side_by_side = True
            i += 1
        elif argv[i] == "--report":
            full = True
            i += 1
        elif argv[i] == "--controller":
            if i + 1 >= len(argv):
                fail("--controller needs a value")
            controller = argv[i + 1]
            i += 2
        elif argv[i] in ("-h", "--help"):
            print(__doc__)
            return 0
        else:
            dirs.append(argv[i])
            i += 1
    if not dirs:
        fail("no OUTDIR given (usage: vispmorph-bench-table.py [--controller NAME | --by-controller] OUTDIR ...)")
    if side_by_side:
        print(stamp(dirs) + "\n")
        print(by_controller(dirs))
        return 0
    if full:
        print(report(dirs))
        return 0
    data = [read_dir(d, controller) for d in dirs]
    if not any(d["rows"] for d in data):
        fail("no run of controller '%s' in %s" % (controller, ", ".join(dirs)))
    print(stamp(dirs) + "\n")
    print(table(data, controller))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
