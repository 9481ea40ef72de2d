#!/usr/bin/python3
"""The README's re-identification, retrieval and correspondence speed tables, from the runs' own files.

Usage: vispmorph-results-table.py --reid OUTDIR
       vispmorph-results-table.py --retrieval OUTDIR [OUTDIR ...]
       vispmorph-results-table.py --match FILE.json

--reid reads OUTDIR/summary.json of a vispmorph-reid run and prints a row per model and group of conditions (pose,
noise, blur, tilt; occlusion, combined-occlusion; any other condition of the run after them): the right answers,
the wrong ones, the rejections and of those the look-alikes' (two templates fit the view alike; "-" for runs that did
not count them) over the views of present shapes, and the false accepts over the views of absent ones, in per cent
of the condition's views.
--retrieval reads OUTDIR/summary.json of vispmorph-retrieval runs (Kimia-99 and MPEG-7, told apart by the name of
their image folder) and prints a row per distance: the Kimia-99 counts at ranks 1..10 and their sum, the MPEG-7
bull's-eye score and the wall time of the MPEG-7 matrix. The first row is Shape Context's published figures (a
citation, not a run: Sebastian, Klein and Kimia, PAMI 2004, for Kimia-99; Belongie, Malik and Puzicha, PAMI 2002,
for MPEG-7).
--match reads the JSON that vispmorph-perf-match writes (--benchmark_out=FILE.json --benchmark_out_format=json) and
prints a row per polygon size N: the brute force, the fast exact search, its speed-up over the brute force and the
windowed search (starts within +-4 vertices of the previous frame's), each the CPU time of its fastest repetition
(the least disturbed by whatever else the machine runs).
Above each table, the commit its runs were measured at (the summaries' "commit", the benchmark context's "commit";
"commit not recorded" for older runs). The tables are computed from the files only: what they say is what the runs
did. Exit status: 0, or 2 on a missing or malformed file or bad arguments.
"""

import json
import os
import re
import sys

from vispmorph_bench_files import commit_stamp

REID_GROUPS = (("pose", "noise", "blur", "tilt"), ("occlusion", "combined-occlusion"))
REID_FIELDS = ("model", "condition", "views", "right", "wrong", "rejected", "absent_views", "false_accepts")
RETRIEVAL_FIELDS = ("images", "distance", "rank_counts", "rank_counts_sum", "bullseye_percent", "matrix_seconds",
                    "threads")
DATASETS = {"kimia99": "Kimia-99", "mpeg7": "MPEG-7"}
SHAPE_CONTEXT = "| Shape Context (published; cited, not run) | 97 91 88 85 84 77 75 66 56 37 (756) | 76.51 % | |"
MATCH_SEARCHES = ("brute", "fast", "window")
TIME_UNITS = {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}  # in microseconds


class ResultsFileError(Exception):
    pass


def fail(message):
    sys.stderr.write("vispmorph-results-table: " + message + "\n")
    sys.exit(2)


def read_json(path):
    """The JSON value of the file at PATH, or ResultsFileError saying why not."""
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except OSError as e:
        raise ResultsFileError("cannot read '%s': %s" % (path, e.strerror))
    except ValueError as e:
        raise ResultsFileError("'%s' is not JSON: %s" % (path, e))


def read_summary(outdir, fields):
    path = os.path.join(outdir, "summary.json")
    summary = read_json(path)
    if not isinstance(summary, dict):
        raise ResultsFileError("'%s': expected an object" % path)
    missing = [k for k in fields if k not in summary]
    if missing:
        raise ResultsFileError("'%s' has no %s" % (path, ", ".join(missing)))
    if not isinstance(summary.get("commit", ""), str):
        raise ResultsFileError("'%s': commit is not a string" % path)
    return path, summary


def percent(n, total):
    """n / total in per cent, two decimals at most, trailing zeros dropped (100, 97.5, 2.47)."""
    return ("%.2f" % (100.0 * n / total)).rstrip("0").rstrip(".")


