#!/usr/bin/env python3
"""Charts and tables from mmvBenchmark's output (run by scripts/benchmark).

    plot_benchmark.py BENCH_OUT_DIR DOCS_DIR

Reads BENCH_OUT_DIR/benchmark.csv, machine.txt and images/, writes into
DOCS_DIR: benchmark.csv (a copy), benchmark_pareto.png (error vs frame time),
benchmark_sample_distance.png (paper Fig. 9), benchmark_irradiance.png
(paper Fig. 6), benchmark_images.png (images and error maps) and
benchmark_tables.md (stage times and targets). Needs numpy and matplotlib
(pvpython has both; so may python3).
"""
import csv
import math
import os
import shutil
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.image as mpimg  # noqa: E402

FAMILY_STYLE = {
    "ours": dict(color="tab:blue", marker="o", label="ours (multi-material)"),
    "vtk-phong": dict(color="tab:green", marker="s", label="VTK Phong"),
    "vtk-scattering": dict(color="tab:red", marker="^", label="VTK volumetric scattering"),
}


def load(out_dir):
    with open(os.path.join(out_dir, "benchmark.csv")) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k, v in r.items():
            try:
                r[k] = float(v)
            except ValueError:
                pass
    machine = {}
    path = os.path.join(out_dir, "machine.txt")
    if os.path.exists(path):
        for line in open(path):
            key, _, value = line.strip().partition(" ")
            machine[key] = value
    return rows, machine


def label(machine):
    renderer = machine.get("renderer", "unknown renderer")
    if "llvmpipe" in renderer:
        renderer = "Mesa llvmpipe (software)"
    size = machine.get("size", "?")
    return "%s, %s cores, %sx%s px" % (renderer, machine.get("cores", "?"), size, size)


def scenes_of(rows):
    seen = []
    for r in rows:
        if r["scene"] not in seen:
            seen.append(r["scene"])
    return seen


def psnr_for_plot(v):
    return 99.0 if math.isinf(v) else v


def pareto(rows, out, machine):
    scenes = scenes_of(rows)
    fig, axes = plt.subplots(1, len(scenes), figsize=(5.2 * len(scenes), 4.6), squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        pts = [r for r in rows if r["scene"] == scene]
        for fam, style in FAMILY_STYLE.items():
            sel = [r for r in pts if r["family"] == fam]
            if sel:
                ax.scatter([r["interaction_ms"] for r in sel], [psnr_for_plot(r["psnr"]) for r in sel],
                           s=36, **style)
        for r in pts:
            name = r["method"].replace("ours ", "").replace("vtk scatter ", "")
            if r["method"] == "ours":
                name = "ours (default)"
            ax.annotate(name, (r["interaction_ms"], psnr_for_plot(r["psnr"])), fontsize=6,
                        xytext=(3, 2), textcoords="offset points")
        # Pareto front: no other point both faster and more accurate.
        front = sorted(pts, key=lambda r: r["interaction_ms"])
        best, line = -1e9, []
        for r in front:
            if r["psnr"] > best:
                best = r["psnr"]
                line.append(r)
        ax.plot([r["interaction_ms"] for r in line], [psnr_for_plot(r["psnr"]) for r in line],
                "k--", lw=0.8, label="Pareto front")
        ax.set_xscale("log")
        ax.set_xlabel("interaction frame time, median (ms, log)")
        ax.set_ylabel("PSNR vs reference (dB, higher is better)")
        ax.set_title(scene)
        ax.grid(True, which="both", alpha=0.3)
    axes[0][0].legend(fontsize=7, loc="upper left")
    fig.suptitle("Error vs frame time: " + label(machine), fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "benchmark_pareto.png"), dpi=110)
    plt.close(fig)


