"""Charts of mmvIrradianceBenchmark's irradiance_updates.csv.

    python3 plot_irradiance_updates.py IRRADIANCE_UPDATES.csv OUT.png

Three panels, the update time as a multiple of one VTK Phong frame measured
in the same run: against the number of lights, against the scattering
strength s, and against the irradiance resolution (with and without
scattering). Bars for layered draws and empty-voxel skipping are printed.
"""

import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def series(rows, sweep, x, where=lambda r: True):
    points = sorted(
        (float(r[x]), float(r["update_over_phong"]), r)
        for r in rows
        if r["sweep"] == sweep and where(r))
    return [p[0] for p in points], [p[1] for p in points], [p[2] for p in points]


def main():
    rows = load(sys.argv[1])
    out = sys.argv[2]
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2))

    xs, ys, _ = series(rows, "lights", "lights")
    axes[0].plot(xs, ys, "o-")
    axes[0].set_xlabel("lights")
    axes[0].set_title("s = 8, scale 0.5")

    xs, ys, rs = series(rows, "scattering", "scattering")
    axes[1].plot(range(len(xs)), ys, "o-")
    axes[1].set_xticks(range(len(xs)))
    axes[1].set_xticklabels(
        ["%g\n(%s)" % (x, r["diffusion_dims"]) for x, r in zip(xs, rs)], fontsize=8)
    axes[1].set_xlabel("scattering s (diffusion grid)")
    axes[1].set_title("5 lights, scale 0.5")

    for s, style in (("0", "o-"), ("8", "s--")):
        xs, ys, _ = series(rows, "resolution", "irradiance_scale",
                           lambda r, s=s: r["scattering"] == s)
        axes[2].plot(xs, ys, style, label="s = %s" % s)
    axes[2].set_xlabel("irradiance scale (x data resolution)")
    axes[2].set_title("5 lights")
    axes[2].legend()

    for ax in axes:
        ax.set_yscale("log")
        ax.set_ylabel("irradiance update / VTK Phong frame")
        ax.axhline(0.25, color="grey", ls=":", lw=1)
        ax.axhline(2.0, color="grey", ls="--", lw=1)
        ax.grid(alpha=0.3, which="both")
    axes[0].text(axes[0].get_xlim()[0], 0.27, " 0.25: still-frame budget without scattering (1.25x)",
                 fontsize=7, color="grey")
    axes[0].text(axes[0].get_xlim()[0], 2.1, " 2: still-frame budget with scattering (3x)",
                 fontsize=7, color="grey")
    fig.suptitle("Irradiance update on the CT-sized head (256 x 256 x 127), "
                 "Mesa llvmpipe, 2 cores, 400 x 400")
    fig.tight_layout()
    fig.savefig(out, dpi=110)

    for sweep in ("draws", "empty-space"):
        for r in rows:
            if r["sweep"] == sweep:
                base = [b for b in rows if b["sweep"] == "scattering"
                        and b["scattering"] == r["scattering"]]
                if base:
                    print("%s off, s = %s: %.3f s vs %.3f s on (%.2fx)" % (
                        sweep, r["scattering"], float(r["update_s"]),
                        float(base[0]["update_s"]),
                        float(r["update_s"]) / float(base[0]["update_s"])))


if __name__ == "__main__":
    main()