def cells(values):
    """One cell for a group of conditions: 0 when all are none, else every percentage, joined by slashes."""
    if all(n == 0 for n, _ in values):
        return "0"
    return " / ".join(percent(n, total) for n, total in values) + " %"


def reid_table(outdir):
    path, summary = read_summary(outdir, ("results",))
    rows = summary["results"]
    if not isinstance(rows, list) or not rows:
        raise ResultsFileError("'%s': results is not a list of rows" % path)
    by = {}
    models = []
    for r in rows:
        if not isinstance(r, dict) or any(k not in r for k in REID_FIELDS):
            raise ResultsFileError("'%s': a row of results lacks one of %s" % (path, ", ".join(REID_FIELDS)))
        if not all(isinstance(r[k], int) and r[k] >= 0 for k in REID_FIELDS[2:]):
            raise ResultsFileError("'%s': a row of results has a count that is not a whole number" % path)
        lk = r.get("rejected_look_alikes", 0)
        if not isinstance(lk, int) or isinstance(lk, bool) or not 0 <= lk <= r["rejected"]:
            raise ResultsFileError("'%s': a row's rejected_look_alikes is not a count within its rejections" % path)
        if r["views"] == 0 or r["absent_views"] == 0:
            raise ResultsFileError("'%s': %s, %s has no views" % (path, r["model"], r["condition"]))
        if r["model"] not in models:
            models.append(r["model"])
        by[(r["model"], r["condition"])] = r
    conditions = []
    for r in rows:
        if r["condition"] not in conditions:
            conditions.append(r["condition"])
    groups = [[c for c in g if c in conditions] for g in REID_GROUPS]
    grouped = {c for g in groups for c in g}
    groups = [g for g in groups if g] + [[c] for c in conditions if c not in grouped]
    absent = sorted({r["absent_views"] for r in rows})
    lines = [commit_stamp([(outdir, summary.get("commit"))]), "",
             "| model | condition | right | wrong | rejected | rejected as look-alikes | false accepts (%s absent) |" %
             " / ".join(str(a) for a in absent), "|---|---|---|---|---|---|---|"]
    for m in models:
        for g in groups:
            if any((m, c) not in by for c in g):
                raise ResultsFileError("'%s': %s lacks a condition of %s" % (path, m, " / ".join(g)))
            rs = [by[(m, c)] for c in g]
            counted = all("rejected_look_alikes" in r for r in rs)
            lines.append("| %s | %s | %s | %s | %s | %s | %s |" % (
                m, " / ".join(g), cells([(r["right"], r["views"]) for r in rs]),
                cells([(r["wrong"], r["views"]) for r in rs]), cells([(r["rejected"], r["views"]) for r in rs]),
                cells([(r["rejected_look_alikes"], r["views"]) for r in rs]) if counted else "-",
                cells([(r["false_accepts"], r["absent_views"]) for r in rs])))
    return lines


def distance_label(d, path):
    try:
        mirrors = ", mirrors" if d["mirrors"] else ""
        if d["model"] == "height":
            return "height (%d points, %d segments, skip %g, %d starts%s)" % (
                d["points"], d["segments"], d["skip"], d["starts"], mirrors)
        return "%s (%d points%s, kb %g)" % (d["model"], d["points"], mirrors, d["kb"])
    except (KeyError, TypeError, ValueError):
        raise ResultsFileError("'%s': distance lacks its model, points, mirrors, kb or the height model's settings"
                               % path)


