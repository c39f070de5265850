#!/usr/bin/env python3
"""Error against the physical reference versus frame time, from
mmvPhysicalCalibration's CSV.

    plot_physical.py physical_calibration.csv OUT.png [IMAGE_DIR OUT_IMAGES.png]

Also prints a markdown table of the best fits. With IMAGE_DIR (the
calibration's output folder) also writes the truth and best-fit images.

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
    # mmvPhysicalCalibration --anisotropy G: ours above is v2 (HG(G)), this v1 (g = 0).
    # mmvPhysicalCalibration --fit-exposure: ka and kd fitted at each (s, c_t).
    "ours-exposure": dict(color="tab:purple", marker="D", label="ours, s and c_t scaled, ka/kd fitted"),
    "ours-v1": dict(color="tab:orange", marker="x", label="ours v1 (isotropic), s and c_t scaled"),
    # Rows of the directional-fade shading model (ours-fade), in CSVs that
    # compare it with the hybrid model.
    "ours-fade": dict(color="tab:gray", marker="+", label="ours v2 before the hybrid model (fade)"),
    "ours-fade-default": dict(color="tab:gray", marker="P", label="ours v2 before the hybrid, defaults"),
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
                           s=90 if family.endswith("default") else 30, alpha=0.8,
                           **{k: v for k, v in style.items()})
            for family in ("ours", "ours-exposure", "ours-v1", "ours-fade", "vtk-scattering"):
                pts = [r for r in sub if r["family"] in (family, family + "-default")]
                if pts:
                    best = min(pts, key=lambda r: float(r[key]))
                    ax.annotate(best["setting"].replace("_scale", "").replace("anisotropy", "g"),
                                (float(best["frame_ms"]), float(best[key])), fontsize=6,
                                xytext=(3, -9), textcoords="offset points")
            if row == 0:
                ax.axhline(float(sub[0]["truth_rmse_floor"]), color="k", ls="--", lw=1,
                           label="truth's noise (RMS standard error)")
            ax.set_title("%s: %s" % (scene, title), fontsize=10)
            ax.set_xlabel("frame time (ms, llvmpipe)")
            ax.set_ylabel("RMSE vs Monte Carlo truth (0-255)")
            ax.set_ylim(bottom=0)
            ax.grid(alpha=0.3)
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=5, fontsize=8)
    fig.suptitle("Error against the physical reference (vtkMultiMaterialPathTracer, %s spp, %s px)"
                 % (rows[0]["truth_spp"], rows[0]["size"]))
    fig.tight_layout(rect=(0, 0.05, 1, 0.95))
    fig.savefig(out, dpi=90)


def summary(path):
    """Markdown table: per scene, ours at defaults and best fit, VTK Phong, VTK
    scattering at its best fit overall and at no more than ours' best-fit
    frame time; RMSE over the whole image (volume pixels after the best
    brightness factor in brackets)."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    print("| scene | truth noise | ours default | ours best fit | VTK Phong | VTK scattering best fit"
          " | VTK scattering best at <= ours' best-fit frame time |")
    print("|---|---|---|---|---|---|---|")
    scenes = []
    for r in rows:
        if r["scene"] not in scenes:
            scenes.append(r["scene"])

    def cell(r):
        label = (" " + r["setting"]) if r["setting"] else ""
        return "%.1f (%.1f), %.0f ms%s" % (float(r["rmse"]), float(r["volume_gain_rmse"]),
                                           float(r["frame_ms"]), label)
    for scene in scenes:
        sub = [r for r in rows if r["scene"] == scene]
        ours = [r for r in sub if r["family"].startswith("ours") and not r["family"].startswith("ours-fade")]
        default = [r for r in sub if r["family"] == "ours-default"][0]
        best_ours = min(ours, key=lambda r: float(r["rmse"]))
        phong = [r for r in sub if r["family"] == "vtk-phong"]
        vtk = [r for r in sub if r["family"] == "vtk-scattering"]
        best_vtk = min(vtk, key=lambda r: float(r["rmse"])) if vtk else None
        budget = [r for r in vtk if float(r["frame_ms"]) <= float(best_ours["frame_ms"])]
        best_budget = min(budget, key=lambda r: float(r["rmse"])) if budget else None
        print("| %s | %.2f | %s | %s | %s | %s | %s |" % (
            scene, float(sub[0]["truth_rmse_floor"]), cell(default), cell(best_ours),
            cell(phong[0]) if phong else "not run", cell(best_vtk) if best_vtk else "not run",
            cell(best_budget) if best_budget else ("none that fast" if vtk else "not run")))


def images(image_dir, scenes, out):
    """Rows: scenes; columns: the Monte Carlo truth and each family's best fit."""
    import matplotlib.image as mpimg
    columns = [("truth", "Monte Carlo truth"), ("best_ours", "ours, best fit"),
               ("best_vtk-phong", "VTK Phong"), ("best_vtk-scattering", "VTK scattering, best fit")]
    fig, axes = plt.subplots(len(scenes), len(columns), figsize=(2.4 * len(columns), 2.4 * len(scenes)),
                             squeeze=False)
    for i, scene in enumerate(scenes):
        for j, (suffix, title) in enumerate(columns):
            ax = axes[i][j]
            ax.imshow(mpimg.imread("%s/%s_%s.png" % (image_dir, scene, suffix)))
            ax.set_xticks([])
            ax.set_yticks([])
            if i == 0:
                ax.set_title(title, fontsize=9)
            if j == 0:
                ax.set_ylabel(scene, fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=100)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
    summary(sys.argv[1])
    if len(sys.argv) > 3:  # IMAGE_DIR OUT_IMAGES.png
        with open(sys.argv[1]) as f:
            names = []
            for r in csv.DictReader(f):
                if r["scene"] not in names:
                    names.append(r["scene"])
        images(sys.argv[3], names, sys.argv[4])
