"""A study that drives one output down (objective minimise): its cost table and speed-versus-accuracy chart show the
verified value of that output with its interval, and how many times below the reference it lies; a study of the
other kind (targets) is left out of that table rather than mixed in."""
from demcal_study import plots, sections


def row(name, strategy, runs, mean, low, high, passed=True, output="total_recovery_time_s"):
    return {"name": name, "strategy": strategy, "dem_runs": runs, "wall_s": 60.0 * runs / 40, "max_error_pct": 3.0,
            "passed": passed, "tolerance_pct": 10.0,
            "minimised": {"output": output, "mean": mean, "ci95": [low, high], "reference": 12.41}}


def test_the_table_gives_the_verified_value_its_interval_and_the_reduction(tmp_path):
    rows = [row("loop", "DEM in the loop (lhs-wca)", 205, 2.5, 2.4, 2.6),
            row("surface", "response surface + ga", 85, 4.279, 3.7386, 4.8199, passed=False)]
    targets = dict(rows[1], name="rock", minimised=None)
    lines = sections.minimised_table(rows + [targets])
    table = [line for line in lines if line.startswith("| loop") or line.startswith("| surface")]
    # Every number to four significant digits (report_text.num), the interval as the mean.
    assert table[0] == "| loop | DEM in the loop (lhs-wca) | 205 | 5.125 | 2.5 | 2.4 - 2.6 | 4.964 | yes |"
    assert table[1].endswith("| 4.279 | 3.739 - 4.82 | 2.9 | no |")
    assert not any(line.startswith("| rock") for line in lines)
    assert plots.comparison_png(rows + [targets], str(tmp_path / "speed_accuracy.png")) is None
    assert (tmp_path / "speed_accuracy.png").stat().st_size > 0


def test_the_chart_draws_minimised_studies_with_their_intervals(tmp_path):
    out = tmp_path / "chart.png"
    rows = [row("loop", "in the loop", 205, 2.5, 2.4, 2.6), row("surface", "surface", 85, 4.3, None, None),
            row("other", "another output", 50, 1.0, 0.9, 1.1, output="E_GPa")]
    assert plots.comparison_png(rows, str(out)) is None
    assert out.stat().st_size > 0
