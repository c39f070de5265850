#!/usr/bin/env python3
"""Chart of pv_lightkit_orbit.py's result: grouped bars of the interactive and
still frame-time ratios to ParaView's Volume (Shade on) per method (and, for
more than 3 interactive frames per step, the ratio of the last 3 of each step),
with the targets drawn as marks.

    plot_lightkit_orbit.py OUT/lightkit_orbit.csv [OUT/lightkit_orbit.png]

Needs matplotlib (pvpython has it; so may python3).
"""
import csv
import os
import sys


def _float(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return float("nan")


def load_results(csv_path):
    """The rows of a benchmark CSV and the machine.txt beside it (key value
    per line), shared with pv_ct_resolution.py."""
    with open(csv_path) as f:
        rows = list(csv.DictReader(f))
    machine = {}
    machine_path = os.path.join(os.path.dirname(csv_path), "machine.txt")
    if os.path.exists(machine_path):
        for line in open(machine_path):
            key, _, value = line.strip().partition(" ")
            machine[key] = value
    return rows, machine


def plot(csv_path, png_path):
    import math

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker  # noqa: F401 - used through matplotlib.ticker

    rows, machine = load_results(csv_path)

    names = [r["method"] for r in rows]
    # Bars: interactive (all frames), interactive settled (the last frames of
    # each step, only when a step has more of them than are kept), still.
    series = [("interactive_ratio", "tab:blue", "interactive frame (ratio)", "interactive_target")]
    try:
        long_drag = int(machine.get("interactive_frames", "0")) > 3
    except ValueError:
        long_drag = False
    if long_drag and rows and "interactive_settled_ratio" in rows[0]:
        series.append(("interactive_settled_ratio", "tab:cyan",
                       "interactive, last 3 frames of each step (ratio)", "interactive_target"))
    series.append(("still_ratio", "tab:orange", "still frame (ratio)", "still_target"))
    width = 0.8 / len(series)
    xs = list(range(len(rows)))
    fig, ax = plt.subplots(figsize=(8.0, 4.8))
    all_values = []
    labelled = set()
    for i, (key, color, label, target_key) in enumerate(series):
        offset = (i - (len(series) - 1) / 2.0) * width
        values = [_float(r.get(key)) for r in rows]
        all_values += values
        bars = ax.bar([x + offset for x in xs], [0 if math.isnan(v) else v for v in values], width,
                      color=color, label=label)
        for bar, v in zip(bars, values):
            text = "n/a" if math.isnan(v) else "%.2fx" % v
            ax.annotate(text, (bar.get_x() + bar.get_width() / 2, 0 if math.isnan(v) else v),
                        xytext=(0, 2), textcoords="offset points", ha="center", fontsize=8,
                        zorder=5, bbox=dict(boxstyle="square,pad=0.1", fc="white", ec="none",
                                            alpha=0.85))
        tcolor, ttext = (("darkred", "still target") if target_key == "still_target"
                         else ("navy", "interactive target"))
        for x, r in zip(xs, rows):
            t = _float(r.get(target_key))
            if not math.isnan(t):
                ax.hlines(t, x + offset - width / 2, x + offset + width / 2, colors=tcolor,
                          linestyles="--", lw=2, label=None if ttext in labelled else ttext)
                labelled.add(ttext)
    ax.axhline(1.0, color="gray", lw=0.8)
    ax.set_xticks(xs)
    ax.set_xticklabels(names, fontsize=9)
    ax.set_ylabel("median frame time / ParaView Volume (Shade on)")
    values = [v for v in all_values if not math.isnan(v) and v > 0]
    targets = [_float(r.get(k)) for r in rows for k in ("interactive_target", "still_target")]
    top = max(values + [t for t in targets if not math.isnan(t)] + [1.0])
    if values and top / min(values) > 20:
        ax.set_yscale("log")
        ax.set_ylim(min(values + [1.0]) / 1.5, top * 1.5)
        ax.yaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: "%gx" % v))
    else:
        ax.set_ylim(0, top * 1.15)
    ax.set_title("Light-kit orbit, resample %s, %s px view, %s steps x %s interactive frames, "
                 "%s cores (lower is better)"
                 % (machine.get("resample", "?"), machine.get("view", "?"), machine.get("steps", "?"),
                    machine.get("interactive_frames", "?"), machine.get("cores", "?")),
                 fontsize=9)
    ax.legend(fontsize=8, loc="upper left")
    ax.grid(True, axis="y", which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(png_path, dpi=100)
    plt.close(fig)
    return png_path


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    src = sys.argv[1]
    dst = sys.argv[2] if len(sys.argv) > 2 else os.path.splitext(src)[0] + ".png"
    print("wrote " + plot(src, dst))
