"""``to_dataframe()`` of every result: the same table as the file the CLI writes.

Each DataFrame is compared with its CSV (or Parquet) file read back by pandas: the same
columns in the same order, the same values (to the CSV's 9-10 significant digits) and the
same number of rows; without pandas the call names the extra to install.
"""

from __future__ import annotations

import sys

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.cli import main
from gearcoupling.loading import write_capacity_csv
from inspection_synth import synthetic_hub

pd = pytest.importorskip("pandas")


def same_table(frame, path, **read):
    """``frame`` equals the file at ``path`` read by pandas (rtol 1e-8: the CSV's digits)."""
    if str(path).endswith(".parquet"):
        disk = pd.read_parquet(path)
    else:
        disk = pd.read_csv(path, **read)
    assert list(frame.columns) == list(disk.columns)
    assert len(frame) == len(disk) > 0
    pd.testing.assert_frame_equal(frame, disk, check_exact=False, rtol=1e-8, atol=1e-12,
                                  check_dtype=False)


@pytest.fixture(scope="module")
def swept(renzo):
    return gc.sweep(renzo, 1.0, np.arange(0.0, 360.0, 15.0))


def test_sweep_dataframe_is_sweep_csv(swept, tmp_path):
    frame = swept.to_dataframe()
    same_table(frame, swept.write_csv(tmp_path / "sweep.csv"))
    assert len(frame) == 2 * swept.teeth * swept.angles_deg.size
    # tidy: one row per (rotation, tooth, flank), the arrays' values
    row = frame[(frame.tooth == 3) & (frame.flank == "ccw")].iloc[5]
    assert row["clearance_mm"] == swept.clearance_mm[1, 3, 5]


def test_load_dataframe_is_load_csv(swept, tmp_path):
    res = gc.load_from_sweep(swept)
    frame = res.to_dataframe()
    same_table(frame, res.write_csv(tmp_path / "load.csv"))
    # rotation-major blocks of every tooth; each block carries the torque (P R = T)
    P = frame.tangential_force_N.to_numpy().reshape(swept.angles_deg.size, res.teeth)
    carried = P.sum(axis=1) * res.spec.tooth.pitch_radius * 1e-3
    np.testing.assert_allclose(carried, res.torque_Nm, rtol=1e-6)


def test_capacity_and_curve_dataframes_are_capacity_csv(renzo, tmp_path):
    curve = gc.capacity_curve(renzo, [0.0, 0.5, 1.0])
    frame = curve.to_dataframe()
    same_table(frame, write_capacity_csv({renzo.name: curve}, tmp_path / "capacity.csv"))
    assert frame.misalignment_deg.tolist() == [0.0, 0.5, 1.0]
    one = curve[2].to_dataframe()
    assert len(one) == 1 and one.capacity_Nm.iloc[0] == curve[2].capacity_Nm


def test_inspection_dataframe_is_inspection_csv(renzo, tmp_path, capsys):
    scan = tmp_path / "scan.xyz"
    np.savetxt(scan, synthetic_hub(renzo, per_flank=120, index_mm={4: 0.01}))
    assert main(["compare", "renzo-1967", str(scan), "-o", str(tmp_path), "--coarse", "none",
                 "--fit-points", "3000"]) == 0
    capsys.readouterr()
    rep = gc.compare_part(renzo, scan, coarse="none", fit_points=3000)
    frame = rep.to_dataframe()
    same_table(frame, tmp_path / "inspection.csv", comment="#")
    assert len(frame) == renzo.tooth.teeth


@pytest.mark.needs_dask
@pytest.mark.slow
def test_study_dataframe_is_the_parquet_table(tmp_path):
    study = tmp_path / "s.toml"
    study.write_text('[study]\nbase = "renzo-1967"\noutputs = ["min_backlash_mm"]\n'
                     '[accuracy]\nsteps = 2\n[[vary]]\nkey = "misalignment_deg"\n'
                     'values = [0.0, 1.0]\n')
    run = gc.run_study(gc.load_study(study), tmp_path / "out", workers=1)
    frame = run.to_dataframe()
    same_table(frame, run.table)
    assert frame.misalignment_deg.tolist() == [0.0, 1.0]
    assert frame.min_backlash_mm.iloc[1] < frame.min_backlash_mm.iloc[0]


def test_without_pandas_the_error_names_the_extra(swept, monkeypatch):
    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas raises ImportError
    with pytest.raises(gc.BackendError, match=r"gearcoupling\[pandas\]"):
        swept.to_dataframe()
