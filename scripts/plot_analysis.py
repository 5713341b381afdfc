#!/usr/bin/python3
"""Figures of the demcal analysis outputs.

  main-effects: level means k of each factor, one panel per factor, from
                `demcal-analyze range --format json`;
  pareto:       F values of the ANOVA terms against F_crit, from
                `demcal-analyze anova --format json`;
  fit:          predicted vs observed and residuals vs fitted, from
                `demcal-fit ... --residuals` (response surfaces or GA-BP).

    /usr/bin/python3 scripts/plot_analysis.py main-effects RANGE.json --out FILE.png [--response NAME]
    /usr/bin/python3 scripts/plot_analysis.py pareto ANOVA.json --out FILE.png [--response NAME]
    /usr/bin/python3 scripts/plot_analysis.py fit RESIDUALS.csv --out FILE.png [--response NAME]

With several responses and no --response, one figure per response is written
to FILE with "_<response>" inserted before the extension; each path written is
printed. Bad input: a one-line message on stderr and exit status 2.
"""
import argparse
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

DPI = 150
PROG = os.path.basename(sys.argv[0]) if sys.argv and sys.argv[0] else "plot_analysis.py"


class InputError(Exception):
    """Bad input: reported as one line on stderr, exit status 2."""


# ---------------------------------------------------------------- input ---

def load_json(path):
    try:
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
    except OSError as e:
        raise InputError(f"cannot read {path}: {e.strerror}")
    except json.JSONDecodeError as e:
        raise InputError(f"{path} is not valid JSON: {e.msg} at line {e.lineno}")
    if not isinstance(data, dict) or not data:
        raise InputError(f"{path}: expected a non-empty JSON object keyed by response")
    return data


def load_csv(path):
    try:
        with open(path, newline="", encoding="utf-8") as f:
            reader = csv.DictReader(f)
            rows = list(reader)
            header = reader.fieldnames or []
    except OSError as e:
        raise InputError(f"cannot read {path}: {e.strerror}")
    except csv.Error as e:
        raise InputError(f"{path} is not valid CSV: {e}")
    return header, rows


def number(value, what):
    """A finite or infinite float from a JSON/CSV value; None stays None."""
    if value is None:
        return None
    if isinstance(value, bool):
        raise InputError(f"{what}: expected a number, got {value!r}")
    try:
        return float(value)
    except (TypeError, ValueError):
        raise InputError(f"{what}: expected a number, got {value!r}")


def select_responses(names, wanted, source):
    names = list(names)
    if not names:
        raise InputError(f"{source}: no responses found")
    if wanted is None:
        return names
    if wanted not in names:
        raise InputError(f"{source}: unknown response {wanted!r} (available: {', '.join(names)})")
    return [wanted]


def output_path(out, response, several):
    if not several:
        return out
    root, ext = os.path.splitext(out)
    return f"{root}_{response.replace('/', '_over_')}{ext or '.png'}"  # a ratio A/B: no sub-folder


def save(fig, path):
    fig.tight_layout()
    try:
        fig.savefig(path, dpi=DPI)
    except OSError as e:
        raise InputError(f"cannot write {path}: {e.strerror}")
    finally:
        plt.close(fig)
    print(path)


def fmt(value):
    return f"{value:.4g}"


# --------------------------------------------------------- main effects ---

def parse_range(response, table):
    """(grand_mean, runs, [(factor, levels, k, R, rank)]) of one response."""
    where = f"range JSON, response {response!r}"
    if not isinstance(table, dict) or not isinstance(table.get("factors"), dict) or not table["factors"]:
        raise InputError(f"{where}: expected an object with a non-empty \"factors\" object")
    grand_mean = number(table.get("grand_mean"), f"{where}, grand_mean")
    if grand_mean is None:
        raise InputError(f"{where}: missing \"grand_mean\"")
    runs = table.get("runs")
    factors = []
    # JSON objects lose their order; "factor_order" keeps the design's column order.
    order = table.get("factor_order") or list(table["factors"])
    for name in order:
        f = table["factors"].get(name)
        fw = f"{where}, factor {name!r}"
        if not isinstance(f, dict) or not isinstance(f.get("levels"), list) or not isinstance(f.get("k"), list):
            raise InputError(f"{fw}: expected \"levels\" and \"k\" lists")
        if len(f["levels"]) != len(f["k"]) or not f["k"]:
            raise InputError(f"{fw}: \"levels\" and \"k\" differ in length or are empty")
        levels = [number(v, f"{fw}, levels") for v in f["levels"]]
        k = [number(v, f"{fw}, k") for v in f["k"]]
        r = number(f.get("R"), f"{fw}, R")
        rank = f.get("rank")
        factors.append((name, levels, k, r, rank))
    return grand_mean, runs, factors


