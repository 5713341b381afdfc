"""scripts/measured_on.py: a study script writes its table into its doc between marker lines and keeps the prose
around them; a doc without the markers is not written over."""
import os
import sys

import pytest

from conftest import REPO

sys.path.insert(0, os.path.join(REPO, "scripts"))
from measured_on import commit, machine, write_block  # noqa: E402

SCRIPT = "scripts/some_study.py"


def test_a_new_doc_is_the_block_alone_and_a_rerun_replaces_only_the_block(tmp_path):
    doc = tmp_path / "study.md"
    write_block(str(doc), SCRIPT, "| a |\n|---|\n| 1 |\n")
    first = doc.read_text()
    assert first.splitlines() == [f"<!-- begin: written by {SCRIPT} -->", "| a |", "|---|", "| 1 |",
                                  f"<!-- end: written by {SCRIPT} -->"]
    doc.write_text("# Title\n\nBefore.\n\n" + first + "\n## Reading it\n\nAfter.\n")
    write_block(str(doc), SCRIPT, "| a |\n|---|\n| 2 |")
    assert doc.read_text() == (f"# Title\n\nBefore.\n\n<!-- begin: written by {SCRIPT} -->\n| a |\n|---|\n| 2 |\n"
                               f"<!-- end: written by {SCRIPT} -->\n\n## Reading it\n\nAfter.\n")


def test_a_doc_without_its_markers_is_left_alone_with_a_one_line_error(tmp_path):
    doc = tmp_path / "study.md"
    doc.write_text("# Written by hand\n")
    with pytest.raises(SystemExit, match="exists without one pair of lines"):
        write_block(str(doc), SCRIPT, "| a |")
    assert doc.read_text() == "# Written by hand\n"
    # The check a script makes before its runs (text None) says the same and writes nothing, nor a new file.
    with pytest.raises(SystemExit, match="exists without one pair of lines"):
        write_block(str(doc), SCRIPT, None)
    write_block(str(tmp_path / "new.md"), SCRIPT, None)
    assert not (tmp_path / "new.md").exists()


@pytest.mark.skipif(not os.path.isdir(os.path.join(REPO, ".git")), reason="not a git checkout")
def test_the_stamp_names_the_cores_and_a_commit():
    assert machine().split(" ", 1)[0] == str(os.cpu_count())
    assert commit().split(" ", 1)[0] not in ("", "unknown")
