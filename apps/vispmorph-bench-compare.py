#!/usr/bin/python3
"""Two vispmorph-bench runs of the same starts, run for run: what a code change did to them.

Usage: vispmorph-bench-compare.py [--strict] BEFORE AFTER

Reads BEFORE/runs.csv and AFTER/runs.csv (their timings.csv and timings.json for the compute and the machine yardstick
when present), pairs the
runs by set, robot, controller, scenario and scenario seed, and prints in markdown:
- how many runs are identical (same outcome, failure reason, iterations and final errors, as written), and those
  found in one folder only;
- every run whose outcome (success, failure reason) changed;
- every run with the same outcome but other iterations or final errors, and how many of the successful ones ended
  nearer the goal or farther from it (final translation error);
- per set, the mean compute time per iteration (measure + control, CPU ms, over the runs that measured) before and
  after, and its ratio to each folder's yardstick: the machine's speed changes between runs, the ratio less.

Exit status: 0; 1 with --strict when an outcome changed or a run is in one folder only (a regression check); 2 when
a folder cannot be read.
"""

import os
import sys

from vispmorph_bench_files import SETS, BenchFileError, number, ordered, read_meta, read_runs, success, yardstick

KEY = ("set", "robot", "controller", "scenario", "seed")
RESULT = ("success", "failure", "iterations", "final_t_mm", "final_r_deg")
COLUMNS = KEY + RESULT + ("object", "measure_ms", "control_ms")


def fail(message):
    sys.stderr.write("vispmorph-bench-compare: " + message + "\n")
    sys.exit(2)


def read_dir(path):
    try:
        rows = read_runs(path, COLUMNS)
    except BenchFileError as e:
        fail(str(e))
    runs = {}
    for r in rows:
        k = tuple(r[c] for c in KEY)
        if k in runs:
            fail("%s: run %s appears twice" % (path, "/".join(k)))
        runs[k] = r
    return runs, yardstick(read_meta(path))  # no summary: no yardstick, no ratio


def outcome(r):
    return "success" if success(r) else "failed: " + (r["failure"] or "?")


def final(r):
    return "%s / %s" % (r["final_t_mm"] or "-", r["final_r_deg"] or "-")


def run_name(k):
    return "%s | %s | %s | %s" % (k[0], k[1], k[2], k[3])


def print_runs(keys, before, after, both_outcomes):
    """The runs \a keys as a markdown table: outcome (before -> after, or the one they share), iterations, final error."""
    print()
    print("| set | robot | controller | scenario | object | %s | iterations | final error (mm / deg) |"
          % ("before -> after" if both_outcomes else "outcome"))
    print("|---|---|---|---|---|---|---|---|")
    for k in keys:
        b, a = before[k], after[k]
        result = "%s -> %s" % (outcome(b), outcome(a)) if both_outcomes else outcome(a)
        print("| %s | %s | %s | %s -> %s | %s -> %s |" % (
            run_name(k), b["object"], result, b["iterations"], a["iterations"], final(b), final(a)))


def compute(rows):
    """Mean measure + control (ms) over the runs that measured, or None."""
    totals = []
    for r in rows:
        m, c = number(r["measure_ms"]), number(r["control_ms"])
        if m is not None and c is not None and m + c > 0:
            totals.append(m + c)
    return sum(totals) / len(totals) if totals else None


def main(argv):
    strict = "--strict" in argv
    dirs = [a for a in argv if a != "--strict"]
    if len(dirs) != 2 or any(a.startswith("--") for a in dirs):
        fail("usage: vispmorph-bench-compare.py [--strict] BEFORE AFTER")
    before, yb = read_dir(dirs[0])
    after, ya = read_dir(dirs[1])
    common = [k for k in before if k in after]
    only_before = [k for k in before if k not in after]
    only_after = [k for k in after if k not in before]
    changed_outcome = [k for k in common if outcome(before[k]) != outcome(after[k])]
    changed_result = [k for k in common if k not in changed_outcome
                      and any(before[k][c] != after[k][c] for c in RESULT)]
    identical = len(common) - len(changed_outcome) - len(changed_result)

    print("# %s -> %s" % (dirs[0], dirs[1]))
    print()
    print("- runs compared: %d; identical: %d; outcome changed: %d; same outcome, other result: %d"
          % (len(common), identical, len(changed_outcome), len(changed_result)))
    print("- only in %s: %d; only in %s: %d" % (dirs[0], len(only_before), dirs[1], len(only_after)))
    for k in only_before + only_after:
        print("  - %s (%s)" % ("/".join(k), dirs[0] if k in before else dirs[1]))

    if changed_outcome:
        print()
        print("Outcome changed:")
        print_runs(changed_outcome, before, after, True)

    if changed_result:
        nearer = farther = 0
        deltas = []
        for k in changed_result:
            tb, ta = number(before[k]["final_t_mm"]), number(after[k]["final_t_mm"])
            if success(before[k]) and tb is not None and ta is not None and ta != tb:
                deltas.append(ta - tb)
                nearer += ta < tb
                farther += ta > tb
        print()
        print("Same outcome, other result (successes: %d nearer the goal%s, %d farther%s):" % (
            nearer, " by up to %.3g mm" % -min(deltas) if nearer else "", farther,
            " by up to %.3g mm" % max(deltas) if farther else ""))
        print_runs(changed_result, before, after, False)

    print()
    print("Compute per iteration (measure + control, mean over the runs that measured; yardstick %s -> %s ms):" % (
        "%.3f" % yb if yb else "-", "%.3f" % ya if ya else "-"))
    print()
    print("| set | controller | before (ms) | after (ms) | before / yardstick | after / yardstick |")
    print("|---|---|---|---|---|---|")
    sets = ordered([k[0] for k in common], SETS)
    controllers = ordered([k[2] for k in common], [])
    for s in sets:
        for c in controllers:
            keys = [k for k in common if k[0] == s and k[2] == c]
            if not keys:
                continue
            mb, ma = compute([before[k] for k in keys]), compute([after[k] for k in keys])
            cell = lambda v: "%.3f" % v if v is not None else "-"
            ratio = lambda v, y: "%.2f" % (v / y) if v is not None and y else "-"
            print("| %s | %s | %s | %s | %s | %s |" % (s, c, cell(mb), cell(ma), ratio(mb, yb), ratio(ma, ya)))

    if strict and (changed_outcome or only_before or only_after):
        sys.exit(1)


if __name__ == "__main__":
    main(sys.argv[1:])
