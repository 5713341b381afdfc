"""A study whose only stage is a screening (as data/studies/concrete_screening.json) runs end to end: an L18
on the test suite's small specimen through plan and make, into its analysis and a report of it."""
import json
import os
import subprocess

from conftest import PYTHON_DIR, REPO, run_study_layer


def test_a_screening_alone_runs_into_its_report(tmp_path, bin_dir):
    with open(os.path.join(REPO, "tests", "data", "study_small_screening.json")) as f:
        study = json.load(f)
    alone = {k: study[k] for k in ("scene", "space", "screening")}
    alone.update(name="screening_alone", description="The small screening alone.")
    path = tmp_path / "screening_alone.json"
    path.write_text(json.dumps(alone))
    out = tmp_path / "s"
    planned = run_study_layer(["plan", str(path), str(out)], bin_dir)
    assert planned.returncode == 0, planned.stderr
    make = ["make", "--no-print-directory", "-f", str(out / "plan.mk"), f"BIN={bin_dir}",
            f"CACHE={tmp_path / 'cache'}", "JOBS=2", "all"]
    env = dict(os.environ, PYTHONPATH=PYTHON_DIR)
    done = subprocess.run(make, cwd=REPO, env=env, capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    report = (out / "report.md").read_text()
    assert report.startswith("# Screening report: screening_alone")
    assert "### Analysis of variance of sigma_u_MPa" in report and "## Significant factors" in report
    assert "18 DEM runs" in report and "Factors kept" not in report
    # The screening is the result: its table keeps every DEM output, not only the analysed ones.
    header = (out / "screening" / "screening.csv").read_text().splitlines()[0].split(",")
    assert {"sigma_u_MPa", "E_GPa", "nu", "peak_strain"} <= set(header)
    assert "data:image/png;base64" in (out / "report.html").read_text()
    again = subprocess.run(make, cwd=REPO, env=env, capture_output=True, text=True)
    assert "Nothing to be done" in again.stdout, again.stdout
