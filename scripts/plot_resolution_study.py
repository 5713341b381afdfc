#!/usr/bin/python3
"""Figure of the resolution study: mean +- one standard deviation over the seeds
of sigma_u, E and nu, and the wall time per run, against the disk count (at
0.02 m/s) and against the platen velocity (at about 5,000 disks).

    /usr/bin/python3 scripts/plot_resolution_study.py [docs/explanation/resolution_study.csv] [docs/explanation/resolution_study.png]
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

source = sys.argv[1] if len(sys.argv) > 1 else "docs/explanation/resolution_study.csv"
target = sys.argv[2] if len(sys.argv) > 2 else "docs/explanation/resolution_study.png"
rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(source))]
by_size = sorted((r for r in rows if r["platen_velocity_m_s"] == 0.02), key=lambda r: r["disks"])
mid = sorted({r["disks_planned"] for r in rows if r["platen_velocity_m_s"] != 0.02})
by_speed = sorted((r for r in rows if r["disks_planned"] in mid), key=lambda r: r["platen_velocity_m_s"])

outputs = [("sigma_u_MPa", "sigma_u (MPa)"), ("E_GPa", "E (GPa)"), ("nu", "nu")]
fig, axes = plt.subplots(2, 4, figsize=(16, 7))
for row, (series, x_key, x_label) in enumerate([(by_size, "disks", "disks (platens at 0.02 m/s)"),
                                                (by_speed, "platen_velocity_m_s", "platen velocity (m/s), ~5,000 disks")]):
    x = [r[x_key] for r in series]
    for col, (key, label) in enumerate(outputs):
        mean = [r[key + "_mean"] for r in series]
        sd = [abs(r[key + "_mean"]) * r[key + "_cv_pct"] / 100 for r in series]
        ax = axes[row][col]
        ax.errorbar(x, mean, yerr=sd, marker="o", capsize=4)
        ax.set_xscale("log")
        ax.set_xlabel(x_label)
        ax.set_ylabel(label + ", mean +- sd of 5 seeds")
        ax.grid(True, alpha=0.3)
    ax = axes[row][3]
    ax.plot(x, [r["wall_s_per_run"] for r in series], marker="s", color="tab:red")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(x_label)
    ax.set_ylabel("wall time per run (s)")
    ax.grid(True, alpha=0.3)
fig.suptitle("demcal: parallel-bonded UCS, resolution and loading rate (measured, 2-core machine)")
fig.tight_layout()
fig.savefig(target, dpi=90)
print("wrote", target)
