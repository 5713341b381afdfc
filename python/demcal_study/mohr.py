"""Mohr circles of a biaxial series with its Mohr-Coulomb envelope, from the verification runs of a calibration: per
confinement the mean peak (sigma_3, sigma_1) over the runs, a circle each, and the least-squares envelope through
those means (sigma_1 = sigma_c + N_phi sigma_3, the line the biaxial test fits per run). Compression positive."""
import csv
import math
import re

PEAK = re.compile(r"^(?:(?P<label>.+)\.)?sigma_(?P<which>[13])_peak_MPa_(?P<k>\d+)$")


def series_means(runs_csv):
    """{label: [(k, mean sigma_3, mean sigma_1, runs)]} over the ok runs, "" for a scene's one test; and
    {label: {output: [values]}} of the envelope outputs (c_MPa, phi_deg, hb_m_i) per run."""
    with open(runs_csv, newline="") as f:
        rows = [r for r in csv.DictReader(f) if r.get("status", "ok") == "ok"]
    if not rows:
        return {}, {}
    peaks = {}
    for column in rows[0]:
        m = PEAK.match(column)
        if m:
            peaks.setdefault(m.group("label") or "", {}).setdefault(int(m.group("k")), {})[m.group("which")] = column
    means, envelope = {}, {}
    for label, by_k in peaks.items():
        points = []
        for k in sorted(by_k):
            if set(by_k[k]) != {"1", "3"}:
                continue
            pairs = [(float(r[by_k[k]["3"]]), float(r[by_k[k]["1"]])) for r in rows
                     if r[by_k[k]["3"]] not in ("", "nan") and r[by_k[k]["1"]] not in ("", "nan")]
            if pairs:
                points.append((k, sum(p[0] for p in pairs) / len(pairs), sum(p[1] for p in pairs) / len(pairs),
                               len(pairs)))
        if points:
            means[label] = points
            prefix = label + "." if label else ""
            envelope[label] = {name: [float(r[prefix + name]) for r in rows if r.get(prefix + name) not in (None, "", "nan")]
                               for name in ("c_MPa", "phi_deg", "hb_m_i")}
    return means, envelope


def envelope_line(points):
    """(sigma_c, N_phi, c, phi_deg) of the least-squares line through the mean peaks; None when it has no friction
    angle (fewer than two confinements, or a slope <= 0)."""
    if len(points) < 2:
        return None
    xs, ys = [p[1] for p in points], [p[2] for p in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    if sxx <= 0:
        return None
    n_phi = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    if n_phi <= 0:
        return None
    sigma_c = my - n_phi * mx
    return sigma_c, n_phi, sigma_c / (2 * math.sqrt(n_phi)), math.degrees(math.asin((n_phi - 1) / (n_phi + 1)))


def mohr_png(label, points, out_png):
    """Writes the circles and the envelope; None when written, else why not."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as e:
        return f"(no Mohr-circle plot: {e})"
    fig, ax = plt.subplots(figsize=(7, 4))
    top = 0.0
    for k, s3, s1, _ in points:
        centre, radius = 0.5 * (s1 + s3), 0.5 * (s1 - s3)
        t = [math.pi * i / 100 for i in range(101)]
        ax.plot([centre + radius * math.cos(a) for a in t], [radius * math.sin(a) for a in t], color=f"C{k - 1}",
                label=f"confinement {k}: sigma_3 {s3:.3g}, sigma_1 {s1:.3g} MPa")
        top = max(top, s1)
    line = envelope_line(points)
    if line:
        _, _, c, phi = line
        sigma = [0.0, top]
        ax.plot(sigma, [c + s * math.tan(math.radians(phi)) for s in sigma], "k--",
                label=f"envelope: c {c:.3g} MPa, phi {phi:.1f} deg")
    ax.set_xlim(0, top * 1.05)
    ax.set_ylim(0, None)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("normal stress sigma (MPa)")
    ax.set_ylabel("shear stress tau (MPa)")
    ax.set_title(f"{label + ': ' if label else ''}Mohr circles at the mean peaks of the verification runs", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    fig.savefig(out_png, dpi=150)
    plt.close(fig)
    return None


def _mean_sd(values):
    from .report_text import num
    if not values:
        return "-"
    m = sum(values) / len(values)
    if len(values) < 2:
        return num(m)
    sd = math.sqrt(sum((v - m) ** 2 for v in values) / (len(values) - 1))
    return f"{num(m)} (SD {num(sd)})"


def mohr_section(runs_csv, out_dir, heading="##", png_prefix="mohr"):
    """The report's Markdown for every biaxial series among the runs: a table of the mean peaks, the envelope of
    the means beside the mean of the per-run envelopes, and the figure (mohr_LABEL.png in out_dir)."""
    import os
    from .report_text import md, num
    means, envelope = series_means(runs_csv)
    lines = []
    for label, points in sorted(means.items()):
        lines += [f"{heading} Mohr circles{' of ' + md(label) if label else ''}", "",
                  "| confinement | mean sigma_3 MPa | mean sigma_1 MPa | runs |", "|---|---|---|---|"]
        lines += [f"| {k} | {num(s3)} | {num(s1)} | {n} |" for k, s3, s1, n in points]
        line = envelope_line(points)
        per_run = envelope[label]
        lines += ["", "Envelope through the mean peaks: " +
                  (f"c {num(line[2])} MPa, phi {num(line[3])} deg" if line else "none (no positive slope)") +
                  f"; per run (mean, SD): c_MPa {_mean_sd(per_run['c_MPa'])}, phi_deg {_mean_sd(per_run['phi_deg'])}"
                  + (f", Hoek-Brown m_i {_mean_sd(per_run['hb_m_i'])}" if per_run["hb_m_i"] else "") + ".", ""]
        png = f"{png_prefix}{'_' + label if label else ''}.png"
        why = mohr_png(label, points, os.path.join(out_dir, png))
        lines += [f"![Mohr circles]({png})" if why is None else why, ""]
    return lines
