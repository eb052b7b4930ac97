#!/usr/bin/env python3
"""Plot the speed/accuracy study written by bench/speed_accuracy.

    python3 bench/plot_speed_accuracy.py [--cpu] [--per-second] [speed_accuracy.csv] [speed_accuracy.png]

One panel per scene: cost per step (us) against the worst joint gap (m),
log-log, one marker per solver policy, the points of a policy joined in order
of time step (1/30 s ... 1/240 s; the largest marker is the largest step).
Runs that went non-finite are drawn as a red cross at the top of the panel.
The cost is the wall-clock time per step; --cpu plots the CPU time instead
(steadier on a machine shared with other work). The cost per step hardly
depends on the step, so each policy's points stand in a column; --per-second
plots the cost per simulated second (cost per step / h) instead, where a
smaller step costs more and each policy traces its own speed/accuracy curve.
Without matplotlib it prints a note and exits 0: the CSV and the table the
study prints hold the same numbers.
"""

import csv
import math
import sys
from collections import OrderedDict

from study_plot import pyplot_or_note

MARKERS = {
    "direct": "D",
    "direct-nops": "s",
    "iterative4": "v",
    "iterative16": "<",
    "iterative64": ">",
    "iterative256": "^",
    "hybrid": "o",
    "hybrid-mixed": "P",
}
OK_GAP, BROKEN_GAP = 1e-3, 0.1  # m, as in speed_accuracy.cpp
FLOOR = 1e-12  # m: a gap of zero is drawn here on the log axis


def read(path, cost_column):
    scenes = OrderedDict()
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            scene = scenes.setdefault(row["scene"], OrderedDict())
            scene.setdefault(row["policy"], []).append(
                {
                    "h": float(row["h"]),
                    "cost": float(row[cost_column]),
                    "gap": float(row["worst_gap_m"]),
                    "finite": row["finite"] == "1",
                }
            )
    return scenes


def main():
    flags = {a for a in sys.argv[1:] if a.startswith("--")}
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    cpu, per_second = "--cpu" in flags, "--per-second" in flags
    source = args[0] if args else "speed_accuracy.csv"
    target = args[1] if len(args) > 1 else source.rsplit(".", 1)[0] + ".png"
    plt = pyplot_or_note(source)
    if plt is None:
        return 0

    scenes = read(source, "cpu_us_per_step" if cpu else "cost_us_per_step")
    columns = 3
    rows = math.ceil(len(scenes) / columns)
    fig, axes = plt.subplots(rows, columns, figsize=(5.2 * columns, 4.2 * rows), squeeze=False)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for ax, (scene, policies) in zip(axes.flat, scenes.items()):
        finite_gaps = [max(p["gap"], FLOOR) for runs in policies.values() for p in runs if p["finite"]]
        top = max(finite_gaps + [BROKEN_GAP]) * 3.0
        for index, (policy, runs) in enumerate(policies.items()):
            color = colors[index % len(colors)]
            runs = sorted(runs, key=lambda p: -p["h"])
            xs = [p["cost"] / p["h"] * 1e-3 if per_second else p["cost"] for p in runs]
            ys = [max(p["gap"], FLOOR) if p["finite"] else top for p in runs]
            ax.plot(xs, ys, "-", color=color, alpha=0.4, linewidth=1)
            sizes = [20 + 60 * (p["h"] / runs[0]["h"]) for p in runs]
            ax.scatter(xs, ys, s=sizes, marker=MARKERS.get(policy, "o"), color=color, label=policy, zorder=3)
            bad = [(x, top) for x, p in zip(xs, runs) if not p["finite"]]
            if bad:
                ax.scatter(*zip(*bad), marker="x", color="red", s=80, zorder=4)
        ax.axhspan(BROKEN_GAP, top * 10, color="red", alpha=0.06)
        ax.axhline(OK_GAP, color="green", linestyle=":", linewidth=1)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylim(top=top * 2)
        ax.set_title(scene)
        clock = "CPU time" if cpu else "wall-clock"
        ax.set_xlabel(f"{clock} per simulated second (ms)" if per_second else f"{clock} per step (us)")
        ax.set_ylabel("worst joint gap (m)")
        ax.grid(True, which="both", alpha=0.2)
    for ax in list(axes.flat)[len(scenes):]:
        ax.axis("off")
    handles, labels = axes.flat[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=len(labels), frameon=False)
    fig.suptitle("spook solver policies: cost against worst joint gap (marker size: time step 1/30 ... 1/240 s;"
                 " dotted: 1 mm; shaded: broken, >= 0.1 m)", fontsize=10)
    fig.tight_layout(rect=(0, 0.05, 1, 0.96))
    fig.savefig(target, dpi=110)
    print(f"plot written to {target}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
