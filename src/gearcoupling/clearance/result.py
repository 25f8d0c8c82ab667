"""The frozen result of a sweep, its design summary and its long-form rows."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import ArgumentError, GeometryError
from ..geometry import FLANKS, renzo_z0_mm
from ..io import write_csv_columns
from ..tables import dataframe
from .kernel import KINDS, NONE

CSV_COLUMNS = ("theta_deg", "tooth", "flank", "clearance_mm", "normal_clearance_mm",
               "pitch_clearance_mm", "contact_z_mm", "contact_r_mm", "contact_kind")


@dataclass(frozen=True, eq=False)
class SweepResult:
    """Clearance, contact and backlash of every tooth and flank over a set of rotations.

    Arrays indexed ``(flank, tooth, angle)`` use the flank order ``(cw, ccw)``. Clearances
    are in mm, positive = free: ``clearance_mm`` circumferential (``r * dalpha``) and
    ``normal_clearance_mm`` along the sleeve flank normal, each the minimum over the whole
    active flank; ``pitch_clearance_mm`` and ``pitch_normal_clearance_mm`` the minima along
    the hub flank's pitch line. ``contact_z_mm`` and ``contact_r_mm`` locate the point of
    first touch (the minimum of the normal gap) in hub flank coordinates (axial position
    and radius in the hub frame); ``contact_kind`` indexes :data:`KINDS`.

    Attributes
    ----------
    angles_deg : (n_angle,) float
        Rotation ``psi`` of the coupling (degrees).
    theta_deg : (n_tooth, n_angle) float
        Turning angle of each tooth from the tilt axis, in ``[0, 360)``.
    backlash_rad, backlash_mm : (n_angle,) float
        Free turning of the hub about its axis (angle, and arc at the pitch radius).
    """

    spec: Any = field(repr=False)  # the CouplingSpec swept: loads on this sweep use it
    misalignment_deg: float
    teeth: int
    pitch_radius_mm: float
    base_radius_mm: float
    pressure_angle_deg: float
    aligned_backlash_mm: float
    half_face_mm: float
    angles_deg: NDArray[np.float64]
    theta_deg: NDArray[np.float64]
    clearance_mm: NDArray[np.float64]
    normal_clearance_mm: NDArray[np.float64]
    pitch_clearance_mm: NDArray[np.float64]
    pitch_normal_clearance_mm: NDArray[np.float64]
    contact_z_mm: NDArray[np.float64]
    contact_r_mm: NDArray[np.float64]
    contact_kind: NDArray[np.int8]
    backlash_rad: NDArray[np.float64]
    backlash_mm: NDArray[np.float64]
    # (flank, tooth, angle) hub rotation closing each flank, inf where it never touches
    # (``normal / r_b / rate``, first order in the gap); read by gearcoupling.loading
    gap_angle_rad: NDArray[np.float64]
    tolerance_mm: float
    table_error_mm: float
    design: dict[str, Any] = field(default_factory=dict)

    kinds: tuple[str, ...] = KINDS

    @property
    def spec_name(self) -> str:
        return str(self.spec.name)

    def check_finite(self) -> SweepResult:
        """This result, after checking that no value is NaN and that values are infinite
        only where nothing faces the sleeve flank (``"no contact"``); else
        :class:`~gearcoupling.errors.GeometryError` naming the array and a place. Writers
        call it before they write anything."""
        facing = self.contact_kind != NONE
        for name in ("clearance_mm", "normal_clearance_mm", "contact_z_mm", "contact_r_mm",
                     "pitch_clearance_mm", "pitch_normal_clearance_mm", "backlash_mm"):
            a = getattr(self, name)
            bad = np.isnan(a)
            if name in ("clearance_mm", "normal_clearance_mm", "contact_z_mm", "contact_r_mm"):
                bad |= facing & ~np.isfinite(a)
            if np.any(bad):
                where = tuple(int(i) for i in np.argwhere(bad)[0])
                raise GeometryError(f"sweep of {self.spec_name!r} at "
                                    f"{self.misalignment_deg:g}°: {name} is not finite at "
                                    f"index {where} (a kernel fault: please report the spec)")
        return self

    def kind_names(self) -> NDArray[np.str_]:
        """``contact_kind`` as strings, ``(flank, tooth, angle)``."""
        return np.asarray(KINDS)[self.contact_kind]

    def separation(self, which: str = "pitch_normal") -> NDArray[np.float64]:
        """Renzo's separation ``z``: each tooth's clearance minus the smallest of its flank
        at that rotation, ``(flank, tooth, angle)``; ``which`` names the clearance
        (``clearance``, ``normal``, ``pitch`` or ``pitch_normal``)."""
        c = self._measure(which)
        return c - np.min(c, axis=1, keepdims=True)

    def _measure(self, which: str) -> NDArray[np.float64]:
        table = {"clearance": self.clearance_mm, "normal": self.normal_clearance_mm,
                 "pitch": self.pitch_clearance_mm, "pitch_normal": self.pitch_normal_clearance_mm}
        if which not in table:
            raise ArgumentError("measure", which, f"one of {sorted(table)}")
        return table[which]

    def peak_to_peak(self, which: str) -> NDArray[np.float64]:
        """Largest separation per flank over teeth and rotations, ``(2,)`` mm."""
        sep = self.separation(which)
        return np.array([np.max(np.where(np.isfinite(s), s, -np.inf)) for s in sep])

    def contacting_theta_deg(self, which: str = "pitch_normal") -> NDArray[np.float64]:
        """Turning angle of the tooth with the smallest clearance of each flank over all
        teeth and rotations, ``(2,)``, folded into ``(-90, 90]``: the tilt repeats every
        180° of theta, so the teeth at theta and theta + 180° touch alike."""
        c = self._measure(which)
        out = []
        for f in range(2):
            k, j = np.unravel_index(np.argmin(c[f]), c[f].shape)
            th = float(np.mod(self.theta_deg[k, j], 180.0))
            out.append(th - 180.0 if th > 90.0 else th)
        return np.array(out)

    def summary(self) -> dict[str, Any]:
        """Design quantities of this sweep as plain data (units in the keys)."""
        ppn = self.peak_to_peak("pitch_normal")
        ppc = self.peak_to_peak("pitch")
        fn = self.peak_to_peak("normal")
        fc = self.peak_to_peak("clearance")
        th = self.contacting_theta_deg()
        i = math.radians(self.misalignment_deg)
        out: dict[str, Any] = {
            "spec": self.spec_name,
            "misalignment_deg": self.misalignment_deg,
            "angles": int(self.angles_deg.size),
            "teeth": self.teeth,
            "tolerance_mm": self.tolerance_mm,
            "flank_table_error_mm": self.table_error_mm,
            "aligned_backlash_mm": self.aligned_backlash_mm,
            "aligned_backlash_deg": math.degrees(self.aligned_backlash_mm / self.pitch_radius_mm),
            "min_backlash_mm": float(np.min(self.backlash_mm)),
            "min_backlash_deg": math.degrees(float(np.min(self.backlash_rad))),
            "max_backlash_mm": float(np.max(self.backlash_mm)),
            "min_clearance_mm": {f: float(np.min(self.clearance_mm[k]))
                                 for k, f in enumerate(FLANKS)},
            "min_normal_clearance_mm": {f: float(np.min(self.normal_clearance_mm[k]))
                                        for k, f in enumerate(FLANKS)},
            "pitch_line_peak_to_peak_normal_mm": dict(zip(FLANKS, ppn.tolist(), strict=True)),
            "pitch_line_peak_to_peak_circumferential_mm": dict(zip(FLANKS, ppc.tolist(),
                                                                   strict=True)),
            "flank_peak_to_peak_normal_mm": dict(zip(FLANKS, fn.tolist(), strict=True)),
            "flank_peak_to_peak_circumferential_mm": dict(zip(FLANKS, fc.tolist(), strict=True)),
            "contacting_tooth_theta_deg": dict(zip(FLANKS, th.tolist(), strict=True)),
            "contact_kinds": {f: sorted({KINDS[c] for c in np.unique(self.contact_kind[k])})
                              for k, f in enumerate(FLANKS)},
            "max_contact_z_mm": float(np.max(np.abs(self.contact_z_mm))),
            "half_face_mm": self.half_face_mm,
        }
        if self.misalignment_deg > 0:
            out["renzo_z0_mm"] = renzo_z0_mm(self._crown_radius(), i,
                                             math.radians(self.pressure_angle_deg))
            out["renzo_z0_circumferential_mm"] = out["renzo_z0_mm"] / math.cos(
                math.radians(self.pressure_angle_deg))
        out.update(self.design)
        return out

    def _crown_radius(self) -> float:
        return float(self.design.get("crowning_radius_midplane_mm", math.inf))

    def write_csv(self, path):
        """Write :meth:`rows` under :data:`CSV_COLUMNS` atomically; returns the path."""
        return write_csv_columns(path, CSV_COLUMNS, self.columns())

    def columns(self) -> list:
        """The columns of :meth:`rows`, each flattened in their order (angle, tooth,
        flank): floats as arrays, tooth, flank and kind as lists."""
        shape = (2, self.teeth, self.angles_deg.size)

        def flat(a):  # (flank, tooth, angle) -> rows
            return np.broadcast_to(a, shape).transpose(2, 1, 0).ravel()

        names = np.asarray(KINDS)
        return [flat(self.theta_deg[None].astype(float)),
                flat(np.arange(self.teeth)[None, :, None]).tolist(),
                [FLANKS[f] for f in flat(np.arange(2)[:, None, None]).tolist()],
                *(flat(np.asarray(a, dtype=float)) for a in (
                    self.clearance_mm, self.normal_clearance_mm, self.pitch_clearance_mm,
                    self.contact_z_mm, self.contact_r_mm)),
                names[flat(self.contact_kind)].tolist()]

    def to_dataframe(self):
        """:meth:`rows` as a pandas DataFrame with the columns of ``sweep.csv``
        (:data:`CSV_COLUMNS`; the ``pandas`` extra)."""
        return dataframe(CSV_COLUMNS, self.rows())

    def rows(self):
        """Long-form rows (tuples in :data:`CSV_COLUMNS` order), tooth-major per angle."""
        names = np.asarray(KINDS)
        for j in range(self.angles_deg.size):
            for k in range(self.teeth):
                for f, flank in enumerate(FLANKS):
                    yield (float(self.theta_deg[k, j]), k, flank,
                           float(self.clearance_mm[f, k, j]),
                           float(self.normal_clearance_mm[f, k, j]),
                           float(self.pitch_clearance_mm[f, k, j]),
                           float(self.contact_z_mm[f, k, j]), float(self.contact_r_mm[f, k, j]),
                           str(names[self.contact_kind[f, k, j]]))
