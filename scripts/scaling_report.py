#!/usr/bin/python3
"""Tables and the plot of scripts/scaling.sh from tetray-composite-bench's JSON files.

  scaling_report.py calibration DIR   real_P.json against sim_P.json: CSV on stdout
  scaling_report.py sweep DIR         every PLATFORM_P_MODE.json: CSV on stdout
  scaling_report.py rounds DIR        every bluegene_p_zorder_P.json, round by round: CSV
  scaling_report.py plot DIR          DIR/sweep.csv as DIR/sweep.png (log-log, time per ranks)
"""
import csv
import glob
import json
import os
import re
import sys


def runs(path):
    return json.load(open(path))["runs"]


def key(run):
    return (run["size"], run["mode"], run["algorithm"])


def durations(ends):
    """Time of each round from the ends of the rounds (a round a rank left early is -1)."""
    out, last = [], 0.0
    for end in ends:
        if end is None or end < 0:
            break
        out.append(end - last)
        last = end
    return out


def calibration(folder):
    writer = csv.writer(sys.stdout)
    writer.writerow(["ranks", "size", "mode", "algorithm", "real_ms", "simulated_ms", "error_pct",
                     "worst_round_error_ms", "round_error_of_total_pct", "same_image"])
    for real_path in sorted(glob.glob(os.path.join(folder, "real_*.json"))):
        ranks = re.search(r"real_(\d+)\.json", real_path).group(1)
        simulated = {key(r): r for r in runs(os.path.join(folder, f"sim_{ranks}.json"))}
        for real in runs(real_path):
            sim = simulated[key(real)]
            error = 100.0 * (sim["median_ms"] - real["median_ms"]) / real["median_ms"]
            pairs = zip(durations(real["round_end_ms"]), durations(sim["round_end_ms"]))
            worst = max((abs(a - b) for a, b in pairs), default=0.0)
            writer.writerow([ranks, real["size"], real["mode"], real["algorithm"],
                             f"{real['median_ms']:.2f}", f"{sim['median_ms']:.2f}",
                             f"{error:+.1f}", f"{worst:.2f}",
                             f"{100.0 * worst / real['median_ms']:.1f}",
                             "yes" if real["root_image_hash"] == sim["root_image_hash"] else "NO"])


def sweep(folder):
    writer = csv.writer(sys.stdout)
    writer.writerow(["platform", "ranks", "size", "mode", "algorithm", "rows", "total_ms",
                     "rounds_ms", "assembly_ms", "sent_max_MB", "message_bytes_per_pixel"])
    rows = []
    for path in glob.glob(os.path.join(folder, "*_*_*.json")):
        match = re.search(r"(cluster|bluegene_p)_(\d+)_(dense|sparse)\.json$", path)
        if not match:
            continue
        for run in runs(path):
            rows.append([match.group(1), run["ranks"], run["size"], run["mode"], run["algorithm"],
                         run.get("rows", "natural"), f"{run['median_ms']:.3f}", f"{run['composite_ms']:.3f}",
                         f"{run['assembly_ms']:.3f}", f"{run['sent_max_bytes'] / 1e6:.2f}",
                         f"{run['message_bytes_per_pixel']:.2f}"])
    rows.sort(key=lambda r: (r[0], r[3], r[2], r[4], r[1]))
    writer.writerows(rows)


def rounds(folder):
    writer = csv.writer(sys.stdout)
    writer.writerow(["ranks", "size", "mode", "rows", "rounds_ms", "assembly_ms", "total_ms",
                     "each_round_ms"])
    rows = []
    for path in glob.glob(os.path.join(folder, "bluegene_p_zorder_*.json")):
        for run in runs(path):
            radix_rounds = durations(run["round_end_ms"])[:len(run["round_end_ms"]) // 2]
            rows.append([run["ranks"], run["size"], run["mode"], run.get("rows", "natural"),
                         f"{run['composite_ms']:.1f}", f"{run['assembly_ms']:.1f}",
                         f"{run['median_ms']:.1f}", " ".join(f"{t:.1f}" for t in radix_rounds)])
    rows.sort(key=lambda r: (r[2], r[3], r[0]))
    writer.writerows(rows)


def plot(folder):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = list(csv.DictReader(open(os.path.join(folder, "sweep.csv"))))
    panels = sorted({(r["platform"], r["mode"]) for r in rows})
    figure, axes = plt.subplots(1, len(panels), figsize=(5.5 * len(panels), 4.5), squeeze=False)
    for axis, (platform, mode) in zip(axes[0], panels):
        series = {}
        for r in rows:
            if (r["platform"], r["mode"]) == (platform, mode):
                name = f"{r['algorithm']} {r['size']}²"
                series.setdefault(name, []).append((int(r["ranks"]), float(r["total_ms"])))
        for name, points in sorted(series.items()):
            points.sort()
            axis.plot([p for p, _ in points], [t for _, t in points], marker="o", label=name)
        axis.set_xscale("log", base=2)
        axis.set_yscale("log")
        axis.set_xlabel("ranks")
        axis.set_ylabel("composite + assembly on the root, ms")
        axis.set_title(f"{platform}, {mode}")
        axis.grid(True, which="both", alpha=0.3)
        axis.legend(fontsize=7)
    figure.tight_layout()
    figure.savefig(os.path.join(folder, "sweep.png"), dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] not in ("calibration", "sweep", "rounds", "plot"):
        sys.exit(__doc__)
    {"calibration": calibration, "sweep": sweep, "rounds": rounds,
     "plot": plot}[sys.argv[1]](sys.argv[2])
