"""``gearcoupling check``: files, table and exit status (called in-process)."""

import csv
import json

import pytest

from gearcoupling.cli import main

pytestmark = [pytest.mark.needs_fcl]


def table_rows(text: str) -> list[list[str]]:
    """The cells of the worst-angle table's rows (a row's wrapped lines joined)."""
    rows: list[list[str]] = []
    for line in text.splitlines():
        if line.startswith("│"):
            cells = [c.strip() for c in line.strip("│").split("│")]
            if cells[0]:
                rows.append(cells)
            else:
                rows[-1] = [f"{a} {b}".strip() for a, b in zip(rows[-1], cells, strict=True)]
    return rows


def test_free_coupling_exits_0_and_writes_everything(tmp_path, capsys):
    out = tmp_path / "free"
    assert main(["check", "renzo-1967", "--angles", "6", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "worst angles" in text and "no interference" in text
    rows = table_rows(text)
    assert len(rows) == 6 and all(r[4] == "none" for r in rows)  # no tooth overlaps
    rows = list(csv.DictReader((out / "interference.csv").read_text().splitlines()))
    assert len(rows) == 6 and all(float(r["min_gap_mm"]) > 0 for r in rows)
    data = json.loads((out / "interference.json").read_text())
    assert data["interferes"] is False and data["misalignment_deg"] == pytest.approx(1.0)
    # mesh gap vs the exact sweep, per angle, within the chordal tolerance
    for r, exact in zip(rows, data["sweep_min_normal_clearance_mm"], strict=True):
        assert abs(float(r["min_gap_mm"]) - exact) < data["tolerance_mm"]
    assert (out / "interference.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert (out / "worst_hub.stl").stat().st_size > 0
    assert not (out / "worst_overlap.stl").exists()
    assert [p.name for p in out.glob(".*")] == [".gearcoupling.json"]  # the record only


def test_binding_coupling_exits_1(tmp_path, capsys):
    out = tmp_path / "tight"
    argv = ["check", "renzo-1967", "--misalignment", "1", "--angles", "4", "--set",
            "hub.backlash=0.001", "--method", "distance", "-o", str(out)]
    assert main(argv) == 1
    text = capsys.readouterr().out
    assert "INTERFERENCE" in text
    data = json.loads((out / "interference.json").read_text())
    assert data["interferes"] is True and data["overlaps"]
    # each row names the overlapping teeth: the first four and how many more
    for row in table_rows(text):
        psi = float(row[0])
        teeth = sorted({o["tooth"] for o in data["overlaps"]
                        if abs(o["angle_deg"] - psi) < 0.01})
        more = f" +{len(teeth) - 4}" if len(teeth) > 4 else ""
        assert row[4] == " ".join(map(str, teeth[:4])) + more, (row, teeth)
    assert data["max_overlap_depth_mm"] > 0
    assert (out / "worst_hub.stl").exists()


def test_hub_turned_past_backlash_exits_1(tmp_path):
    assert main(["check", "renzo-1967", "--misalignment", "0", "--angles", "2",
                 "--hub-rotation", "0.1", "-o", str(tmp_path)]) == 1
    data = json.loads((tmp_path / "interference.json").read_text())
    assert {o["flank"] for o in data["overlaps"]} == {"ccw"}


@pytest.mark.parametrize("argv, words", [
    (["--tolerance", "-1"], "--tolerance: '-1'"),
    (["--misalignment", "9"], "--misalignment = 9.0"),
    (["--hub-rotation", "20"], "hub_rotation_deg"),
    (["--teeth", "40"], "teeth = 40"),
])
def test_bad_options_exit_2(tmp_path, capsys, argv, words):
    assert main(["check", "renzo-1967", "--angles", "2", "-o", str(tmp_path), *argv]) == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err


def test_backlash_option_writes_mesh_and_sweep_backlash(tmp_path):
    assert main(["check", "renzo-1967", "--angles", "3", "--backlash", "--method", "distance",
                 "-o", str(tmp_path)]) == 0
    rows = list(csv.DictReader((tmp_path / "interference.csv").read_text().splitlines()))
    data = json.loads((tmp_path / "interference.json").read_text())
    bound = 2 * data["tolerance_mm"] * 63.5 / (63.5 * 0.9396926207859084)
    for r, exact in zip(rows, data["sweep_backlash_mm"], strict=True):
        assert abs(float(r["backlash_mm"]) - exact) < bound
    assert data["min_backlash_mm"] == pytest.approx(min(float(r["backlash_mm"]) for r in rows))