def grid(n, max_cols=5):
    cols = min(n, max_cols if n > 8 else 4)
    rows = math.ceil(n / cols)
    return rows, cols


def level_label(value):
    return "" if value is None else f"{value:g}"


def plot_main_effects(response, grand_mean, runs, factors, path):
    rows, cols = grid(len(factors))
    fig, axes = plt.subplots(rows, cols, figsize=(3.3 * cols, 2.9 * rows), sharey=True, squeeze=False)
    for ax, (name, levels, k, r, rank) in zip(axes.flat, factors):
        x = np.arange(len(levels))
        y = np.array([np.nan if v is None else v for v in k])
        ax.plot(x, y, "o-", color="tab:blue", markersize=5)
        ax.axhline(grand_mean, color="grey", linestyle="--", linewidth=1)
        ax.set_xticks(x)
        ax.set_xticklabels([level_label(v) for v in levels])
        ax.set_xlim(-0.4, len(levels) - 0.6)
        r_text = "n/a" if r is None else fmt(r)
        ax.set_title(f"{name}\n(R={r_text}, rank {rank})", fontsize=9)
        ax.set_xlabel(f"{name} level", fontsize=8)
        ax.tick_params(labelsize=8)
        ax.grid(True, alpha=0.3)
    for ax in axes[:, 0]:
        ax.set_ylabel(f"mean k of {response}", fontsize=9)
        ax.yaxis.set_tick_params(labelleft=True)
    for ax in list(axes.flat)[len(factors):]:
        ax.set_visible(False)
    runs_text = f", {runs} runs" if runs is not None else ""
    fig.suptitle(f"Main effects on {response} (dashed: grand mean = {fmt(grand_mean)}{runs_text})", fontsize=11)
    save(fig, path)


def for_each_response(args, tables, draw):
    """Calls draw(response, table, png path) for the chosen response or every one."""
    responses = select_responses(tables.keys(), args.response, args.input)
    for response in responses:
        draw(response, tables[response], output_path(args.out, response, len(responses) > 1))


def cmd_main_effects(args):
    for_each_response(args, load_json(args.input),
                      lambda response, table, path: plot_main_effects(response, *parse_range(response, table), path))


# --------------------------------------------------------------- pareto ---

SIG_COLOURS = {"**": "#08306b", "*": "#4292c6", "": "#c6dbef"}
SIG_LABELS = {"**": "** p < 0.01", "*": "* p < 0.05", "": "not significant"}


def parse_anova(response, table):
    """(plotted terms [(name, F, sig, crit05, crit01, df)], pooled names, error df)."""
    where = f"anova JSON, response {response!r}"
    if not isinstance(table, dict):
        raise InputError(f"{where}: expected an object keyed by term")
    error = table.get("error")
    if not isinstance(error, dict):
        raise InputError(f"{where}: missing \"error\" object")
    terms, pooled = [], []
    for name, t in table.items():
        if name == "error":
            continue
        tw = f"{where}, term {name!r}"
        if not isinstance(t, dict) or "F" not in t:
            raise InputError(f"{tw}: expected an object with \"F\"")
        f = number(t["F"], f"{tw}, F")
        if t.get("pooled"):
            pooled.append(name)
        if f is None or t.get("pooled"):
            continue
        sig = t.get("significance") or ""
        if sig not in SIG_COLOURS:
            raise InputError(f"{tw}: unknown significance {sig!r}")
        terms.append((name, f, sig, number(t.get("F_crit_0.05"), f"{tw}, F_crit_0.05"),
                      number(t.get("F_crit_0.01"), f"{tw}, F_crit_0.01"), t.get("df")))
    if not terms:
        raise InputError(f"{where}: no term with a non-null F to plot")
    return terms, pooled, error.get("df")


def same_crits(terms):
    first = terms[0]
    return all(math.isclose(t[3] or 0, first[3] or 0, rel_tol=1e-9) and
               math.isclose(t[4] or 0, first[4] or 0, rel_tol=1e-9) for t in terms)


