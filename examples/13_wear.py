"""Wear over life: Archard wear of the flanks at one operating point, the worn flanks' loads
solved again, and the life to the wear limit with its band across the lubrication regime.

Run: python examples/13_wear.py
"""

from pathlib import Path

import gearcoupling as gc
from gearcoupling.wear import write_wear

# 2000 h at 1°, 2000 N·m, 1800 rpm; a coarse flank grid and one rotation phase keep it short
# (docs/wear.md measures what the defaults buy)
res = gc.wear("renzo-1967", 1.0, 2000.0, 1800.0, 2000.0, grid=(16, 8), phases=1)
assert isinstance(res, gc.WearResult)
lo, hi = res.life_band_h
print(f"{res.steps} steps; backlash {res.backlash_mm[0, 0]:.4f} -> {res.backlash_mm[-1, 0]:.4f}"
      f" mm; largest hub depth {res.hub_max_mm[-1].max() * 1e3:.2f} µm")
print(f"life to the wear limit {res.life_h:.3g} h (band {lo:.3g}-{hi:.3g} h, {res.life_basis})")
print(res.to_dataframe().tail(3))  # wear.csv's rows (the pandas extra)

out = Path("outputs/renzo-1967/wear")
out.mkdir(parents=True, exist_ok=True)
for path in write_wear(res, out):  # wear.csv, wear_depth.csv, wear_summary.json, plots
    print(" ", path)