def sample_distance(rows, out, machine):
    scenes = scenes_of(rows)
    fig, axes = plt.subplots(2, len(scenes), figsize=(4.6 * len(scenes), 6.4), squeeze=False)
    for c, scene in enumerate(scenes):
        ours = [r for r in rows if r["scene"] == scene and r["family"] == "ours"
                and r["irradiance_scale"] == 0 and r["scattering"] == 1]
        for pre, style, name in ((1, "o-", "pre-integrated"), (0, "s--", "post-classified")):
            sel = sorted([r for r in ours if r["preintegration"] == pre], key=lambda r: r["sample_voxels"])
            if not sel:
                continue
            axes[0][c].plot([r["sample_voxels"] for r in sel], [psnr_for_plot(r["psnr"]) for r in sel],
                            style, label=name)
            axes[1][c].plot([r["sample_voxels"] for r in sel], [r["interaction_ms"] for r in sel],
                            style, label=name)
        for ax in axes[:, c]:
            ax.set_xscale("log", base=2)
            ax.set_xticks([0.5, 1, 2, 4])
            ax.set_xticklabels(["0.5", "1", "2", "4"])
            ax.grid(True, alpha=0.3)
        axes[0][c].set_title(scene)
        axes[0][c].set_ylabel("PSNR vs reference (dB)")
        axes[1][c].set_ylabel("interaction frame (ms)")
        axes[1][c].set_xlabel("sample distance (voxels)")
        axes[0][c].legend(fontsize=7)
    fig.suptitle("Error and time vs sample distance (cf. paper Fig. 9; reference at 1/8 voxel): "
                 + label(machine), fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "benchmark_sample_distance.png"), dpi=110)
    plt.close(fig)


def effective_scale(r, full):
    dims = [float(x) for x in str(r["irradiance_dims"]).split("x") if x]
    return dims[0] / full if dims and full else float("nan")


def irradiance(rows, out, machine):
    scenes = scenes_of(rows)
    fig, axes = plt.subplots(1, len(scenes), figsize=(4.8 * len(scenes), 3.9), squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        ours = [r for r in rows if r["scene"] == scene and r["family"] == "ours"
                and r["sample_voxels"] == 1 and r["preintegration"] == 1 and r["scattering"] == 1]
        full = max((float(str(r["irradiance_dims"]).split("x")[0]) for r in ours), default=0)
        sel = sorted(ours, key=lambda r: effective_scale(r, full))
        xs = [effective_scale(r, full) for r in sel]
        ax.plot(xs, [psnr_for_plot(r["psnr"]) for r in sel], "o-", color="tab:blue", label="PSNR")
        ax.set_xlabel("irradiance resolution (fraction of the data's)")
        ax.set_ylabel("PSNR vs reference (dB)", color="tab:blue")
        ax2 = ax.twinx()
        ax2.plot(xs, [r["light_irradiance_ms"] for r in sel], "s--", color="tab:orange",
                 label="irradiance update")
        ax2.plot(xs, [r["raycast_ms"] for r in sel], "^:", color="tab:gray", label="ray cast")
        ax2.set_yscale("log")
        ax2.set_ylabel("time per update / frame (ms, log)", color="tab:orange")
        ax.set_title(scene)
        ax.grid(True, alpha=0.3)
        ax2.legend(fontsize=7, loc="lower right")
    fig.suptitle("Error and time vs irradiance resolution (cf. paper Fig. 6): " + label(machine),
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "benchmark_irradiance.png"), dpi=110)
    plt.close(fig)


