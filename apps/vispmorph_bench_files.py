"""What vispmorph-bench-plots.py and vispmorph-bench-table.py both read from a vispmorph-bench output folder: the
canonical order of the sets, runs.csv's fields as numbers, and the CSV files themselves. No matplotlib here: the
table needs none.
"""

import csv
import json
import math
import os

# Canonical orders of the sets (DESIGN.md, benchmark protocol) and of the controllers (VISPMorph's, then the stock
# ones); names not listed are appended in order of appearance.
SETS = ["planar", "planar-hard", "6dof", "calib", "calib-no-tilt", "noise", "occlusion", "deformable", "faults"]
CONTROLLERS = ["morph", "morph-planar", "morph-vpservo", "ibvs-current", "ibvs-desired", "ibvs-mean", "pbvs", "moments",
               "moments-planar"]


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


def read_meta(path):
    """The "meta" object of OUTDIR/summary.json, or {} when the summary is missing or unreadable (an older run)."""
    try:
        with open(os.path.join(path, "summary.json")) as f:
            meta = json.load(f).get("meta", {})
    except (OSError, ValueError, AttributeError):
        return {}
    return meta if isinstance(meta, dict) else {}


def yardstick(meta):
    """The run's machine yardstick (ms): the mean of its readings before and after the runs, or None."""
    values = [number(meta.get(k)) for k in ("yardstick_extract_ms_before", "yardstick_extract_ms_after")]
    values = [v for v in values if v and v > 0]
    return sum(values) / len(values) if values else None
