"""Chart of mmvIrradianceBenchmark's ct_resolution.csv: accuracy against
speed of the irradiance resolution on the CT-sized head.

    python3 plot_ct_resolution.py CT_RESOLUTION.csv OUT.png

One curve per scattering strength: the still frame after a light move (as a
multiple of a VTK Phong frame of the same run) against the PSNR of the image
against the full-resolution irradiance; points labelled by the scale.
"""

import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    with open(sys.argv[1]) as f:
        rows = list(csv.DictReader(f))
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    for s, style in (("0", "o-"), ("8", "s--")):
        points = [r for r in rows if r["scattering"] == s]
        xs = [float(r["still_over_phong"]) for r in points]
        # The full-resolution image is its own reference: plot it at 60 dB.
        ys = [min(60.0, float(r["psnr_vs_full_db"])) if not math.isinf(
            float(r["psnr_vs_full_db"])) else 60.0 for r in points]
        ax.plot(xs, ys, style, label="scattering s = %s" % s)
        for x, y, r in zip(xs, ys, points):
            ax.annotate("%g" % float(r["irradiance_scale"]), (x, y), fontsize=8,
                        textcoords="offset points", xytext=(4, 4))
    ax.axhline(40.0, color="grey", ls=":", lw=1)
    ax.axvline(1.25, color="tab:blue", ls=":", lw=1)
    ax.axvline(3.0, color="tab:orange", ls=":", lw=1)
    ax.text(1.27, 41, "1.25x: still target, s = 0", fontsize=7, color="tab:blue")
    ax.text(3.05, 43, "3x: still target, s = 8", fontsize=7, color="tab:orange")
    ax.set_xscale("log")
    ax.set_xlabel("still frame after a light move / VTK Phong frame (log)")
    ax.set_ylabel("PSNR vs full-resolution irradiance (dB; 60 = itself)")
    ax.set_title("Irradiance scale on the CT-sized head, 5 lights, 400 x 400, llvmpipe",
                 fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend()
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)


if __name__ == "__main__":
    main()
