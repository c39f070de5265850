"""Charts of docs/scaling.md (issue 11) from the benchmarks' CSV files:

    pvpython plot_scaling.py SCALING_MPI.csv SCALING_SIZE.csv OUT_MPI.png OUT_SIZE.png

(pvpython has matplotlib; so does python3 where it is installed.)
SCALING_MPI.csv: Testing/Benchmark/pv_mpi_scaling.py (rank 0's figures, one
row per rank count and round). SCALING_SIZE.csv: mmvVolumeSizeBenchmark (one
row per volume size). Every round is drawn as a point and the median as a
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
    series = [
        ("light_move_frame_s", "still frame after a light move", "C0"),
        ("irradiance_update_s", "irradiance update (mapper timer)", "C1"),
        ("still_frame_s", "frame, nothing changed", "C2"),
        ("exchange_s", "exchange (pre-filter + all-reduce)", "C3"),
    ]
    fig, (times, sent) = plt.subplots(1, 2, figsize=(11, 4.2))
    for key, label, colour in series:
        medians = []
        for n in ranks:
            values = [number(r[key]) for r in rows if int(r["ranks"]) == n]
            values = [v for v in values if v is not None]
            times.scatter([n] * len(values), values, color=colour, alpha=0.5, s=18)
            medians.append(statistics.median(values) if values else None)
        shown = [(n, m) for n, m in zip(ranks, medians) if m is not None]
        times.plot([n for n, _ in shown], [m for _, m in shown], color=colour, marker="o",
                   label=label)
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


def main(argv):
    if len(argv) != 5:
        sys.exit(__doc__)
    plot_mpi(read_rows(argv[1]), argv[3])
    plot_size(read_rows(argv[2]), argv[4])
    print("wrote %s, %s" % (argv[3], argv[4]))


if __name__ == "__main__":
    main(sys.argv)
