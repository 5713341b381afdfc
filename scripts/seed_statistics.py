"""Mean and coefficient of variation of DEM macro values over the seeds of one setting
(shared by the resolution-study scripts)."""
import statistics


def macro_mean_cv(points, keys=("sigma_u_MPa", "E_GPa", "nu")):
    """{key_mean, key_cv_pct} over the points' macro values; NaN where there are too few."""
    row = {}
    for key in keys:
        values = [p["macro"][key] for p in points]
        mean = statistics.mean(values) if values else float("nan")
        row[key + "_mean"] = mean
        row[key + "_cv_pct"] = 100 * statistics.stdev(values) / abs(mean) if len(values) > 1 else float("nan")
    return row
