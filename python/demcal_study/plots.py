"""The report's own figures (matplotlib): stress-strain curves of the verification runs, the convergence of
the DEM in the loop, speed against accuracy over the compared studies. Each returns None when it wrote the
figure, else why not (the report then leaves the figure out)."""
import csv


NO_CURVES = "(no curves stored)"  # curves_png's answer when no run stored a curve: a report then leaves the section out


def pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def curve_sets(group):
    """The curves a stored point holds, {label: (strain, stress)}: "" for a scene's one test, the test's label for
    each test of a test list (its datasets are curve_LABEL.axial_strain, ...)."""
    out = {}
    for key in group:
        if key.startswith("curve_") and key.endswith("axial_strain"):
            prefix = key[len("curve_"):-len("axial_strain")]
            stress = "curve_" + prefix + "stress_MPa"
            if stress in group and len(group[key]) > 0 and len(group[stress]) > 0:  # an external run may store none
                out[prefix.rstrip(".")] = (group[key][:], group[stress][:])
    return out


def confined(group, label):
    """Whether the label's curve is a confined test's (its stress is then sigma_1 - sigma_3)."""
    return "curve_" + (label + "." if label else "") + "confining_stress_MPa" in group


def pieces(strain, stress):
    """A curve split where its strain starts again (a biaxial series: one specimen per confinement)."""
    start = 0
    for k in range(1, len(strain)):
        if strain[k] < strain[k - 1]:
            yield strain[start:k], stress[start:k]
            start = k
    yield strain[start:], stress[start:]


def curve_axes(description):
    """{label: {"x", "y"}} of a scene's curves as demcal-dem describes them ("" for a scene's one test; a test
    list's labels), None for a test whose record is not a stress-strain curve."""
    if description.get("test") == "list":
        return {t["label"]: t.get("curve_axes") for t in description.get("tests", [])}
    return {"": description.get("curve_axes")}


def axes_of(scene):
    """curve_axes of the scene file `scene` (through demcal-dem describe); None when it cannot be described."""
    from . import executables
    from .errors import StudyError
    try:
        return curve_axes(executables.describe(scene))
    except (StudyError, OSError, KeyError, TypeError):
        return None


def curves_png(runs_h5, out_png, axes):
    """The stored curves of every point in `runs_h5`, one panel per test, labelled by `axes` (curve_axes)."""
    if axes is None:
        return "(no curve plot: the scene could not be described, so its axes are unknown)"
    try:
        import h5py
    except ImportError as e:
        return f"(no curve plot: {e})"
    with h5py.File(runs_h5, "r") as f:
        if "points" not in f or not any(curve_sets(f["points"][name]) for name in f["points"]):
            return NO_CURVES
    try:
        plt = pyplot()
    except ImportError as e:
        return f"(no curve plot: {e})"
    with h5py.File(runs_h5, "r") as f:
        runs = {name: {label: c for label, c in curve_sets(f["points"][name]).items() if axes.get(label)}
                for name in sorted(f["points"])}
    labels = sorted({label for sets in runs.values() for label in sets})
    if not labels:
        return NO_CURVES
    fig, panels = plt.subplots(1, len(labels), figsize=(6 * len(labels), 4), squeeze=False)
    for ax, label in zip(panels[0], labels):
        for name, sets in runs.items():
            if label not in sets:
                continue
            for k, (strain, stress) in enumerate(pieces(*sets[label])):
                ax.plot(strain * 100, stress, color=f"C{list(runs).index(name) % 10}",
                        label=name.replace("run1_", "") if k == 0 else None)
        ax.set_xlabel(axes[label]["x"] + " (%)")
        ax.set_ylabel(axes[label]["y"])
        ax.set_title(f"{label + ': ' if label else ''}verification runs at the calibrated parameters", fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out_png, dpi=150)
    plt.close(fig)  # as the other figures: a long-lived process would keep every figure open
    return None


def convergence_png(history_csv, out_png, objective_kind):
    try:
        plt = pyplot()
    except ImportError as e:
        return f"(no convergence plot: {e})"
    with open(history_csv) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        return "(empty history)"
    fig, ax = plt.subplots(figsize=(6, 4))
    for restart in sorted({r["restart"] for r in rows}):
        pts = [(int(r["evaluations"]), float(r["best_objective"])) for r in rows if r["restart"] == restart]
        ax.step([p[0] for p in pts], [p[1] for p in pts], where="post", label=f"run {restart}")
    ax.set_yscale("log")
    ax.set_xlabel("evaluations (DEM runs asked for)")
    ax.set_ylabel(f"best {objective_kind}")
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(out_png, dpi=150)
    plt.close(fig)
    return None


def comparison_png(rows, out_png):
    """Largest verified error (or, when the first study minimised an output, that output's verified mean with its
    95 % interval) against DEM runs and against wall time, one point per study (cost.study_cost)."""
    try:
        plt = pyplot()
    except ImportError as e:
        return f"(no chart: {e})"
    minimised = rows[0]["minimised"]
    if minimised:
        output = minimised["output"]
        points = [(r, r["minimised"]["mean"]) for r in rows if r["minimised"] and r["minimised"]["output"] == output]
        ylabel = f"verified {output}\n(mean and its 95 % interval)"
    else:
        points = [(r, r["max_error_pct"]) for r in rows if r["max_error_pct"] is not None]
        ylabel = "largest verified relative error (%)"
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    strategies = [r["strategy"] for r, _ in points]
    for index, (r, y) in enumerate(points):
        # Two studies of one strategy (other scenes, say) are told apart by their names.
        label = r["strategy"] if strategies.count(r["strategy"]) == 1 else f"{r['name']}\n({r['strategy']})"
        bar = None
        if minimised:
            low, high = r["minimised"]["ci95"]
            if low is not None and high is not None:
                bar = [[y - low], [high - y]]
        for ax, x in ((axes[0], r["dem_runs"]), (axes[1], None if r["wall_s"] is None else r["wall_s"] / 60)):
            if x is None:
                continue
            ax.errorbar(x, y, yerr=bar, fmt="o", capsize=3)
            # Labels alternate above and below their points, so two studies of like cost do not overprint.
            ax.annotate(label, (x, y), fontsize=8, xytext=(4, 4 if index % 2 == 0 else -14),
                        textcoords="offset points")
    largest = [max([r["dem_runs"] for r, _ in points] + [1]),
               max([r["wall_s"] / 60 for r, _ in points if r["wall_s"] is not None] + [1])]
    if minimised:
        top = max(r["minimised"]["ci95"][1] or y for r, y in points)
    else:
        tol = rows[0]["tolerance_pct"]
        top = max([y for _, y in points] + [tol])
    for ax, xlabel, right in zip(axes, ("DEM runs", "wall time of make study (min)"), largest):
        if not minimised:
            ax.axhline(tol, color="grey", linestyle="--", linewidth=1, label=f"tolerance {tol:g} %")
            ax.legend(fontsize=8)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.set_xlim(0, 1.45 * right)  # room for the labels
        ax.set_ylim(0, 1.15 * top)
        ax.grid(alpha=0.3)
    fig.suptitle("Speed versus accuracy of the calibration strategies")
    fig.tight_layout()
    fig.savefig(out_png, dpi=150)
    plt.close(fig)
    return None