def retrieval_table(outdirs):
    rows = {}  # label -> {dataset: (path, summary)}
    threads = set()
    commits = []
    for outdir in outdirs:
        path, s = read_summary(outdir, RETRIEVAL_FIELDS)
        commits.append((outdir, s.get("commit")))
        name = os.path.basename(os.path.normpath(str(s["images"]))).lower()
        if name not in DATASETS:
            raise ResultsFileError("'%s': images '%s' is neither of %s" % (path, s["images"], ", ".join(DATASETS)))
        label = distance_label(s["distance"], path)
        if name in rows.setdefault(label, {}):
            raise ResultsFileError("'%s': a second %s run of %s" % (path, DATASETS[name], label))
        ranks = s["rank_counts"]
        if not isinstance(ranks, list) or len(ranks) != 10 or sum(ranks) != s["rank_counts_sum"]:
            raise ResultsFileError("'%s': rank_counts is not 10 counts summing to rank_counts_sum" % path)
        rows[label][name] = s
        if name == "mpeg7":
            threads.add(s["threads"])
    lines = [commit_stamp(commits), "",
             "| distance | Kimia-99 ranks 1..10 (sum) | MPEG-7 bull's-eye | MPEG-7 matrix, wall time (%s threads) |" %
             (" / ".join(str(t) for t in sorted(threads)) or "-"), "|---|---|---|---|", SHAPE_CONTEXT]
    for label, runs in rows.items():
        k, m = runs.get("kimia99"), runs.get("mpeg7")
        lines.append("| %s | %s | %s | %s |" % (
            label, "%s (%d)" % (" ".join(str(c) for c in k["rank_counts"]), k["rank_counts_sum"]) if k else "",
            "%.2f %%" % m["bullseye_percent"] if m else "", "%.0f s" % m["matrix_seconds"] if m else ""))
    return lines


def match_table(path):
    report = read_json(path)
    if not isinstance(report, dict) or not isinstance(report.get("benchmarks"), list) or \
            not isinstance(report.get("context", {}), dict):
        raise ResultsFileError("'%s': not a Google Benchmark report (context, benchmarks)" % path)
    commit = report.get("context", {}).get("commit")
    if commit is not None and not isinstance(commit, str):
        raise ResultsFileError("'%s': commit is not a string" % path)
    fastest = {}  # (search, N) -> least CPU time of a repetition, us
    for b in report["benchmarks"]:
        if not isinstance(b, dict) or b.get("run_type", "iteration") != "iteration" or b.get("error_occurred"):
            continue
        m = re.fullmatch(r"BM_(%s)/([0-9]+)" % "|".join(MATCH_SEARCHES), str(b.get("run_name", b.get("name", ""))))
        if not m:
            continue
        try:
            t = float(b["cpu_time"]) * TIME_UNITS[b["time_unit"]]
        except (KeyError, TypeError, ValueError):
            raise ResultsFileError("'%s': %s has no cpu_time in a known time_unit" % (path, m.group(0)))
        key = (m.group(1), int(m.group(2)))
        fastest[key] = min(t, fastest.get(key, t))
    sizes = sorted({n for (search, n) in fastest if ("brute", n) in fastest and ("fast", n) in fastest})
    if not sizes:
        raise ResultsFileError("'%s': no N with both BM_brute/N and BM_fast/N" % path)
    lines = [commit_stamp([(path, commit)]), "",
             "| N | brute force | fast exact | speed-up | window (+-4 starts) |", "|---|---|---|---|---|"]
    for n in sizes:
        b, f, w = fastest[("brute", n)], fastest[("fast", n)], fastest.get(("window", n))
        lines.append("| %d | %.0f us | %.0f us | %.1fx | %s |" % (n, b, f, b / f, "%.0f us" % w if w else "-"))
    return lines


def main(argv):
    if len(argv) == 2 and argv[0] == "--reid":
        make = lambda: reid_table(argv[1])
    elif len(argv) >= 2 and argv[0] == "--retrieval":
        make = lambda: retrieval_table(argv[1:])
    elif len(argv) == 2 and argv[0] == "--match":
        make = lambda: match_table(argv[1])
    else:
        sys.stderr.write(__doc__)
        return 2
    try:
        lines = make()
    except ResultsFileError as e:
        fail(str(e))
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
