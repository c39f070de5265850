"""Chart of pv_lighting_changes.py: each change's still frame as a ratio to
ParaView's Volume (colour edits and the second loop: to the method's own
still frame), one panel per volume, the targets marked.

    python3 Testing/Benchmark/plot_lighting_changes.py changes.csv changes.png
"""

import csv
import sys

# Sequences shown as a ratio to the method's own still frame.
OWN_STILL = ("colour", "series-2")


def plot(csv_path, png_path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    with open(csv_path) as f:
        rows = list(csv.DictReader(f))
    volumes = list(dict.fromkeys(r["volume"] for r in rows))
    methods = [m for m in dict.fromkeys(r["method"] for r in rows) if m != "pv-volume"]
    sequences = [s for s in dict.fromkeys(r["sequence"] for r in rows) if s != "still"]
    fig, axes = plt.subplots(1, len(volumes), figsize=(6 * len(volumes), 4.2), squeeze=False)
    width = 0.8 / max(len(methods), 1)
    for ax, volume in zip(axes[0], volumes):
        for m, method in enumerate(methods):
            xs, ys, targets = [], [], []
            for s, sequence in enumerate(sequences):
                row = next((r for r in rows if r["volume"] == volume and r["method"] == method
                            and r["sequence"] == sequence), None)
                if row is None:
                    continue
                own = row["ratio_to_own_still"]
                if sequence in OWN_STILL and not own:
                    continue  # no still frame of its own to compare with
                value = float(own) if own else float(row["ratio_to_pv_volume"])
                xs.append(s + (m - (len(methods) - 1) / 2.0) * width)
                ys.append(value)
                targets.append(float(row["target"]) if row["target"] else None)
            ax.bar(xs, ys, width, label=method)
            for x, t in zip(xs, targets):
                if t is not None:
                    ax.plot([x - width / 2, x + width / 2], [t, t], color="black", lw=2)
        ax.axhline(1.0, color="grey", lw=0.8, ls="--")
        ax.set_xticks(range(len(sequences)))
        ax.set_xticklabels(sequences)
        ax.set_title("%s (black bars: targets)" % volume)
        ax.set_ylabel("still frame / ParaView Volume's\n(colour, series-2: / own still frame)")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png_path, dpi=100)
    return png_path


if __name__ == "__main__":
    print(plot(sys.argv[1], sys.argv[2]))
