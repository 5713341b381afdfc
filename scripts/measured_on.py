"""What every measured table states beside its numbers: the machine, the commit and where a script writes its table
into a doc (between two marker lines, so the prose around it survives a re-run)."""
import os
import platform
import subprocess

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def machine():
    """Cores, CPU model and kernel, as /proc/cpuinfo and the platform name them."""
    model = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            model = next((line.split(":", 1)[1].strip() for line in f if line.startswith("model name")), model)
    except OSError:
        pass
    return f"{os.cpu_count()} cores, {model}, {platform.system()} {platform.release()}"


def commit():
    """The checked-out commit, marked when tracked files differ from it."""
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=REPO, capture_output=True, text=True)
    dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=REPO, capture_output=True,
                           text=True).stdout.strip()
    return (head.stdout.strip() or "unknown") + (" (with uncommitted changes)" if dirty else "")


def write_block(path, script, text):
    """Puts `text` into the doc at `path` between the marker lines of `script`: the whole file when it does not exist,
    the block alone when the file has its markers. A doc without them is left alone (an error), since writing over
    it would lose what was written around the table by hand. With text None it only checks that it could write
    (a script does that before its runs)."""
    begin, end = f"<!-- begin: written by {script} -->", f"<!-- end: written by {script} -->"
    block = f"{begin}\n{(text or '').rstrip()}\n{end}"
    if not os.path.exists(path):
        if text is None:
            return
        with open(path, "w") as f:
            f.write(block + "\n")
        return
    with open(path) as f:
        old = f.read()
    if old.count(begin) != 1 or old.count(end) != 1 or old.index(begin) > old.index(end):
        raise SystemExit(f"{script}: {path} exists without one pair of lines '{begin}' and '{end}'; add them around "
                         "the table it should replace, or write elsewhere with --out")
    if text is None:
        return
    with open(path, "w") as f:
        f.write(old[:old.index(begin)] + block + old[old.index(end) + len(end):])
