"""Reports that read right: no exact-scaling claim for a scene that declares none, coordinates with their units, no
empty curves plot, names escaped for Markdown, verdicts in words, numbers to four significant digits, the final
parameter set (fixed values included) in one block at the top and as parameters.json beside the report, and no
absolute or internal paths."""
import json
import os
import re

import h5py
import markdown
import numpy as np
import pytest

from conftest import fake_describing_bin, run_study_layer
from demcal_study import calibrate, commands, executables, export, mohr, sections
from demcal_study.calibrate_report import final_runs_lines, report
from demcal_study.report_text import md, md_embedded, num, percent, verdict_words
from demcal_study.to_html import to_html
from test_calibrate import DESCRIPTION, fake  # noqa: F401 (fake: the closed-form stand-in for the DEM)


def calibrated(tmp_path, bin_dir, description=None, fixed=None, scene=None, monkeypatch=None):
    """A calibration of the stand-in (E_GPa 6.5, sigma_u_MPa 48, nu 0.2) run to its end (demcal-doe makes its first
    design), and its folder."""
    if description is not None:
        monkeypatch.setattr(executables, "describe", lambda scene, space=None: description)
    out = str(tmp_path / "cal")
    os.makedirs(out, exist_ok=True)
    config = {"scene": scene or "fake.json", "space": None, "targets": {"E_GPa": 6.5, "sigma_u_MPa": 48.0, "nu": 0.2},
              "fixed": fixed or {}, "tolerance": 0.05, "budget": 60, "scale_parameter": None}
    with open(os.path.join(out, "calibration.json"), "w") as f:
        json.dump(config, f)
    tools = commands.Tools(bin=bin_dir, jobs="2", cache=str(tmp_path / "cache"), python="")
    code = calibrate.Calibration(config, out, tools, quiet=True).run()
    report(out)
    with open(os.path.join(out, "solution.json")) as f:
        solution = json.load(f)
    with open(os.path.join(out, "report.md")) as f:
        return code, solution, out, f.read()


def external(description=DESCRIPTION):
    """The stand-in as an external program: no exact scaling declared, and a modulus in GPa no output depends on."""
    d = json.loads(json.dumps(description))
    d["exact_scaling"] = False
    d["parameters"]["young_GPa"] = {"unit": "GPa", "quantity": "stress", "stress_like": True, "si_factor": 1e9,
                                    "value": 24.0, "low": 1.0, "high": 100.0, "shapes_specimen": False}
    return d


def test_an_external_scene_gets_no_exact_scaling_claim_and_its_coordinates_keep_their_units(fake, tmp_path, bin_dir,
                                                                                           monkeypatch):
    code, solution, out, text = calibrated(tmp_path, bin_dir, external(), monkeypatch=monkeypatch)
    assert solution["problem"]["scale_parameter"] is None
    assert "exact scale factor" not in text and "`None`" not in text and "None" not in text
    assert "## The problem\n\nThe scene does not declare exact scaling" in text
    rows = {}
    for line in text.splitlines():  # each name's first row: the coordinates table
        if line.startswith("| "):
            rows.setdefault(line.split(" | ")[0][2:], line)
    assert rows["young_GPa"].startswith("| young_GPa | value in GPa | GPa | 1 | 100 | 24 | log |")
    assert rows["kn_ks"].startswith("| kn_ks | dimensionless | 1 |")
    assert "ratio to the scale parameter" not in text and "Scale factor" not in text
    # A scene that scales exactly keeps its dimensionless form.
    _, _, _, scaled = calibrated(tmp_path / "scaled", bin_dir, DESCRIPTION, monkeypatch=monkeypatch)
    assert "## The problem in dimensionless form" in scaled and "by an exact scale factor" in scaled
    assert "| sc_Pa | ratio to the scale parameter | 1 |" in scaled


def test_no_curves_section_when_no_run_stored_a_curve(tmp_path):
    runs = tmp_path / "runs"
    runs.mkdir()
    with h5py.File(runs / "runs.h5", "w") as f:  # an external program's runs: curve datasets without a point
        for seed in (1, 2):
            g = f.create_group(f"points/run1_seed{seed}")
            g.create_dataset("curve_axial_strain", data=np.zeros(0))
            g.create_dataset("curve_stress_MPa", data=np.zeros(0))
    assert final_runs_lines(str(runs), str(tmp_path), {"": {"x": "axial strain", "y": "axial stress (MPa)"}}) == []
    assert not (tmp_path / "verification_curves.png").exists()


