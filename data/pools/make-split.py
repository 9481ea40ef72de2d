#!/usr/bin/python3
"""Writes data/pools/split.json: the development and evaluation pools of the shape datasets.

The rule, fixed before any evaluation run:
- a class is identified as DATASET:CLASS (mpeg7:apple, kimia99:3: Kimia-99's classes.csv gives numbers);
- within each dataset the classes are ordered by the SHA-256 of "vispmorph-split-v1:" + their identifier, and the
  first half (rounded down) is the development pool, the rest the evaluation pool;
- byte-identical images are kept once (the first in name order); the others are listed as duplicates and excluded;
- no class is chosen or moved by hand.

Usage: make-split.py [DATASETS_DIR] > data/pools/split.json  (default ../shared/datasets beside the repository)
"""
import csv
import hashlib
import json
import os
import sys

SALT = "vispmorph-split-v1:"


def class_key(c):
    return (0, int(c), "") if c.isdigit() else (1, 0, c.lower())


def natural_key(name):
    stem, _, num = name.rpartition("-")
    num = num.split(".")[0]
    return (stem, int(num)) if num.isdigit() else (name, 0)


def dataset_images(root, dataset):
    """{class: [file names]} of one dataset."""
    classes = {}
    if dataset == "mpeg7":
        for f in sorted(os.listdir(os.path.join(root, "mpeg7")), key=natural_key):
            if f.endswith(".png"):
                classes.setdefault(f.rsplit("-", 1)[0], []).append(f)
    else:
        with open(os.path.join(root, "kimia99", "classes.csv")) as fh:
            for row in csv.DictReader(fh):
                classes.setdefault(row["class"], []).append(row["file"])
        for c in classes.values():
            c.sort()
    return classes


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "..", "..", "shared", "datasets")
    out = {
        "rule": __doc__.split("The rule, fixed before any evaluation run:\n", 1)[1].split("\nUsage:")[0].strip(),
        "salt": SALT,
        "datasets": {},
    }
    for dataset in ("mpeg7", "kimia99"):
        classes = dataset_images(root, dataset)
        seen, duplicates = {}, []
        images = {}
        for c in sorted(classes, key=class_key):
            keep = []
            for f in classes[c]:
                with open(os.path.join(root, dataset, f), "rb") as fh:
                    digest = hashlib.sha256(fh.read()).hexdigest()
                if digest in seen:
                    duplicates.append({"file": f, "same_as": seen[digest]})
                else:
                    seen[digest] = f
                    keep.append(f)
            images[c] = keep
        order = sorted(classes, key=lambda c: hashlib.sha256((SALT + dataset + ":" + c).encode()).hexdigest())
        half = len(order) // 2
        out["datasets"][dataset] = {
            "development": sorted(order[:half], key=class_key),
            "evaluation": sorted(order[half:], key=class_key),
            "duplicates": duplicates,
            "images": {c: images[c] for c in sorted(images, key=class_key)},
        }
    json.dump(out, sys.stdout, indent=1)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
