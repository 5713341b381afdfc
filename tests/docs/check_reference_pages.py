#!/usr/bin/python3
"""The reference pages cannot drift from the program: every registered contact model and lab test has its page
(docs/reference/contact_models/NAME.md, docs/reference/lab_tests/NAME.md), a model's page names every parameter key
the model takes, a lab test's page names every output of the shipped scenes that run it, and each executable's page
names every option its --help lists.

    check_reference_pages.py BIN_DIR SOURCE_DIR

Prints one line per missing page or name and exits 1 when there is any; 0 otherwise."""
import glob
import json
import os
import re
import subprocess
import sys

PROGRAMS = ("demcal-doe", "demcal-dem", "demcal-analyze", "demcal-fit", "demcal-predict", "demcal-invert",
            "demcal-verify")


def run(command):
    return subprocess.run(command, check=True, capture_output=True, text=True).stdout


def named(page_text, name):
    """`name` appears in backticks on the page (alone, or as the start of a code span such as `name: ...`)."""
    return re.search(r"`" + re.escape(name) + r"(`|[ =:\[(])", page_text) is not None


def page(source, *parts):
    path = os.path.join(source, "docs", "reference", *parts)
    return path, (open(path, encoding="utf-8").read() if os.path.exists(path) else None)


def shipped_scenes_by_test(bin_dir, source):
    """{test name: {scene path: [output names]}} over data/scenes (test lists count for each of their tests)."""
    by_test = {}
    for path in sorted(glob.glob(os.path.join(source, "data", "scenes", "**", "*.json"), recursive=True)):
        d = json.loads(run([os.path.join(bin_dir, "demcal-dem"), "describe", "--scene", path]))
        if d["test"] == "list":
            for out_name, o in d["outputs"].items():
                test = next(t["test"] for t in d["tests"] if t["label"] == o["test"])
                by_test.setdefault(test, {}).setdefault(path, []).append(out_name.split(".", 1)[-1])
        else:
            by_test.setdefault(d["test"], {})[path] = list(d["outputs"])
    return by_test


def help_options(bin_dir, program):
    text = run([os.path.join(bin_dir, program), "--help"])
    sub = re.search(r"^Subcommands:\n((?:  \S.*\n)+)", text, re.M)
    for name in re.findall(r"^  (\S+)", sub.group(1), re.M) if sub else []:
        text += run([os.path.join(bin_dir, program), name, "--help"])
    return sorted(set(re.findall(r"(--[a-z][a-z0-9-]*)", text)) - {"--help"})


def problems(bin_dir, source):
    out = []
    registries = json.loads(run([os.path.join(bin_dir, "demcal-dem"), "describe", "--registries"]))
    # Contact models per engine: a 2D model's page is NAME.md, a 3D one's NAME_3d.md.
    for dim, models in registries["contact_models"].items():
        for model in models:
            path, text = page(source, "contact_models", model + (".md" if dim == "2d" else f"_{dim}.md"))
            if text is None:
                out.append(f"{os.path.relpath(path, source)}: missing (the {dim} contact model \"{model}\" is registered)")
                continue
            out += [f"{os.path.relpath(path, source)}: does not name the parameter `{key}`"
                    for key in registries["contact_model_parameters"][dim][model] if not named(text, key)]
    scenes = shipped_scenes_by_test(bin_dir, source)
    for test in registries["tests"]:
        path, text = page(source, "lab_tests", test + ".md")
        if text is None:
            out.append(f"{os.path.relpath(path, source)}: missing (the lab test \"{test}\" is registered)")
            continue
        for scene, outputs in scenes.get(test, {}).items():
            out += [f"{os.path.relpath(path, source)}: does not name the output `{name}` "
                    f"(of {os.path.relpath(scene, source)})" for name in outputs if not named(text, name)]
    for program in PROGRAMS:
        path, text = page(source, "executables", program + ".md")
        if text is None:
            out.append(f"{os.path.relpath(path, source)}: missing (an executable of the build)")
            continue
        out += [f"{os.path.relpath(path, source)}: does not name the option `{option}`"
                for option in help_options(bin_dir, program) if not named(text, option)]
    return sorted(set(out))


def main(argv):
    if len(argv) != 3:
        print(__doc__.split("\n\n")[1].strip(), file=sys.stderr)
        return 2
    found = problems(argv[1], argv[2])
    for line in found:
        print(line)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
