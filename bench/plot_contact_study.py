#!/usr/bin/env python3
"""Plot the contact study written by bench/contact_study.

    python3 bench/plot_contact_study.py [contact_study.csv] [contact_study.png]

One panel per scene: wall-clock cost per step (ms) against the drift (m),
log-log, one marker per policy (solver and, for hybrid, the friction solve
type) and per reference engine (Bullet, ODE) when the study ran them. The spheres scene has no drift: its panel plots the deepest
penetration over the last second instead. Runs that went non-finite or were
stopped as too slow are drawn as a red cross at the top of the panel (their
cost is that of the steps they took). Without matplotlib it prints a note and
exits 0: the CSV and the table the study prints hold the same numbers.
"""

import csv
import math
import sys
from collections import OrderedDict

from study_plot import pyplot_or_note

MARKERS = {
    "direct": "D",
    "hybrid SPLIT": "o",
    "hybrid DIRECT_AND_ITERATIVE": "s",
    "hybrid DIRECT": "P",
    "iterative16": "<",
    "iterative64": ">",
    "bullet SI": "v",
    "bullet MLCP": "^",
    "ode quick": "*",
    "ode world": "h",
}
OK_DRIFT, FELL_DRIFT = 1e-3, 0.1  # m, as in contact_study.cpp
SOFT_PENETRATION = 0.01  # m, spheres
FLOOR = 1e-12  # m: a zero is drawn here on the log axis


def label(row):
    friction = row["friction_solve_type"]
    return row["policy"] if friction == "-" else f"{row['policy']} {friction}"


def read(path):
    scenes = OrderedDict()
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            drift = float(row["drift_m"])
            scenes.setdefault(row["scene"], []).append(
                {
                    "policy": label(row),
                    "cost": float(row["ms_per_step"]),
                    "drift": drift,
                    "penetration": float(row["max_penetration_m"]),
                    "failed": row["finite"] != "1" or row["verdict"] == "too slow",
                }
            )
    return scenes


def main():
    source = sys.argv[1] if len(sys.argv) > 1 else "contact_study.csv"
    target = sys.argv[2] if len(sys.argv) > 2 else source.rsplit(".", 1)[0] + ".png"
    plt = pyplot_or_note(source)
    if plt is None:
        return 0

    scenes = read(source)
    if not scenes:
        print(f"note: {source} holds no runs; no plot written")
        return 0
    columns = min(len(scenes), 2)
    rows = math.ceil(len(scenes) / columns)
    fig, axes = plt.subplots(rows, columns, figsize=(5.6 * columns, 4.4 * rows), squeeze=False)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    order = list(MARKERS)
    for ax, (scene, runs) in zip(axes.flat, scenes.items()):
        by_penetration = all(math.isnan(r["drift"]) for r in runs)
        key = "penetration" if by_penetration else "drift"
        good = [max(r[key], FLOOR) for r in runs if not r["failed"] and not math.isnan(r[key])]
        limit = SOFT_PENETRATION if by_penetration else FELL_DRIFT
        top = max(good + [limit]) * 3.0
        for r in runs:
            index = order.index(r["policy"]) if r["policy"] in order else len(order)
            y = top if r["failed"] or math.isnan(r[key]) else max(r[key], FLOOR)
            ax.scatter([r["cost"]], [y], s=60, marker=MARKERS.get(r["policy"], "o"),
                       color=colors[index % len(colors)], label=r["policy"], zorder=3)
            if r["failed"]:
                ax.scatter([r["cost"]], [top], marker="x", color="red", s=90, zorder=4)
        if by_penetration:
            ax.axhspan(SOFT_PENETRATION, top * 10, color="red", alpha=0.06)
        else:
            ax.axhspan(FELL_DRIFT, top * 10, color="red", alpha=0.06)
            ax.axhline(OK_DRIFT, color="green", linestyle=":", linewidth=1)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylim(top=top * 2)
        ax.set_title(scene)
        ax.set_xlabel("wall-clock per step (ms)")
        ax.set_ylabel("deepest penetration, last second (m)" if by_penetration else "drift (m)")
        ax.grid(True, which="both", alpha=0.2)
    for ax in list(axes.flat)[len(scenes):]:
        ax.axis("off")
    legend = OrderedDict()
    for ax in axes.flat:
        for handle, name in zip(*ax.get_legend_handles_labels()):
            legend.setdefault(name, handle)
    fig.legend(legend.values(), legend.keys(), loc="lower center", ncol=min(len(legend), 5), frameon=False)
    fig.suptitle("contact scenes: cost against drift (dotted: 1 mm; shaded: fell, >= 0.1 m, or spheres"
                 " penetration > 1 cm; red x: non-finite or too slow)", fontsize=9)
    fig.tight_layout(rect=(0, 0.14 if rows == 1 else 0.08, 1, 0.95))
    fig.savefig(target, dpi=110)
    print(f"plot written to {target}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