def plot_pareto(response, terms, pooled, error_df, path):
    terms = sorted(terms, key=lambda t: t[1])  # barh draws bottom-up: largest ends at top
    names = [t[0] for t in terms]
    f_values = np.array([t[1] for t in terms])
    crits = [c for t in terms for c in (t[3], t[4]) if c is not None and c > 0]
    positive = f_values[f_values > 0]
    log = positive.size > 0 and f_values.max() / positive.min() > 100

    fig, ax = plt.subplots(figsize=(8, 0.35 * len(terms) + 2.2))
    y = np.arange(len(terms))
    colours = [SIG_COLOURS[t[2]] for t in terms]
    if log:
        low = min(list(positive) + crits) / 3
        ax.set_xscale("log")
        ax.barh(y, np.maximum(f_values, low) - low, left=low, color=colours, edgecolor="black", linewidth=0.5)
        ax.set_xlim(low, max(list(f_values) + crits) * 3)
    else:
        ax.barh(y, f_values, color=colours, edgecolor="black", linewidth=0.5)
        ax.set_xlim(0, max(list(f_values) + crits) * 1.15)
    for yi, f in zip(y, f_values):
        label = f"{f:.0f}" if f >= 1000 else f"{f:.3g}"
        ax.annotate(label, (f if f > 0 else ax.get_xlim()[0], yi), xytext=(4, 0), textcoords="offset points",
                    va="center", fontsize=8, bbox=dict(facecolor="white", edgecolor="none", alpha=0.8, pad=0.5))

    if same_crits(terms):
        c05, c01 = terms[0][3], terms[0][4]
        if c05 is not None:
            ax.axvline(c05, color="black", linestyle="--", linewidth=1, label=f"F_crit 0.05 = {c05:.3g}")
        if c01 is not None:
            ax.axvline(c01, color="black", linestyle=":", linewidth=1.2, label=f"F_crit 0.01 = {c01:.3g}")
    else:
        for yi, t in zip(y, terms):
            if t[3] is not None:
                ax.plot([t[3]] * 2, [yi - 0.45, yi + 0.45], color="black", linestyle="--", linewidth=1)
            if t[4] is not None:
                ax.plot([t[4]] * 2, [yi - 0.45, yi + 0.45], color="black", linestyle=":", linewidth=1.2)
        ax.plot([], [], color="black", linestyle="--", label="F_crit 0.05 (per term df)")
        ax.plot([], [], color="black", linestyle=":", label="F_crit 0.01 (per term df)")
    for sig in ("**", "*", ""):
        if any(t[2] == sig for t in terms):
            ax.barh([np.nan], [np.nan], color=SIG_COLOURS[sig], edgecolor="black", linewidth=0.5,
                    label=SIG_LABELS[sig])

    ax.set_yticks(y)
    ax.set_yticklabels(names, fontsize=9)
    ax.set_ylim(-0.6, len(terms) - 0.4)
    ax.set_xlabel("F" + (" (log scale)" if log else ""))
    ax.set_ylabel("term")
    ax.grid(True, axis="x", alpha=0.3, which="both" if not log else "major")
    ax.legend(fontsize=8, loc="lower right", framealpha=0.9)
    ax.set_title(f"ANOVA Pareto of F for {response} (error df = {error_df})", fontsize=11)
    if pooled:
        fig.text(0.01, 0.005, "pooled into the error: " + ", ".join(pooled), fontsize=8, ha="left", va="bottom",
                 wrap=True)
    save(fig, path)


def cmd_pareto(args):
    for_each_response(args, load_json(args.input),
                      lambda response, table, path: plot_pareto(response, *parse_anova(response, table), path))


# ------------------------------------------------------------------ fit ---

SURFACE_COLUMNS = ["run", "response", "observed", "fitted", "residual", "press_residual"]
GABP_COLUMNS = ["run", "set", "response", "observed", "fitted", "residual"]
SET_COLOURS = {"training": "tab:blue", "validation": "tab:orange"}


def parse_residuals(path, header, rows):
    """("surface" | "gabp", {response: [row dicts with floats]})."""
    if header == SURFACE_COLUMNS:
        kind, numeric = "surface", ["observed", "fitted", "residual", "press_residual"]
    elif header == GABP_COLUMNS:
        kind, numeric = "gabp", ["observed", "fitted", "residual"]
    else:
        raise InputError(f"{path}: unrecognised header {','.join(header)!r} "
                         f"(expected {','.join(SURFACE_COLUMNS)} or {','.join(GABP_COLUMNS)})")
    by_response = {}
    for line, row in enumerate(rows, start=2):
        parsed = dict(row)
        for col in numeric:
            parsed[col] = number(row[col], f"{path} line {line}, {col}")
            if parsed[col] is None:
                raise InputError(f"{path} line {line}: missing {col}")
        by_response.setdefault(row["response"], []).append(parsed)
    if not by_response:
        raise InputError(f"{path}: no data rows")
    return kind, by_response


