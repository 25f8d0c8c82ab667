"""Figures of the data sheet: the wind-up curve and the loads over a turn at the allowable
misalignment."""

from __future__ import annotations

import numpy as np

from ..plots import new_figure


def plot_windup(torsion, title: str = ""):
    """Torque against wind-up (teeth from first touch, and with the bodies), with the secant
    and tangent stiffness at the operating torque."""
    fig, ax = new_figure(figsize=(7.5, 4.5), layout="constrained")
    w = np.abs(torsion.windup_rad) * 1e6
    T = np.abs(torsion.torque_Nm)
    ax.plot(np.abs(torsion.mesh_windup_rad) * 1e6, T, color="C0", lw=1, ls="--",
            label="teeth (from first touch)")
    ax.plot(w, T, color="C0", marker=".", label="teeth and bodies")
    T0 = abs(torsion.operating_torque_Nm)
    w0 = T0 / torsion.secant_Nm_per_rad * 1e6
    ax.plot([0, w0], [0, T0], color="C1", lw=1, label=f"secant {torsion.secant_Nm_per_rad:.4g} "
            "N·m/rad")
    span = 0.25 * w.max()
    ax.plot([w0 - span, w0 + span], [T0 - torsion.tangent_Nm_per_rad * span * 1e-6,
                                     T0 + torsion.tangent_Nm_per_rad * span * 1e-6],
            color="C2", lw=1, label=f"tangent {torsion.tangent_Nm_per_rad:.4g} N·m/rad")
    ax.plot([w0], [T0], "k*", label="operating torque")
    if torsion.capacity_Nm is not None:
        ax.axhline(torsion.capacity_Nm, color="0.5", lw=0.8, ls=":", label="capacity")
    ax.set_xlabel("wind-up (µrad)")
    ax.set_ylabel("torque (N·m)")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=8, loc="best")
    ax.set_title(title, fontsize=10)
    return fig


def plot_allowable_loads(allowable, title: str = ""):
    """Bending moment and axial slip force over the turn at the allowable misalignment.
    The tick labels read as the values (no offset such as "+2.461e2" above the axis, no
    powers of ten); the bending moment, nearly even over the turn, is drawn from 0."""
    fig, (a0, a1) = new_figure(2, 1, figsize=(7.5, 5), sharex=True, layout="constrained")
    psi = allowable.angles_deg
    a0.plot(psi, allowable.bending_moment_Nm, color="C0")
    a0.set_ylabel("bending moment (N·m)")
    top = float(np.max(allowable.bending_moment_Nm, initial=0.0))
    a0.set_ylim(0.0, 1.1 * top if top > 0 else 1.0)  # the line below the frame
    a1.plot(psi, allowable.axial_slip_force_N, color="C1", label="axial slip force")
    a1.plot(psi, allowable.axial_force_N, color="C2", label="thrust along the hub axis")
    a1.plot(psi, allowable.radial_force_N, color="C3", label="radial force")
    a1.set_ylabel("force (N)")
    a1.set_xlabel("rotation ψ (deg)")
    a1.legend(fontsize=8, loc="best")
    a0.set_title(title, fontsize=10)
    for ax in (a0, a1):
        ax.ticklabel_format(axis="y", useOffset=False, style="plain")
    return fig


__all__ = ["plot_allowable_loads", "plot_windup"]
