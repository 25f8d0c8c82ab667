"""``gearcoupling load``: load sharing, pressures and machine loads of every tooth over a turn."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..atomic import write_json
from ..errors import SpecError
from ..loadspec import LOAD_MODELS
from .common import (
    MAX_ANGLES,
    add_misalignment_argument,
    add_spec_arguments,
    count,
    misalignment_deg,
    number_in,
    output_dir,
    positive_length,
    progress,
    progress_callback,
    spec_from_args,
)

MAX_TORQUE_NM = 1e9  # far above any coupling; beyond ~1e150 the contact law overflows


def register(sub) -> None:
    p = sub.add_parser("load", help="tooth loads, contact pressure, wind-up and machine loads "
                       "over a turn under torque (load.csv, load_summary.json, plots)")
    add_spec_arguments(p)
    add_misalignment_argument(p)
    p.add_argument("--model", choices=LOAD_MODELS, default=None,
                   help="load model (default: the spec's [load] model)")
    p.add_argument("--torque", type=number_in(-MAX_TORQUE_NM, MAX_TORQUE_NM, "N·m"),
                   default=None, metavar="NM",
                   help=f"torque in N·m, |T| <= {MAX_TORQUE_NM:g}; the sign picks the loaded "
                        "flank; write a negative one as --torque=-5e3 (default: the spec's)")
    p.add_argument("--angles", type=count(1, MAX_ANGLES), default=360, metavar="N",
                   help=f"rotations over one turn, 1-{MAX_ANGLES} (default 360)")
    p.add_argument("--tolerance", type=positive_length, default=1e-7, metavar="MM",
                   help="sweep accuracy of every gap in mm, > 0 (default 1e-7)")
    p.add_argument("--no-plots", action="store_true", help="write only the CSV and JSON")
    p.add_argument("--quick-plots", action="store_true",
                   help="only the tooth-load and patch plots (skip the misalignment studies)")
    p.set_defaults(func=run)


def study_misalignments(spec, count: int = 7) -> np.ndarray:
    """Misalignments of the studies: 0 to the design angle (at least 0.5°), 0 left out."""
    top = max(math.degrees(spec.design_misalignment), 0.5)
    return np.linspace(top / count, top, count)


def studies(spec, torque_Nm: float, model: str | None, out: Path) -> list[Path]:
    """Wei Figs. 12-13 and Renzo's q-graph (Fig. 12) for the spec, over one tooth pitch."""
    from ..clearance import sweep
    from ..loading import load_from_sweep
    from ..loading.capacity import capacity_from_sweep, default_angles
    from ..loading.plots import plot_q_graph, plot_vs_misalignment
    from ..plots import save_figure

    mis = study_misalignments(spec)
    torques = [0.5 * torque_Nm, torque_Nm, 2.0 * torque_Nm]
    peak: dict[str, list[float]] = {f"T = {t:.4g} N·m": [] for t in torques}
    moment: dict[str, list[float]] = {f"T = {t:.4g} N·m": [] for t in torques}
    q_pts: list[tuple[float, float]] = []
    ld = spec.load
    with progress("load studies", mis.size) as advance:
        for i in mis:
            sw = sweep(spec, float(i), default_angles(spec, None))
            for t, key in zip(torques, peak, strict=True):
                res = load_from_sweep(sw, torque_Nm=t, model=model)
                peak[key].append(float(np.max(res.tangential_force_N)))
                moment[key].append(res.summary()["tilting_moment_Nm"]["mean"])
            if ld.allowable_tooth_load_N is not None and ld.mesh_stiffness_N_per_mm is not None:
                c = capacity_from_sweep(sw, model="linear")
                rc = spec.derived["crowning_radius_midplane_mm"]
                z0 = 0.5 * rc * math.tan(math.radians(i)) ** 2 / math.tan(spec.tooth.pressure_angle)
                zc = ld.allowable_tooth_load_N / ld.mesh_stiffness_N_per_mm
                if z0 > 0 and c.criteria_Nm["tooth_load"] and c.aligned_capacity_Nm:
                    q_pts.append((zc / z0, c.criteria_Nm["tooth_load"]
                                  / c.aligned_capacity_Nm))
            advance(f"load studies i = {i:.3g}°")
    label = model or spec.load.model
    paths = [
        save_figure(plot_vs_misalignment(mis, dict(peak), "max tooth load P (N)",
                                         f"{spec.name}: {label}, max tooth load"),
                    out / "load_max_vs_misalignment.png"),
        save_figure(plot_vs_misalignment(mis, dict(moment), "additional (tilting) moment (N·m)",
                                         f"{spec.name}: {label}, mean over the turn"),
                    out / "load_moment_vs_misalignment.png"),
    ]
    if q_pts:
        paths.append(save_figure(plot_q_graph({"linear model, exact geometry": q_pts}),
                                 out / "load_q_graph.png"))
    return paths


def load_files(spec, out: Path, misalignment_deg: float, angles: int, *,
               torque_Nm: float | None = None, model: str | None = None,
               tolerance_mm: float = 1e-7, plots: bool = True,
               with_studies: bool = True) -> list[Path]:
    """Run the loaded analysis and write ``load.csv``, ``load_summary.json`` and plots."""
    from ..loading import load
    from ..loading.inputs import resolve_torque_Nm

    if angles < 1:
        raise SpecError("--angles", angles, "must be at least 1")
    psi = np.arange(angles) * 360.0 / angles
    with progress_callback(f"load ({model or spec.load.model} model)") as advance:
        res = load(spec, misalignment_deg, psi, torque_Nm=torque_Nm, model=model,
                   tolerance_mm=tolerance_mm, progress=advance)
    summary = res.summary()
    paths = [res.write_csv(out / "load.csv"), write_json(out / "load_summary.json", summary)]
    if plots:
        from ..loading.plots import plot_patches, plot_tooth_load
        from ..plots import save_figure

        paths.append(save_figure(plot_tooth_load(res), out / "load_tooth_load.png"))
        paths.append(save_figure(plot_patches(res), out / "load_patches.png"))
        if with_studies:
            paths += studies(spec, resolve_torque_Nm(spec, torque_Nm), model, out)
    return paths


def run(args) -> int:
    spec = spec_from_args(args)
    mis = misalignment_deg(args, spec)
    out = output_dir(args, spec)
    for path in load_files(spec, out, mis, args.angles, torque_Nm=args.torque, model=args.model,
                           tolerance_mm=args.tolerance, plots=not args.no_plots,
                           with_studies=not args.quick_plots):
        print(path)
    return 0
