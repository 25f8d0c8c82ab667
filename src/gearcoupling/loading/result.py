"""The frozen result of a loaded-contact analysis, its summary and its long-form rows."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..io import write_csv_rows
from ..tables import dataframe
from .contact import REGIMES
from .summary import summarise

CSV_COLUMNS = ("theta_deg", "tooth", "flank", "gap_angle_deg", "deflection_mm",
               "tangential_force_N", "normal_force_N", "contact_z_mm", "contact_r_mm",
               "max_pressure_MPa", "interior_pressure_MPa", "edge_load_share", "patch_length_mm",
               "patch_width_mm", "edge_contact", "contact_regime", "root_stress_MPa")


@dataclass(frozen=True, eq=False)
class LoadResult:
    """Loads of every tooth on the loaded flank over a set of rotations.

    Arrays ``(N, M)`` are indexed ``(tooth, angle)`` for the loaded flank
    (``loaded_flank``: ``ccw`` for positive torque, ``cw`` for negative). Forces are
    magnitudes (N): ``tangential_force_N`` at the pitch radius (Renzo's ``P``),
    ``normal_force_N`` along the flank normal. ``deflection_mm`` is the closure
    ``R (dpsi - g_k)`` at the pitch circle. ``windup_rad`` is signed like the torque.
    ``contact_regime`` indexes :data:`REGIMES`; ``root_stress_MPa`` the larger root bending
    stress of hub and sleeve tooth. ``pressure_fields``: a model that solves a pressure
    grid (``surface``) keeps each rotation's solved grid here for
    :func:`~gearcoupling.loading.patch_maps` (a dict per rotation: the solved ``teeth``,
    their cells ``z_mm`` and ``s_mm``, ``mask`` on the flank and ``pressure_MPa``), else
    None.
    """

    spec: Any = field(repr=False)
    misalignment_deg: float
    torque_Nm: float
    model: str
    loaded_flank: str
    angles_deg: NDArray[np.float64]
    theta_deg: NDArray[np.float64]
    windup_rad: NDArray[np.float64]
    gap_angle_rad: NDArray[np.float64]
    deflection_mm: NDArray[np.float64]
    tangential_force_N: NDArray[np.float64]
    normal_force_N: NDArray[np.float64]
    contact_z_mm: NDArray[np.float64]
    contact_r_mm: NDArray[np.float64]
    max_pressure_MPa: NDArray[np.float64]
    interior_pressure_MPa: NDArray[np.float64]
    edge_load_share: NDArray[np.float64]
    patch_length_mm: NDArray[np.float64]
    patch_width_mm: NDArray[np.float64]
    edge_contact: NDArray[np.bool_]
    contact_regime: NDArray[np.int8]
    root_stress_MPa: NDArray[np.float64]
    mesh_stiffness_Nm_per_rad: NDArray[np.float64]  # (M,) dT/d(dpsi) at the load
    pressure_fields: tuple[dict[str, Any], ...] | None = field(default=None, repr=False)

    @property
    def teeth(self) -> int:
        return int(self.theta_deg.shape[0])

    @property
    def in_contact(self) -> NDArray[np.bool_]:
        """``(N, M)`` teeth carrying load."""
        return self.tangential_force_N > 0

    def q(self) -> float:
        """Renzo's load proportion ``T / (R N P_max)``; at zero torque its small-load limit
        (teeth sharing the smallest gap at the worst rotation, over N)."""
        R = self.spec.tooth.pitch_radius
        p_max = float(np.max(self.tangential_force_N))
        if p_max > 0:
            return abs(self.torque_Nm) * 1e3 / (R * self.teeth * p_max)
        g = self.gap_angle_rad
        ties = np.sum(g <= np.min(g, axis=0) + 1e-12, axis=0)
        return float(np.min(ties)) / self.teeth

    def summary(self) -> dict[str, Any]:
        """The ``load_summary.json`` keys, plain data with units in the keys."""
        return summarise(self)

    def write_csv(self, path):
        """Write :meth:`rows` under :data:`CSV_COLUMNS` atomically; returns the path."""
        return write_csv_rows(path, CSV_COLUMNS, self.rows())

    def to_dataframe(self):
        """:meth:`rows` as a pandas DataFrame with the columns of ``load.csv``
        (:data:`CSV_COLUMNS`; the ``pandas`` extra)."""
        return dataframe(CSV_COLUMNS, self.rows())

    def rows(self):
        """Long-form rows (tuples in :data:`CSV_COLUMNS` order), tooth-major per angle."""
        g_deg = np.degrees(self.gap_angle_rad)
        for j in range(self.angles_deg.size):
            for k in range(self.teeth):
                yield (float(self.theta_deg[k, j]), k, self.loaded_flank, float(g_deg[k, j]),
                       float(self.deflection_mm[k, j]), float(self.tangential_force_N[k, j]),
                       float(self.normal_force_N[k, j]), float(self.contact_z_mm[k, j]),
                       float(self.contact_r_mm[k, j]), float(self.max_pressure_MPa[k, j]),
                       float(self.interior_pressure_MPa[k, j]),
                       float(self.edge_load_share[k, j]), float(self.patch_length_mm[k, j]),
                       float(self.patch_width_mm[k, j]), bool(self.edge_contact[k, j]),
                       REGIMES[int(self.contact_regime[k, j])],
                       float(self.root_stress_MPa[k, j]))


