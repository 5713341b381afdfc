"""The study layer's help is a user's: the top-level help lists `calibrate` and `export` only (the stages plan.mk runs
still parse), documents BIN, CACHE and JOBS and the exit codes, `calibrate --help` documents --out-root and --quiet,
and --version names the version of the top-level CMakeLists.txt and the git commit, as the executables do."""
import re

from conftest import REPO, run_study_layer
from demcal_study.__main__ import parser

STAGES = ("plan", "design", "split", "score", "candidates", "screen", "stability", "refine", "report")


def test_the_top_level_help_lists_only_the_users_commands():
    done = run_study_layer(["--help"])
    assert done.returncode == 0, done.stderr
    text = done.stdout
    assert "{calibrate,export}" in text
    listed = re.findall(r"^    (\w+) ", text, re.M)  # argparse's list of subcommands
    assert listed == ["calibrate", "export"], text
    for stage in STAGES:
        assert not re.search(rf"\b{stage}\b.*(OUT_DIR|STUDY|CONFIG)", text), stage
    # The stages still parse: plan.mk runs them.
    args = parser().parse_args(["plan", "study.json", "out"])
    assert (args.command, args.study, args.out) == ("plan", "study.json", "out")
    assert parser().parse_args(["report", "out"]).command == "report"


def test_the_help_documents_the_environment_and_every_exit_code():
    text = run_study_layer(["--help"]).stdout
    for variable in ("BIN", "CACHE", "JOBS"):
        assert re.search(rf"^  {variable}\s+\S", text, re.M), variable
    assert "default build/bin" in text
    for code in range(5):
        assert re.search(rf"^  {code}  \S", text, re.M), code
    assert re.search(r"^  2  bad input.*nothing written", text, re.M)
    assert re.search(r"^  3  a target outside what the scene can reach", text, re.M)


def test_calibrate_help_documents_out_root_and_quiet():
    text = run_study_layer(["calibrate", "--help"]).stdout
    flat = " ".join(text.split())
    assert re.search(r"--out-root DIR the folder the calibration's own folder", flat)
    assert re.search(r"--quiet no progress lines on stderr", flat)
    for code in range(5):
        assert re.search(rf"^  {code}  \S", text, re.M), code


def test_version_names_the_cmake_version_and_the_commit():
    with open(f"{REPO}/CMakeLists.txt") as f:
        version = re.search(r"project\(demcal VERSION ([0-9.]+)", f.read()).group(1)
    done = run_study_layer(["--version"])
    assert done.returncode == 0, done.stderr
    assert re.fullmatch(rf"demcal_study {re.escape(version)} \(commit ([0-9a-f]{{7,40}}(\+local-changes)?|unknown)\)\n",
                        done.stdout), done.stdout


def test_a_usage_error_is_one_line():
    done = run_study_layer(["export", "--to", "pfc"])
    assert done.returncode == 2
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("demcal_study export: error: the following arguments are required")