def r_squared(observed, fitted):
    observed, fitted = np.asarray(observed, float), np.asarray(fitted, float)
    ss_tot = np.sum((observed - observed.mean()) ** 2)
    if observed.size < 2 or ss_tot == 0:
        return float("nan")
    return 1.0 - np.sum((observed - fitted) ** 2) / ss_tot


def groups(kind, rows):
    """[(label, colour, rows)]: one group for surfaces, one per set for GA-BP."""
    if kind == "surface":
        return [("runs", "tab:blue", rows)]
    names = list(dict.fromkeys(r["set"] for r in rows))
    return [(n, SET_COLOURS.get(n, None), [r for r in rows if r["set"] == n]) for n in names]


def plot_fit(response, kind, rows, path):
    fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(11, 4.8))
    r2_parts = []
    for label, colour, members in groups(kind, rows):
        obs = [r["observed"] for r in members]
        fit = [r["fitted"] for r in members]
        r2 = r_squared(obs, fit)
        r2_parts.append(f"R^2 = {r2:.4f}" if kind == "surface" else f"R^2 {label} = {r2:.4f}")
        ax_a.scatter(obs, fit, s=22, color=colour, edgecolor="black", linewidth=0.4, label=f"{label} ({len(members)})")
        ax_b.scatter(fit, [r["residual"] for r in members], s=22, color=colour, edgecolor="black", linewidth=0.4,
                     label=f"residual ({label})" if kind == "gabp" else "residual")
    if kind == "surface":
        press = [(r["fitted"], r["press_residual"]) for r in rows if math.isfinite(r["press_residual"])]
        if press:
            ax_b.scatter(*zip(*press), s=30, facecolors="none", edgecolors="tab:red", linewidth=0.9,
                         label="PRESS residual")
        dropped = len(rows) - len(press)
        if dropped:
            ax_b.text(0.01, 0.01, f"{dropped} non-finite PRESS residual(s) not shown", transform=ax_b.transAxes,
                      fontsize=7, va="bottom")

    values = [r[c] for r in rows for c in ("observed", "fitted")]
    lo, hi = min(values), max(values)
    pad = 0.05 * (hi - lo or abs(hi) or 1.0)
    ax_a.plot([lo - pad, hi + pad], [lo - pad, hi + pad], color="grey", linestyle="--", linewidth=1, label="y = x")
    ax_a.set_xlim(lo - pad, hi + pad)
    ax_a.set_ylim(lo - pad, hi + pad)
    ax_a.set_aspect("equal", adjustable="box")
    ax_a.set_xlabel(f"observed {response}")
    ax_a.set_ylabel(f"fitted {response}")
    ax_a.set_title("(a) fitted vs observed\n" + ", ".join(r2_parts), fontsize=10)
    ax_a.grid(True, alpha=0.3)
    ax_a.legend(fontsize=8, loc="upper left")

    ax_b.axhline(0, color="grey", linestyle="--", linewidth=1)
    ax_b.set_xlabel(f"fitted {response}")
    ax_b.set_ylabel("residual (observed - fitted)")
    ax_b.set_title("(b) residuals vs fitted\n", fontsize=10)
    ax_b.grid(True, alpha=0.3)
    ax_b.legend(fontsize=8, loc="best")

    model = "response surface" if kind == "surface" else "GA-BP network"
    fig.suptitle(f"{model} fit of {response} ({len(rows)} points)", fontsize=11)
    save(fig, path)


def cmd_fit(args):
    header, rows = load_csv(args.input)
    kind, by_response = parse_residuals(args.input, header, rows)
    for_each_response(args, by_response, lambda response, points, path: plot_fit(response, kind, points, path))


# ----------------------------------------------------------------- main ---

def build_parser():
    parser = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    specs = [
        ("main-effects", cmd_main_effects, "RANGE.json", "level means per factor (demcal-analyze range --format json)"),
        ("pareto", cmd_pareto, "ANOVA.json", "Pareto of ANOVA F values (demcal-analyze anova --format json)"),
        ("fit", cmd_fit, "RESIDUALS.csv", "fit diagnostics (demcal-fit ... --residuals)"),
    ]
    for name, func, metavar, help_text in specs:
        p = sub.add_parser(name, help=help_text, description=help_text)
        p.add_argument("input", metavar=metavar)
        p.add_argument("--out", required=True, metavar="FILE.png",
                       help="output image; with several responses, _<response> is inserted before the extension")
        p.add_argument("--response", metavar="NAME", help="plot only this response")
        p.set_defaults(func=func)
    return parser


def main(argv=None):
    args = build_parser().parse_args(argv)
    try:
        args.func(args)
    except InputError as e:
        print(f"{PROG}: error: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
