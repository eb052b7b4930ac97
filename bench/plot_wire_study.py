#!/usr/bin/env python3
"""Plot the wire study written by bench/wire_study.

    python3 bench/plot_wire_study.py [wire_study.csv] [wire_study.png]

Cost against accuracy, log-log: one marker per phase of the pay-out scene
(tension at the load against m g) and per friction coefficient of the
12-fall reeving (winch tension against the capstan chain), at its mean time
per step with a bar up to its slowest step; the dashed line is real time at
the study's 60 Hz. Without matplotlib it prints a note and exits 0: the CSV
and the table the study prints hold the same numbers.
"""

import csv
import sys

from study_plot import pyplot_or_note

REAL_TIME_MS = 1000.0 / 60.0
FLOOR = 1e-6  # relative error: a zero is drawn here on the log axis
MARKERS = {"payout": "o", "reeving": "s"}
TITLES = {"payout": "10 t paid out over two sheaves (tension at the load vs m g)",
          "reeving": "12-fall reeving (winch tension vs the capstan chain)"}


def main():
    source = sys.argv[1] if len(sys.argv) > 1 else "wire_study.csv"
    target = sys.argv[2] if len(sys.argv) > 2 else source.rsplit(".", 1)[0] + ".png"
    plt = pyplot_or_note(source)
    if plt is None:
        return 0
    with open(source, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        print(f"note: {source} holds no runs; no plot written")
        return 0

    fig, ax = plt.subplots(figsize=(7.5, 5.0))
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, row in enumerate(rows):
        mean, slowest = float(row["mean_ms"]), float(row["max_ms"])
        error = max(abs(float(row["error"])), FLOOR)
        label = f"{row['scene']}: {row['phase']} ({row['nodes_min']}-{row['nodes_max']} nodes)"
        color = colors[i % len(colors)]
        ax.errorbar([mean], [error], xerr=[[0.0], [slowest - mean]], fmt=MARKERS.get(row["scene"], "D"),
                    color=color, capsize=3, label=label)
    ax.axvline(REAL_TIME_MS, color="gray", linestyle="--", linewidth=1)
    ax.text(REAL_TIME_MS, ax.get_ylim()[1], " real time (60 Hz)", color="gray", va="top", ha="left", fontsize=8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time per step (ms): mean, bar to the slowest")
    ax.set_ylabel("relative tension error")
    ax.set_title("spook wires at 60 Hz: cost against accuracy", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="best")
    fig.text(0.01, 0.01, "; ".join(TITLES.values()), fontsize=6, color="gray")
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    fig.savefig(target, dpi=120)
    print(f"wrote {target}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