def images(rows, out_dir, out, machine):
    scenes = scenes_of(rows)
    columns = [("reference", "reference (CPU, 1/8 voxel)", None),
               ("ours", "ours (default)", "ours"),
               ("vtk phong", "VTK Phong", "vtk phong"),
               ("vtk scatter b=1 reach=1", "VTK scatter b=1 reach=1", "vtk scatter b=1 reach=1")]
    fig, axes = plt.subplots(len(scenes), 2 * len(columns) - 1,
                             figsize=(2.1 * (2 * len(columns) - 1), 2.3 * len(scenes)), squeeze=False)
    img_dir = os.path.join(out_dir, "images")

    def stem(scene, method):
        return os.path.join(img_dir, "".join(c if c.isalnum() or c == "." else "_"
                                             for c in scene + "_" + method))

    for i, scene in enumerate(scenes):
        col = 0
        for method, title, row_name in columns:
            path = os.path.join(img_dir, scene + "_reference.png") if row_name is None \
                else stem(scene, method) + ".png"
            r = next((x for x in rows if x["scene"] == scene and x["method"] == row_name), None)
            panels = [(path, title)]
            if row_name is not None:
                panels.append((stem(scene, method) + "_error.png",
                               "|error| (white = 64/255)" if r is None else
                               "|error|, PSNR %.1f dB" % r["psnr"]))
            for p, t in panels:
                ax = axes[i][col]
                col += 1
                ax.axis("off")
                if os.path.exists(p):
                    ax.imshow(mpimg.imread(p))
                ax.set_title(("%s: " % scene if col == 1 else "") + t, fontsize=7)
    fig.suptitle("Images at the first camera position: " + label(machine), fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "benchmark_images.png"), dpi=110)
    plt.close(fig)


def fmt(v, digits=1):
    if isinstance(v, float):
        if math.isnan(v):
            return "-"
        return ("%." + str(digits) + "f") % v
    return str(v)


def tables(rows, out, machine):
    lines = ["<!-- generated by Testing/Benchmark/plot_benchmark.py -->",
             "", "Machine: " + label(machine), ""]
    lines += ["### All methods", "",
              "| scene | method | first frame ms | pre-int. ms | irradiance ms | ray cast ms | "
              "interaction ms | light change ms | GPU MB | PSNR dB | SSIM |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        ours = r["family"] == "ours"
        lines.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            r["scene"], r["method"], fmt(r["first_frame_ms"], 0),
            fmt(r["preint_ms"], 2) if ours else "-", fmt(r["light_irradiance_ms"]) if ours else "-",
            fmt(r["raycast_ms"]) if ours else "-", fmt(r["interaction_ms"]),
            fmt(r["light_change_ms"]), fmt(r["gpu_memory_mb"], 2), fmt(r["psnr"]), fmt(r["ssim"], 3)))
    lines += ["", "### Targets", "",
              "| scene | ours / VTK Phong frame (<= 1.25) | fastest VTK scattering / ours frame "
              "(>= 5, at lower error) | VTK scattering best PSNR dB | irradiance update / ray-cast "
              "frame (<= 1) | 256^2 table ms (<= 5) | ours PSNR dB (>= 35) |",
              "|---|---|---|---|---|---|---|"]
    for scene in scenes_of(rows):
        sel = {r["method"]: r for r in rows if r["scene"] == scene}
        ours = sel.get("ours")
        phong = sel.get("vtk phong")
        scatter = [r for r in rows if r["scene"] == scene and r["family"] == "vtk-scattering"]
        if not ours:
            continue
        fastest = min(scatter, key=lambda r: r["interaction_ms"]) if scatter else None
        lines.append("| %s | %s | %s | %s | %s | %s | %s |" % (
            scene,
            fmt(ours["interaction_ms"] / phong["interaction_ms"], 2) if phong else "-",
            fmt(fastest["interaction_ms"] / ours["interaction_ms"], 2) if fastest else "-",
            fmt(max(r["psnr"] for r in scatter)) if scatter else "-",
            fmt(ours["light_irradiance_ms"] / ours["interaction_ms"], 2),
            fmt(ours["preint_table_256_ms"], 2),
            fmt(ours["psnr"])))
    with open(os.path.join(out, "benchmark_tables.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    out_dir, docs = sys.argv[1], sys.argv[2]
    os.makedirs(docs, exist_ok=True)
    rows, machine = load(out_dir)
    shutil.copy(os.path.join(out_dir, "benchmark.csv"), os.path.join(docs, "benchmark.csv"))
    pareto(rows, docs, machine)
    sample_distance(rows, docs, machine)
    irradiance(rows, docs, machine)
    images(rows, out_dir, docs, machine)
    tables(rows, docs, machine)


if __name__ == "__main__":
    main()