def test_names_from_the_tools_are_escaped_and_turn_nothing_italic(tmp_path):
    (tmp_path / "screening").mkdir()
    anova = {"sigma_u_MPa": {"A": {"F": 30.0, "significance": "**"}, "A*B": {"F": 9.0, "significance": "*"},
                             "B*C": {"F": 7.0, "significance": "*"}, "_x_": {"F": 6.0, "significance": "*"},
                             "error": {"F": None, "significance": ""}}}
    (tmp_path / "screening" / "anova.json").write_text(json.dumps(anova))
    text = "\n".join(sections.significance_section(str(tmp_path)))
    html = to_html(text, str(tmp_path))
    assert "<em>" not in html and "<strong>" not in html
    assert "A**, A*B*, B*C*, _x_*" in html
    # An executable's table embedded in a report: its headings and tables kept, its text literal.
    table = ("### Analysis of variance of y\n\n| Source | DF | Significance |\n|---|---|---|\n"
             "| A*B | 1 | ** highly significant |\n| C*D*E | 2 | * significant |\n\n"
             "Marks: ** p < 0.01 (highly significant), * p < 0.05 (significant); a*b and c*d.")
    html = markdown.markdown(md_embedded(table), extensions=["tables"])
    assert "<h3>Analysis of variance of y</h3>" in html and "<td>C*D*E</td>" in html
    assert "<em>" not in html and "<strong>" not in html and "a*b and c*d" in html
    assert md("a|b") == "a\\|b" and md("sigma_u_MPa") == "sigma_u_MPa" and md("<b>") == "&lt;b>"


def test_verdicts_are_written_in_words(fake, tmp_path, bin_dir):
    _, solution, _, text = calibrated(tmp_path, bin_dir)
    assert solution["verifications"][-1]["verdict"] == "mean_inside_band"
    for raw in ("interval_inside_band", "mean_inside_band", "| outside |"):
        assert raw not in text
    assert "the mean lies within the tolerance, but its 95 % interval reaches beyond it" in text
    assert verdict_words("interval_inside_band") == "the mean and its whole 95 % interval lie within the tolerance"
    assert verdict_words("outside") == "the mean lies outside the tolerance, or fewer than two seeds ran"
    (tmp_path / "candidates.json").write_text(json.dumps({"candidates": [
        {"rank": 1, "cluster_size": 3, "x": {"a": 1.0}, "predicted": {"y": 2.0}, "seeds_run": 2, "seeds_failed": 0,
         "outputs": {"y": {"mean": 2.0, "ci95_low": 1.9, "ci95_high": 2.1}}, "verdict": "interval_inside_band",
         "chosen": True}]}))
    lines = sections.candidates_lines(str(tmp_path))
    assert lines[-1].endswith("| the mean and its whole 95 % interval lie within the tolerance | yes |")


def test_numbers_have_four_significant_digits_from_one_function(fake, tmp_path, bin_dir):
    assert [num(x) for x in (140.0, 0.0055149, 1.23456e10, 2.5, 30.000001, -0.0, None, float("nan"))] == [
        "140", "0.005515", "1.235e+10", "2.5", "30", "0", "-", "-"]
    assert [percent(x) for x in (2.14e-6, -14.2, 118.94, 0.58791)] == ["+0", "-14.2", "+118.9", "+0.59"]
    # A per-run envelope's SD of 141.4 MPa was written 1.4e+02 beside means to four digits.
    runs = tmp_path / "runs.csv"
    runs.write_text("status,biaxial.sigma_3_peak_MPa_1,biaxial.sigma_1_peak_MPa_1,biaxial.sigma_3_peak_MPa_2,"
                    "biaxial.sigma_1_peak_MPa_2,biaxial.c_MPa,biaxial.phi_deg\n"
                    "ok,1,20,4,29,100,30.123\nok,1,20,4,29,300,31.456\n")
    envelope = next(line for line in mohr.mohr_section(str(runs), str(tmp_path)) if line.startswith("Envelope"))
    assert "c_MPa 200 (SD 141.4)" in envelope and "phi_deg 30.79 (SD 0.9426)" in envelope and "e+" not in envelope
    _, solution, _, text = calibrated(tmp_path / "cal", bin_dir)
    assert f"Scale factor {solution['scale_factor']:.4g} (" in text


def block_of(text):
    """The first ```text block of a report as {name: (value, comment)}."""
    block = text.split("```text\n", 1)[1].split("\n```", 1)[0]
    out = {}
    for line in block.splitlines():
        name, _, rest = line.partition(" = ")
        value, _, comment = rest.partition("  # ")
        out[name.strip()] = (float(value), comment)
    return out


