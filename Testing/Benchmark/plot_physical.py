#!/usr/bin/env python3
"""Error against the physical reference versus frame time, from
mmvPhysicalCalibration's CSV.

    plot_physical.py physical_calibration.csv OUT.png

One column per scene. Top: RMSE of the whole image (0-255) against the
median frame time, every swept setting of every method; ours at its
defaults, each family's best fit and the truth's own noise floor (RMS of
its per-pixel standard error) are marked. Bottom: the same over the
volume's pixels after the best single brightness factor per image (the
error a wrong exposure does not explain). Needs matplotlib (pvpython).
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {
    "ours": dict(color="tab:blue", marker="o", label="ours, s and c_t scaled"),
    "ours-default": dict(color="tab:blue", marker="*", label="ours at defaults"),
    "vtk-phong": dict(color="tab:green", marker="s", label="VTK Phong"),
    "vtk-scattering": dict(color="tab:red", marker="^", label="VTK scattering (blending, reach, g)"),
}


def main(path, out):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    scenes = []
    for r in rows:
        if r["scene"] not in scenes:
            scenes.append(r["scene"])
    fig, axes = plt.subplots(2, len(scenes), figsize=(4.2 * len(scenes), 7.5), squeeze=False)
    for col, scene in enumerate(scenes):
        sub = [r for r in rows if r["scene"] == scene]
        for row, key, title in ((0, "rmse", "whole image"), (1, "volume_gain_rmse",
                                                             "volume pixels, best brightness")):
            ax = axes[row][col]
            for family, style in STYLE.items():
                pts = [r for r in sub if r["family"] == family]
                if not pts:
                    continue
                ax.scatter([float(r["frame_ms"]) for r in pts], [float(r[key]) for r in pts],
                           s=90 if family == "ours-default" else 30, alpha=0.8,
                           **{k: v for k, v in style.items()})
            for family in ("ours", "vtk-scattering"):
                pts = [r for r in sub if r["family"].startswith(family)]
                if pts:
                    best = min(pts, key=lambda r: float(r[key]))
                    ax.annotate("best: " + best["setting"], (float(best["frame_ms"]), float(best[key])),
                                fontsize=7, xytext=(4, 4), textcoords="offset points")
            if row == 0:
                ax.axhline(float(sub[0]["truth_rmse_floor"]), color="k", ls="--", lw=1,
                           label="truth's noise (RMS standard error)")
            ax.set_title("%s: %s" % (scene, title), fontsize=10)
            ax.set_xlabel("frame time (ms, llvmpipe)")
            ax.set_ylabel("RMSE vs Monte Carlo truth (0-255)")
            ax.set_ylim(bottom=0)
            ax.grid(alpha=0.3)
    axes[0][0].legend(fontsize=7, loc="upper left")
    fig.suptitle("Error against the physical reference (vtkMultiMaterialPathTracer, %s spp, %s px)"
                 % (rows[0]["truth_spp"], rows[0]["size"]))
    fig.tight_layout()
    fig.savefig(out, dpi=90)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
