"""Charts of docs/scaling.md from the benchmarks' CSV files:

    pvpython plot_scaling.py SCALING_MPI.csv SCALING_SIZE.csv OUT_MPI.png OUT_SIZE.png \
        [RANK_REGIONS.csv OUT_REGIONS.png]

(pvpython has matplotlib; so does python3 where it is installed.)
SCALING_MPI.csv: Testing/Benchmark/pv_mpi_scaling.py (rank 0's figures, one
row per rank count, round and mode: each rank its piece's region, or the
whole grid). SCALING_SIZE.csv: mmvVolumeSizeBenchmark (one row per volume
size). RANK_REGIONS.csv: mmvRankRegionBenchmark (each rank's share, ranks run
one after the other). Every round is drawn as a point and the median as a
line, so run-to-run spread on a shared machine stays visible.
"""
import csv
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def number(text):
    return float(text) if text not in ("", None) else None


def plot_mpi(rows, out):
    ranks = sorted({int(r["ranks"]) for r in rows})
    modes = {"piece": "each rank its piece", "whole": "each rank the whole grid"}
    series = []
    for mode, style in (("piece", "-"), ("whole", "--")):
        series += [
            ("light_move_frame_s", mode, "still frame after a light move, " + modes[mode], "C0", style),
            ("irradiance_update_s", mode, "irradiance update, " + modes[mode], "C1", style),
        ]
    series += [
        ("still_frame_s", "piece", "frame, nothing changed", "C2", "-"),
        ("exchange_s", "piece", "exchange (pre-filter + all-reduce)", "C3", "-"),
    ]
    fig, (times, sent) = plt.subplots(1, 2, figsize=(11, 4.2))
    for key, mode, label, colour, style in series:
        medians = []
        for n in ranks:
            values = [number(r[key]) for r in rows
                      if int(r["ranks"]) == n and r.get("mode", "whole") == mode]
            values = [v for v in values if v is not None]
            times.scatter([n] * len(values), values, color=colour, alpha=0.5, s=18)
            medians.append(statistics.median(values) if values else None)
        shown = [(n, m) for n, m in zip(ranks, medians) if m is not None]
        if shown:
            times.plot([n for n, _ in shown], [m for _, m in shown], color=colour, marker="o",
                       linestyle=style, label=label)
    times.set_xticks(ranks)
    times.set_xlabel("MPI ranks (2 and 4 oversubscribed on 2 cores)")
    times.set_ylabel("seconds (rank 0)")
    times.set_title("Wavelet %s^3, irradiance grid %s" % (rows[0]["size"], rows[0]["irradiance_grid"]))
    times.set_ylim(bottom=0)
    times.grid(alpha=0.3)
    times.legend(fontsize=8)

    bytes_sent = [statistics.median(number(r["bytes_sent_per_rank"]) for r in rows
                                    if int(r["ranks"]) == n) / 2**20 for n in ranks]
    sent.bar([str(n) for n in ranks], bytes_sent, color="C4")
    for i, value in enumerate(bytes_sent):
        sent.text(i, value, "%.2f MiB" % value, ha="center", va="bottom", fontsize=9)
    sent.set_xlabel("MPI ranks")
    sent.set_ylabel("MiB sent per rank per data change")
    sent.set_title("Exchange size (nothing per light or camera move)")
    sent.grid(axis="y", alpha=0.3)
    fig.suptitle("Global shadows under MPI, pvbatch, Mesa llvmpipe, 400 x 400")
    fig.tight_layout()
    fig.savefig(out, dpi=100)


