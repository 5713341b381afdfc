"""Writing the files make compares: stage configs (only when their content changes) and targets (always)."""
import os


def write_if_changed(path, text):
    """Writes only when the content differs, so make sees a change only where there is one."""
    if os.path.exists(path):
        with open(path) as f:
            if f.read() == text:
                return
    os.makedirs(os.path.dirname(path), exist_ok=True)
    write_target(path, text)


def write_target(path, text):
    """A make target: always rewritten (through a temporary file, so no half-written target remains), so it is
    newer than what it was made from."""
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)
