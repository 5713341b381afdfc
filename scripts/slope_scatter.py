#!/usr/bin/python3
"""How much the UCS's tangents and secants scatter over seeds, recomputed from stored curves
(docs/explanation/calibration_method.md, "Tangent or secant").

Reads the curves a batch stored (runs.h5: points/NAME/curve_axial_strain, curve_stress_MPa, curve_lateral_strain)
and prints, per file, the mean and seed CV of E and nu as least-squares slopes over windows around the half-peak
point (a twentieth of the points to the peak on each side, the DEM's window until 2026-12-04; a tenth, its window
since; a fifth; and the 30-70 % stretch of the peak stress) and as secants at half the peak. The curves keep the edge gauges' lateral
strain, not the fit over the middle three fifths of the height that the DEM's own tangent nu uses, so nu's tangent rows here are those
of the edge gauges.

    /usr/bin/python3 scripts/slope_scatter.py build/calibration_benchmark/user_sandstone/verify/v01/runs/runs.h5
"""
import argparse
import statistics

import h5py
import numpy as np


def slope(x, y):
    """Least-squares slope of y on x."""
    x, y = np.asarray(x), np.asarray(y)
    dx = x - x.mean()
    return float((dx * (y - y.mean())).sum() / (dx * dx).sum())


def windows(stress):
    """{label: (first, last) point index} of each window around the half-peak point."""
    peak = int(np.argmax(stress))
    half = int(np.argmax(stress >= 0.5 * stress[peak]))
    out = {}
    for label, fraction in (("1/20", 20), ("1/10", 10), ("1/5", 5)):
        w = max(2, peak // fraction)
        out[label] = (max(half - w, 0), min(peak, half + w))
    out["30-70 %"] = (int(np.argmax(stress >= 0.3 * stress[peak])), int(np.argmax(stress >= 0.7 * stress[peak])))
    return out, half


def cv_pct(values):
    return 100 * statistics.stdev(values) / abs(statistics.mean(values))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("runs_h5", nargs="+", help="a batch's runs.h5")
    args = parser.parse_args()
    for path in args.runs_h5:
        with h5py.File(path, "r") as f:
            rows = {}
            for name, g in f["points"].items():
                strain, stress = g["curve_axial_strain"][:], g["curve_stress_MPa"][:]
                lateral = g["curve_lateral_strain"][:]
                spans, half = windows(stress)
                for label, (a, b) in spans.items():
                    s = slice(a, b + 1)
                    rows.setdefault("tangent, " + label, []).append(
                        (slope(strain[s], stress[s]) / 1e3, slope(strain[s], lateral[s])))
                rows.setdefault("secant at half the peak", []).append(
                    (stress[half] / strain[half] / 1e3, lateral[half] / strain[half]))
        print(f"{path}: {len(rows['secant at half the peak'])} curves")
        for label, values in rows.items():
            e = [v[0] for v in values]
            nu = [v[1] for v in values]
            print(f"  {label:<24} E {statistics.mean(e):8.3f} GPa (CV {cv_pct(e):4.1f} %)   "
                  f"nu {statistics.mean(nu):.4f} (CV {cv_pct(nu):4.1f} %)")


if __name__ == "__main__":
    main()