def plot_size(rows, out):
    rows = sorted(rows, key=lambda r: int(r["size"]))
    sizes = [int(r["size"]) for r in rows]
    labels = ["%d^3\n%s MiB\ngrid %s" % (int(r["size"]), r["data_MB"], r["irradiance_grid"].split("x")[0])
              for r in rows]
    fig, (times, memory) = plt.subplots(1, 2, figsize=(11, 4.4))
    for key, label, colour in (("first_frame_s", "first frame", "C0"),
                               ("light_move_frame_s", "still frame after a light move", "C1"),
                               ("irradiance_update_s", "irradiance update", "C2"),
                               ("still_frame_s", "frame, nothing changed", "C3")):
        times.plot(range(len(sizes)), [number(r[key]) for r in rows], marker="o", color=colour,
                   label=label)
    times.set_xticks(range(len(sizes)), labels, fontsize=8)
    times.set_ylabel("seconds")
    times.set_title("Time at the default budget (64 MB)")
    times.set_ylim(bottom=0)
    times.grid(alpha=0.3)
    times.legend(fontsize=8)

    width = 0.38
    xs = range(len(sizes))
    memory.bar([x - width / 2 for x in xs], [number(r["peak_rss_MB"]) / 1024 for r in rows], width,
               label="peak RSS above start", color="C5")
    memory.bar([x + width / 2 for x in xs], [number(r["mmv_textures_MB"]) / 1024 for r in rows],
               width, label="our textures", color="C6")
    memory.set_xticks(list(xs), labels, fontsize=8)
    memory.set_ylabel("GiB")
    memory.set_title("Memory")
    memory.grid(axis="y", alpha=0.3)
    memory.legend(fontsize=8)
    fig.suptitle("Generated n^3 float32 volumes, one directional light, 512 x 512, Mesa llvmpipe")
    fig.tight_layout()
    fig.savefig(out, dpi=100)


def plot_regions(rows, out):
    """Each rank's share (mmvRankRegionBenchmark): the slowest rank's update
    and the largest rank's voxels against the ranks, its piece's region
    against the whole grid, per split axis and with/without scattering."""
    fig, (times, share) = plt.subplots(1, 2, figsize=(11, 4.4))
    cases = sorted({(r["axis"], r["scattering"]) for r in rows if int(r["ranks"]) > 1})
    colours = ["C0", "C1", "C2", "C3", "C4", "C5"]
    for (axis, scattering), colour in zip(cases, colours):
        for mode, style in (("piece", "-"), ("whole", "--")):
            points = sorted(
                (int(r["ranks"]), number(r["slowest_rank_update_s"]),
                 number(r["largest_rank_voxels"]) / number(r["whole_grid_voxels"]))
                for r in rows if r["mode"] == mode and r["scattering"] == scattering and
                (r["axis"] == axis or int(r["ranks"]) == 1))
            label = "split along %s, scattering %s" % (axis, scattering)
            times.plot([p[0] for p in points], [p[1] for p in points], color=colour, marker="o",
                       linestyle=style, label=label + (", whole grid" if mode == "whole" else ""))
            if mode == "piece":
                share.plot([p[0] for p in points], [100.0 * p[2] for p in points], color=colour,
                           marker="o", label=label)
    ranks = sorted({int(r["ranks"]) for r in rows})
    share.plot(ranks, [100.0 / n for n in ranks], color="grey", linestyle=":", label="1 / ranks")
    for axes in (times, share):
        axes.set_xticks(ranks)
        axes.set_xlabel("ranks (run one after the other in one process)")
        axes.set_ylim(bottom=0)
        axes.grid(alpha=0.3)
    times.set_ylabel("seconds")
    times.set_title("Slowest rank's irradiance update (dashed: whole grid)")
    times.legend(fontsize=7, loc="center right", bbox_to_anchor=(1.0, 0.4))
    share.set_ylabel("% of the whole grid's voxels x lights")
    share.set_title("Largest rank's estimated voxels (its region + halo)")
    share.legend(fontsize=7)
    fig.suptitle("CT-sized head, irradiance grid %s, light kit (5 lights), Mesa llvmpipe"
                 % rows[0]["irradiance_grid"])
    fig.tight_layout()
    fig.savefig(out, dpi=100)


def main(argv):
    if len(argv) not in (5, 7):
        sys.exit(__doc__)
    plot_mpi(read_rows(argv[1]), argv[3])
    plot_size(read_rows(argv[2]), argv[4])
    written = [argv[3], argv[4]]
    if len(argv) == 7:
        plot_regions(read_rows(argv[5]), argv[6])
        written.append(argv[6])
    print("wrote " + ", ".join(written))


if __name__ == "__main__":
    main(sys.argv)
