#!/usr/bin/python3
"""Angle of repose of heaps of rods against their aspect ratio (scenes/clumps/heap-rod*.toml).

usage: heap_angles.py RUNS_DIR [--yade YADE_DIR] [--out DIR]

RUNS_DIR holds the run folders heap-rod<k>, heap-rod<k>-seed2, heap-rod<k>-seed3 (k = 1, 2, 3, 5:
rods of k spheres of d = 1 in a row, 0.5 d apart, aspect ratio 1 + 0.5 (k - 1); k = 1 spheres),
written by `yuxi run scenes/clumps/heap-rod<k>[-seed<n>].toml -o RUNS_DIR/<name>`. From each it
reads RUN/measurements.csv: the angle of a line fitted to the column tops (2 d columns, 2.8-9.8 d
from the axis), its R^2 and the kinetic energy per grain at the last row
(t_end, the pour settled). An aspect ratio's angle is the mean of its heaps with the standard
error of the mean.

With --yade, YADE_DIR holds the same heaps poured by YADE (bench/peers/yade/clump_heap.py, run in
YADE_DIR: its folders heap-rod<k>[-seed<n>]), whose measurements.csv has the same columns; their
angles go beside yuxi's in the table, the CSV (engine yade) and the plot.

Writes into DIR (default: the current folder):
  heap_angles.csv   engine,run,rod,aspect_ratio,angle,r2,ke_per_grain
  heap_angles.png   the angle of each heap and the means against the aspect ratio
and prints the table of means as Markdown.
"""
import argparse
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402

RODS = (1, 2, 3, 5)
SEEDS = ("", "-seed2", "-seed3")


def fail(msg):
    sys.exit(f"heap_angles.py: {msg}")


def last_row(path):
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        fail(f"cannot read {path}: {e.strerror}")
    if not rows or "angle" not in rows[-1]:
        fail(f"{path}: no rows with an 'angle' column (a heap-rod scene's measurements.csv?)")
    return rows[-1]


def read_heaps(runs, engine):
    """One row per heap of `engine` whose runs lie in `runs`."""
    heaps = []
    for rod in RODS:
        for seed in SEEDS:
            name = f"heap-rod{rod}{seed}"
            row = last_row(os.path.join(runs, name, "measurements.csv"))
            heaps.append({"engine": engine, "run": name, "rod": rod,
                          "aspect_ratio": 1 + 0.5 * (rod - 1), "angle": float(row["angle"]),
                          "r2": float(row["angle_r2"]), "ke_per_grain": float(row["ke"])})
    return heaps


def mean_and_error(values):
    mean = sum(values) / len(values)
    sd = math.sqrt(sum((a - mean) ** 2 for a in values) / (len(values) - 1))
    return mean, sd / math.sqrt(len(values))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("runs")
    parser.add_argument("--yade", help="the folder of the same heaps poured by YADE")
    parser.add_argument("--out", default=".")
    args = parser.parse_args()
    engines = {"yuxi": read_heaps(args.runs, "yuxi")}
    if args.yade:
        engines["YADE"] = read_heaps(args.yade, "yade")
    heaps = [h for rows in engines.values() for h in rows]
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "heap_angles.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(heaps[0]))
        w.writeheader()
        w.writerows(heaps)
    names = list(engines)
    print("| rods of | aspect ratio | " + " | ".join(
        f"{e}: the three heaps [degrees] | {e}: mean +- standard error | {e}: fit R^2"
        for e in names) + " |")
    print("|---|---|" + "---|---|---|" * len(names))
    fig, ax = plt.subplots(figsize=(5.5, 4))
    for k, (engine, rows) in enumerate(engines.items()):
        means = []
        for rod in RODS:
            mine = [h for h in rows if h["rod"] == rod]
            means.append((mine[0]["aspect_ratio"], *mean_and_error([h["angle"] for h in mine])))
        ax.plot([h["aspect_ratio"] for h in rows], [h["angle"] for h in rows], "o",
                color=f"C{k}", alpha=0.35, label=f"{engine}: each heap")
        ax.errorbar([m[0] for m in means], [m[1] for m in means], yerr=[m[2] for m in means],
                    fmt="s-", color=f"C{k}", capsize=3, label=f"{engine}: mean +- standard error")
    for rod in RODS:
        cells = []
        for rows in engines.values():
            mine = [h for h in rows if h["rod"] == rod]
            angles = [h["angle"] for h in mine]
            mean, se = mean_and_error(angles)
            r2 = [h["r2"] for h in mine]
            cells += [", ".join(f"{a:.2f}" for a in angles), f"{mean:.2f} +- {se:.2f}",
                      f"{min(r2):.2f}-{max(r2):.2f}"]
        print(f"| {rod} sphere{'s' if rod > 1 else ''} | {1 + 0.5 * (rod - 1):g} | "
              + " | ".join(cells) + " |")
    ax.set_xlabel("aspect ratio (rod length / width)")
    ax.set_ylabel("angle of repose [degrees]")
    ax.set_title("heaps of rods of 1-5 spheres, mu = 0.5")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "heap_angles.png"), dpi=120)


if __name__ == "__main__":
    main()
