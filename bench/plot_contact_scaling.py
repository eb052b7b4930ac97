#!/usr/bin/env python3
"""Plot the scaling study written by `contact_study --scaling`.

    python3 bench/plot_contact_scaling.py [contact_scaling.csv] [contact_scaling.png]

Two panels, pyramids and poured spheres: wall-clock cost per step (ms)
against the number of dynamic bodies, log-log, one line per policy (spook's
default hybrid SPLIT and iterative 16, Bullet's and ODE's iterative solvers
when the study ran them). Runs stopped as too slow or non-finite are marked
with a red cross (their cost is that of the steps they took). Dashed: the
1 million body-steps per second line (issue 20's goal for 10,000 spheres).
Without matplotlib it prints a note and exits 0.
"""

import csv
import sys
from collections import OrderedDict

from study_plot import pyplot_or_note

MARKERS = {"hybrid SPLIT": "o", "iterative16": "<", "bullet SI": "v", "ode quick": "*"}


def read(path):
    scenes = OrderedDict()
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            friction = row["friction_solve_type"]
            policy = row["policy"] if friction == "-" else f"{row['policy']} {friction}"
            scenes.setdefault(row["scene"], OrderedDict()).setdefault(policy, []).append(
                (int(row["bodies"]), float(row["ms_per_step"]), row["verdict"] in ("too slow", "non-finite")))
    return scenes


def main():
    source = sys.argv[1] if len(sys.argv) > 1 else "contact_scaling.csv"
    target = sys.argv[2] if len(sys.argv) > 2 else source.rsplit(".", 1)[0] + ".png"
    plt = pyplot_or_note(source)
    if plt is None:
        return 0
    scenes = read(source)
    if not scenes:
        print(f"note: {source} holds no runs; no plot written")
        return 0
    fig, axes = plt.subplots(1, len(scenes), figsize=(5.6 * len(scenes), 4.6), squeeze=False)
    for ax, (scene, policies) in zip(axes.flat, scenes.items()):
        counts = sorted({n for runs in policies.values() for n, _, _ in runs})
        for policy, runs in policies.items():
            runs.sort()
            ax.plot([n for n, _, _ in runs], [ms for _, ms, _ in runs], marker=MARKERS.get(policy, "o"),
                    label=policy)
            failed = [(n, ms) for n, ms, bad in runs if bad]
            if failed:
                ax.scatter(*zip(*failed), marker="x", color="red", s=90, zorder=4)
        ax.plot(counts, [n / 1e3 for n in counts], linestyle="--", color="gray", linewidth=1,
                label="1e6 body-steps/s")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(f"{scene}: cost per step against bodies")
        ax.set_xlabel("dynamic bodies")
        ax.set_ylabel("wall-clock per step (ms)")
        ax.grid(True, which="both", alpha=0.2)
        ax.legend(fontsize=8)
    fig.suptitle("h = 1/60, 2 s per run, mean over the last second (red x: stopped after 120 s or non-finite)",
                 fontsize=9)
    fig.tight_layout(rect=(0, 0, 1, 0.94))
    fig.savefig(target, dpi=110)
    print(f"plot written to {target}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
