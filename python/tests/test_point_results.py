"""The per-point result files of a batch (OUT.points/runR_seedS.json): where they are, and how a missing or cut-off
one reads."""
import json

import pytest

from demcal_study.point_results import point_result_path, read_point_result, stored_point_results


def test_a_points_file_sits_beside_its_batch(tmp_path):
    out = str(tmp_path / "responses.h5")
    assert point_result_path(out, seed=3, run=7) == str(tmp_path / "responses.h5.points" / "run7_seed3.json")
    assert point_result_path(out, 2) == str(tmp_path / "responses.h5.points" / "run1_seed2.json")


def test_missing_and_cut_off_files_read_as_none(tmp_path):
    out = str(tmp_path / "responses.h5")
    (tmp_path / "responses.h5.points").mkdir()
    (tmp_path / "responses.h5.points" / "run1_seed1.json").write_text(json.dumps({"status": "ok", "macro": {"E": 1}}))
    (tmp_path / "responses.h5.points" / "run1_seed2.json").write_text('{"status": "o')  # cut off mid-write
    assert read_point_result(out, 1) == {"status": "ok", "macro": {"E": 1}}
    assert read_point_result(out, 2) is None
    assert read_point_result(out, 3) is None
    assert stored_point_results(out, [1], "who") == [{"status": "ok", "macro": {"E": 1}}]
    with pytest.raises(SystemExit, match=r"^who: .*run1_seed2\.json is missing or not JSON"):
        stored_point_results(out, [1, 2], "who")
