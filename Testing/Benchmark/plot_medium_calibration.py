"""Charts of mmvMediumCalibration (docs/performance.md, "Physical media";
the mapping in docs/how-it-works.md, "Physical media").

  pvpython plot_medium_calibration.py medium_calibration.csv errors.png [IMAGE_DIR images.png]

errors.png: per medium (albedo a, g, optical depth T of the ball's radius),
the RMSE over the medium's pixels (0-255) of ours at the defaults, ours with
the mapping, ours' best fit and VTK's best-fit volumetric scattering against
the path tracer, with the truth's noise floor. images.png: truth, ours
default, ours mapped, ours best fit and VTK for eight media (the PNGs the program wrote).
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

FAMILIES = [
    ("ours-default", "ours, defaults", "#bbbbbb"),
    ("ours-mapped", "ours, PhysicalMediumToMaterial", "#1f77b4"),
    ("ours-fit", "ours, best fit", "#9ecae1"),
    ("vtk-scattering", "VTK scattering, best fit", "#ff7f0e"),
]


def read(path):
    media = {}
    for row in csv.DictReader(open(path)):
        key = (float(row["depth"]), float(row["anisotropy"]), float(row["albedo"]))
        media.setdefault(key, {})[row["family"]] = row
    return media


def key_name(key):
    depth, g, a = key
    return "a{:g}_g{:g}_tau{:g}".format(a, g, depth)


def errors_chart(media, out):
    depths = sorted({k[0] for k in media})
    fig, axes = plt.subplots(len(depths), 1, figsize=(13, 3.2 * len(depths)), squeeze=False)
    for ax, depth in zip(axes[:, 0], depths):
        keys = sorted(k for k in media if k[0] == depth)
        width = 0.8 / len(FAMILIES)
        for f, (family, label, color) in enumerate(FAMILIES):
            xs, ys = [], []
            for i, k in enumerate(keys):
                if family in media[k]:
                    xs.append(i + (f - 1.5) * width)
                    ys.append(float(media[k][family]["volume_rmse"]))
            ax.bar(xs, ys, width, label=label, color=color)
        floors = [float(next(iter(media[k].values()))["truth_rmse_floor"]) for k in keys]
        ax.plot(range(len(keys)), floors, "k_", markersize=14, label="truth noise (RMS SE)")
        ax.set_xticks(range(len(keys)))
        ax.set_xticklabels(["a={:g}\ng={:g}".format(k[2], k[1]) for k in keys], fontsize=8)
        ax.set_yscale("log")
        ax.set_ylabel("RMSE on the medium (0-255)")
        ax.set_title("optical depth of the radius T = {:g}".format(depth))
        ax.grid(axis="y", alpha=0.3)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, fontsize=8, ncol=5, loc="upper center")
    fig.tight_layout(rect=(0, 0, 1, 0.97))
    fig.savefig(out, dpi=90)


def images_chart(media, image_dir, out):
    chosen = [k for k in sorted(media) if k[2] in (0.6, 0.99) and k[1] in (0.0, 0.8) and k[0] in (4.0, 16.0)]
    columns = [("truth", "truth")] + [(f, label) for f, label, _ in FAMILIES]
    fig, axes = plt.subplots(len(chosen), len(columns), figsize=(2.2 * len(columns), 2.2 * len(chosen)),
                             squeeze=False)
    for r, k in enumerate(chosen):
        for c, (family, label) in enumerate(columns):
            ax = axes[r, c]
            ax.axis("off")
            path = os.path.join(image_dir, "ball_{}_{}.png".format(key_name(k), family))
            if os.path.exists(path):
                ax.imshow(mpimg.imread(path), interpolation="nearest")
            if r == 0:
                ax.set_title(label, fontsize=8)
            if c == 0:
                ax.text(-0.05, 0.5, "a={:g} g={:g}\nT={:g}".format(k[2], k[1], k[0]), fontsize=8,
                        transform=ax.transAxes, ha="right", va="center")
    fig.tight_layout()
    fig.savefig(out, dpi=90)


def main():
    if len(sys.argv) not in (3, 5):
        sys.exit(__doc__)
    media = read(sys.argv[1])
    errors_chart(media, sys.argv[2])
    if len(sys.argv) == 5:
        images_chart(media, sys.argv[3], sys.argv[4])


if __name__ == "__main__":
    main()
