"""What vispmorph-bench-plots.py and vispmorph-bench-table.py both read from a vispmorph-bench output folder: the
canonical order of the sets, runs.csv's fields as numbers, and the CSV files themselves; and the "Measured at" line
that vispmorph-bench-table.py and vispmorph-results-table.py print above a table. No matplotlib here: the tables need
none.
"""

import csv
import json
import math
import os

# Canonical orders of the sets (DESIGN.md, benchmark protocol) and of the controllers (VISPMorph's, then the stock
# ones); names not listed are appended in order of appearance.
SETS = ["planar", "planar-hard", "6dof", "calib", "calib-no-tilt", "noise", "occlusion", "deformable", "faults",
        "calib-wide", "saturated", "low-contrast", "rough", "gradient", "plane-edge", "large-distractor", "res-1280",
        "res-320"]
# Columns of timings.csv that read_runs() joins to the runs (they are not in runs.csv: they differ between runs).
TIMING_COLUMNS = ("yardstick_ms", "measure_ms", "control_ms", "max_control_ms", "run_cpu_s", "period_ms")
CONTROLLERS = ["morph", "morph-planar", "morph-paper", "morph-vpservo", "ibvs-current", "ibvs-desired", "ibvs-mean",
               "pbvs", "moments", "moments-planar"]


class BenchFileError(Exception):
    """A bench output file that cannot be read: missing, or without the columns asked for."""


def number(text):
    """Float of a CSV field, None when empty or not a finite number."""
    if text is None:
        return None
    text = text.strip()
    if not text:
        return None
    try:
        v = float(text)
    except ValueError:
        return None
    return v if math.isfinite(v) else None


def success(row):
    return (row.get("success") or "").strip() == "1"


def read_csv(path, columns):
    """The non-blank rows of a CSV file as dicts. \\throw BenchFileError when it is missing or lacks a column."""
    if not os.path.isfile(path):
        raise BenchFileError("cannot open " + path)
    try:
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            header = reader.fieldnames or []
            missing = [c for c in columns if c not in header]
            if missing:
                raise BenchFileError("%s: missing column(s) %s" % (path, ", ".join(missing)))
            return [row for row in reader if any((v or "").strip() for v in row.values() if isinstance(v, str))]
    except (OSError, csv.Error) as e:
        raise BenchFileError("%s: %s" % (path, e))


def ordered(present, canonical):
    """The names of \\a canonical that are present, then the others in order of appearance."""
    seen = []
    for name in present:
        if name not in seen:
            seen.append(name)
    return [n for n in canonical if n in seen] + [n for n in seen if n not in canonical]


def read_runs(path, columns):
    """OUTDIR/runs.csv's rows, each with its compute times from OUTDIR/timings.csv (TIMING_COLUMNS, joined on set,
    robot, controller and scenario; empty when there is no timings.csv or no row for the run). Only the columns of
    \\a columns that are not timing columns must be in runs.csv. \\throw BenchFileError as read_csv()."""
    rows = read_csv(os.path.join(path, "runs.csv"), [c for c in columns if c not in TIMING_COLUMNS])
    key = ("set", "robot", "controller", "scenario")
    times = {}
    timings = os.path.join(path, "timings.csv")
    if os.path.isfile(timings):
        for t in read_csv(timings, key + TIMING_COLUMNS):
            times[tuple(t[k] for k in key)] = t
    for r in rows:
        t = times.get(tuple(r.get(k, "") for k in key), {})
        for c in TIMING_COLUMNS:
            if c in t or c not in r:
                r[c] = t.get(c, "")
    return rows


def read_meta(path):
    """The "meta" objects of OUTDIR/summary.json (the settings) and OUTDIR/timings.json (the machine), merged; {} when
    both are missing or unreadable (an older run)."""
    meta = {}
    for name in ("summary.json", "timings.json"):
        try:
            with open(os.path.join(path, name)) as f:
                m = json.load(f).get("meta", {})
        except (OSError, ValueError, AttributeError):
            continue
        if isinstance(m, dict):
            meta.update(m)
    return meta


def interval(k, n):
    """The 95 % interval of a rate of k in n, as the bench computes it: Wilson's, [0, 3 / n] for k = 0."""
    if n == 0:
        return 0.0, 1.0
    if k == 0:
        return 0.0, min(1.0, 3.0 / n)
    z = 1.959963984540054
    p, z2n = k / n, z * z / n
    centre = (p + z2n / 2) / (1 + z2n)
    half = z * math.sqrt(p * (1 - p) / n + z2n / (4 * n)) / (1 + z2n)
    return max(0.0, centre - half), min(1.0, centre + half)


def yardstick(meta):
    """The run's machine yardstick (ms): the mean of its readings before and after the runs, or None."""
    values = [number(meta.get(k)) for k in ("yardstick_extract_ms_before", "yardstick_extract_ms_after")]
    values = [v for v in values if v and v > 0]
    return sum(values) / len(values) if values else None


def commit_stamp(runs):
    """The line above a table: "Measured at <commit>." from [(run name, commit or None)], the commit each run's tool was
    built at (None: not recorded, a run older than the stamp). Runs at several commits, or some without one, are each
    named after theirs: the table says what it mixes."""
    commits = ordered([c for _, c in runs], [])
    if commits == [None]:
        return "Measured at: commit not recorded."
    if len(commits) == 1:
        return "Measured at %s." % commits[0]
    return "Measured at: %s." % ", ".join(
        "%s (%s)" % (c if c is not None else "commit not recorded", ", ".join(n for n, x in runs if x == c))
        for c in commits)
