#!/usr/bin/python3
"""Turns the CSV files of the tutorials in tutorials/paper/ into the graphs of the paper's Figures 2 and 3.

Usage: /usr/bin/python3 plot-paper-figures.py DIR   (DIR holds fig2-*.csv, fig3-*.csv and fig2-*.png;
the graphs fig2-rotation.png and fig3-translation.png are written there). Run with Debian's interpreter
(python3-matplotlib) and MPLBACKEND=Agg: nothing is displayed.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def column(rows, name):
    return [float(r[name]) for r in rows]


def figure2(d):
    """Layout of the paper's Figure 2: start and final views on the left, the two graphs on the right."""
    moves, subs = read(os.path.join(d, "fig2-moves.csv")), read(os.path.join(d, "fig2-subgoals.csv"))
    fig = plt.figure(figsize=(10, 6.5))
    for i, (name, title) in enumerate([("fig2-start.png", "start pose"), ("fig2-final.png", "final pose")]):
        ax = fig.add_subplot(2, 2, 1 + 2 * i)
        ax.imshow(mpimg.imread(os.path.join(d, name)))
        ax.set_title(title + " (stored view in green)")
        ax.axis("off")
    ax = fig.add_subplot(2, 2, 2)
    ax.plot(column(moves, "move"), column(moves, "rotation_error_deg"), "o-", ms=3)
    ax.set_xlabel("move")
    ax.set_ylabel("angular pose error (deg)")
    ax.set_title("error to the desired pose after each move")
    ax.grid(True, alpha=0.3)
    ax = fig.add_subplot(2, 2, 4)
    ax.bar(column(subs, "subgoal"), column(subs, "virtual_vs_real_deg"))
    ax.axhline(5.73, color="r", ls="--", lw=1, label="switching threshold 0.10 rad")
    ax.set_xlabel("virtual image (sub-goal)")
    ax.set_ylabel("angular error virtual vs real (deg)")
    ax.set_title("virtual image vs real image when reached")
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    fig.suptitle("Figure 2: rotational alignment of the pliers (simulated Viper850, 150 deg)")
    fig.tight_layout()
    out = os.path.join(d, "fig2-rotation.png")
    fig.savefig(out, dpi=100)
    return out


def figure3(d):
    """Layout of the paper's Figure 3: image and world errors on top, sub-goal errors and trajectory below."""
    moves, subs = read(os.path.join(d, "fig3-moves.csv")), read(os.path.join(d, "fig3-subgoals.csv"))
    m = column(moves, "move")
    fig, axes = plt.subplots(2, 2, figsize=(10, 7.5))
    ax = axes[0][0]
    ax.plot(m, column(moves, "image_error_px"), "o-", ms=3)
    ax.set_xlabel("move")
    ax.set_ylabel("error in the morph plane (px)")
    ax.set_title("error in the image")
    ax = axes[0][1]
    ax.plot(m, column(moves, "world_error_mm"), "o-", ms=3, color="tab:green")
    ax.set_xlabel("move")
    ax.set_ylabel("error in the world (mm)")
    ax.set_title("error in the world (simulator truth)")
    ax = axes[1][0]
    ax.bar(column(subs, "subgoal"), column(subs, "virtual_vs_real_px"))
    ax.axhline(5.0, color="r", ls="--", lw=1, label="switching threshold 5 px")
    ax.set_xlabel("virtual image (sub-goal)")
    ax.set_ylabel("error virtual vs real (px)")
    ax.set_title("virtual image vs real image when reached")
    ax.legend(fontsize=8)
    ax = axes[1][1]
    ax.plot(column(moves, "camera_x_mm"), column(moves, "camera_y_mm"), "o-", ms=3, label="camera after each move")
    ax.plot(column(subs, "camera_x_mm"), column(subs, "camera_y_mm"), "s", mfc="none", ms=9, color="tab:orange",
            label="sub-goal reached")
    ax.plot([0], [0], "k*", ms=12, label="desired pose")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.invert_yaxis()  # y down, as in the image
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_title("camera trajectory in the plane")
    ax.legend(fontsize=8)
    for row in axes:
        for a in row:
            a.grid(True, alpha=0.3)
    fig.suptitle("Figure 3: translational alignment with the wedge (simulated Viper850, 70 mm)")
    fig.tight_layout()
    out = os.path.join(d, "fig3-translation.png")
    fig.savefig(out, dpi=100)
    return out


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    for out in (figure2(sys.argv[1]), figure3(sys.argv[1])):
        print("wrote", out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