def test_the_final_parameter_set_is_one_block_at_the_top_and_parameters_json_beside_it(fake, tmp_path, bin_dir):
    code, solution, out, text = calibrated(tmp_path, bin_dir, fixed={"mu": 0.5})
    assert code == calibrate.EXIT_MET
    headings = [line for line in text.splitlines() if line.startswith("## ")]
    assert headings[0] == "## Final parameter set"
    block = block_of(text)
    # Every parameter: the calibrated ones, the fixed one and the one left at the scene's value, exact.
    assert {n: v for n, (v, _) in block.items()} == dict(solution["x"], R_m=1e-3)
    assert block["mu"] == (0.5, "fixed") and block["Ec_Pa"][1] == "Pa, calibrated"
    assert block["R_m"][1] == "m, the scene's value"
    with open(os.path.join(out, "parameters.json")) as f:
        stored = json.load(f)["parameters"]
    assert {n: p["value"] for n, p in stored.items()} == {n: v for n, (v, _) in block.items()}
    assert stored["Ec_Pa"]["unit"] == "Pa" and stored["mu"]["set"] == "fixed"
    # The export line runs as written from the report's folder, with the study layer's package found from there.
    package = os.path.relpath(os.path.join(os.path.dirname(__file__), "..", ""), out).rstrip("/")
    assert (f"PYTHONPATH={package} /usr/bin/python3 -m demcal_study export --solution parameters.json --scene "
            in text)
    html = open(os.path.join(out, "report.html")).read()
    assert re.search(r"<pre><code[^>]*>Ec_Pa = [0-9.]+  # Pa, calibrated\n", html)  # one copyable block
    # export reads parameters.json as it reads a solution: the set as the user's simulator takes it.
    assert export.as_solution(json.load(open(os.path.join(out, "parameters.json"))), "p")["x"]["mu"] == 0.5
    fake_bin = fake_describing_bin(str(tmp_path / "bin"), dict(DESCRIPTION, scene="fake.json"))
    done = run_study_layer(["export", "--solution", os.path.join(out, "parameters.json"), "--scene", "fake.json",
                            "--to", "pfc"], fake_bin)
    assert done.returncode == 0, done.stderr
    assert f"Ec_Pa = {solution['x']['Ec_Pa']!r}" in done.stdout and "mu = 0.5" in done.stdout


def test_a_report_names_no_absolute_or_internal_path(fake, tmp_path, bin_dir):
    scene = tmp_path / "scenes" / "fake.json"
    scene.parent.mkdir()
    scene.write_text("{}")
    _, solution, out, _ = calibrated(tmp_path, bin_dir, scene=str(scene))
    # A failed seed whose reason names a file by its absolute path.
    last = os.path.join(out, solution["verifications"][-1]["folder"], "verification.json")
    with open(last) as f:
        v = json.load(f)
    v["seeds"].append({"seed": 99, "status": "failed", "macro": {},
                       "reason": f"{out}/verify/v01/runs.h5.points/run1_seed99.json: packing failed"})
    with open(last, "w") as f:
        json.dump(v, f)
    report(out)
    text = open(os.path.join(out, "report.md")).read()
    assert str(tmp_path) not in text and not re.search(r"(^|[\s`(])/(tmp|home|work|usr)/(?!bin/python3 )", text, re.M)
    assert "Scene `../scenes/fake.json`" in text
    assert "seed 99 failed: verify/v01/runs.h5.points/run1_seed99.json: packing failed" in text
    assert json.load(open(os.path.join(out, "parameters.json")))["scene"] == "../scenes/fake.json"


def test_a_study_report_opens_with_its_parameter_set_and_names_no_absolute_path(tmp_path, bin_dir):
    import subprocess
    from conftest import REPO
    from test_holdout_and_candidates import write_study
    out = tmp_path / "out"
    planned = run_study_layer(["plan", str(write_study(tmp_path)), str(out)], bin_dir)
    assert planned.returncode == 0, planned.stderr
    made = subprocess.run(["make", "--no-print-directory", "-f", str(out / "plan.mk"), f"BIN={bin_dir}",
                           f"CACHE={tmp_path / 'cache'}", "JOBS=2", "all"], cwd=REPO, capture_output=True, text=True,
                          env=dict(os.environ, PYTHONPATH=os.path.join(REPO, "python")))
    assert made.returncode == 0, made.stdout[-3000:] + made.stderr[-3000:]
    text = (out / "report.md").read_text()
    assert [line for line in text.splitlines() if line.startswith("## ")][0] == "## Final parameter set"
    verification = json.loads((out / "verification.json").read_text())
    block = block_of(text)
    assert block["mode"] == (0.0, "fixed")
    assert block["a_MPa"] == (pytest.approx(verification["parameters"]["a_MPa"]), "MPa, calibrated")
    stored = json.loads((out / "parameters.json").read_text())
    assert stored["parameters"]["b_MPa"]["unit"] == "MPa" and stored["status"] == "verified"
    assert str(tmp_path) not in text and "space `../space.json`" in text
    assert "mean_inside_band" not in text and "interval_inside_band" not in text
