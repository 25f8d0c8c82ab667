"""Frozen outputs of the sweep kernel, to pin its speed-ups to the kernel they replace.

``tests/golden/sweep_kernel.npz`` holds, per template and misalignment (0, 1, 3, 6°), the
minima of tooth 0's cw flank (:func:`~gearcoupling.clearance.tooth_map.flank_minima`,
``periodic=False``, default tolerance) at :data:`THETA_DEG`, computed with the kernel of
main on 2026-11-23 (commit 6466353, before the sweep-speed changes). Regenerate only after
an intended change of the kernel's results: ``PYTHONPATH=src python tests/golden_sweep_kernel.py``
and review why the values moved.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from gearcoupling.clearance.tooth_map import flank_minima
from gearcoupling.spec import load_spec

FILE = Path(__file__).parent / "golden" / "sweep_kernel.npz"
TEMPLATES = ("renzo-1967", "renzo-1967-end-round", "renzo-1967-vari-crown", "industrial-m2",
             "mill-spindle")
MISALIGNMENTS_DEG = (0.0, 1.0, 3.0, 6.0)
THETA_DEG = np.linspace(0.0, 360.0, 97)[:-1] + 0.37  # 96 turning angles, off the symmetries
KEYS = ("clearance", "normal", "pitch", "pitch_normal", "z", "r", "kind")


def minima(name: str, mis_deg: float) -> dict[str, np.ndarray]:
    """The kernel's minima of ``name`` at ``mis_deg`` (arrays ``(96,)``)."""
    out, _ = flank_minima(load_spec(name), math.radians(mis_deg), np.radians(THETA_DEG),
                          tolerance_mm=1e-7, periodic=False)
    return {k: out[k] for k in KEYS}


def main() -> None:
    data = {f"{name}|{deg:g}|{k}": v for name in TEMPLATES for deg in MISALIGNMENTS_DEG
            for k, v in minima(name, deg).items()}
    np.savez_compressed(FILE, **data)
    print(f"wrote {FILE} ({len(data)} arrays)")


if __name__ == "__main__":
    main()
