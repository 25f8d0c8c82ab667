"""Read a measured part: a mesh (STL/PLY/OBJ, its vertices) or a point cloud (CSV/PLY/XYZ)."""

from __future__ import annotations

import warnings
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import ArgumentError, BackendError
from ..interrupts import reraise as reraise_interrupt
from ..io import require_file

MESH_SUFFIXES = (".stl", ".obj", ".ply", ".off", ".glb")
TEXT_SUFFIXES = (".csv", ".xyz", ".txt", ".asc", ".pts")
UNIT_SCALE = {"mm": 1.0, "in": 25.4, "m": 1000.0}
#: the largest coordinate of a scan in mm (1 km, beyond any coupling): the registration
#: squares and sums coordinates, which overflow past about 1e150 mm
MAX_COORDINATE_MM = 1e6
ALLOWED = ("an existing, readable mesh (.stl .obj .ply .off .glb: its vertices are used) or "
           "point cloud (.csv .xyz .txt .asc .pts: x y z columns; .ply vertices)")


def load_points(path: str | Path, units: str = "mm") -> NDArray[np.float64]:
    """Points of a scan or mesh file, in mm.

    Parameters
    ----------
    path : str or Path
    units : {"mm", "in", "m"}
        Length unit of the file's coordinates.

    Returns
    -------
    (n, 3) float
        Finite points (mm); a file with no points or with non-finite coordinates is refused
        (:class:`SpecError`).
    """
    if units not in UNIT_SCALE:
        raise ArgumentError("units", units, f"one of {tuple(UNIT_SCALE)}")
    p = require_file(path, "file", ALLOWED, ArgumentError)
    suffix = p.suffix.lower()
    if suffix in MESH_SUFFIXES:
        pts = _load_mesh(p)
    elif suffix in TEXT_SUFFIXES:
        pts = _load_text(p)
    else:
        raise ArgumentError("file", str(p), ALLOWED)
    if pts.ndim != 2 or pts.shape[1] != 3 or len(pts) == 0:
        raise ArgumentError("file", str(p), "a file with at least one x y z point; it has none")
    bad = ~np.all(np.isfinite(pts), axis=1)
    if np.any(bad):
        raise ArgumentError("file", str(p), f"finite coordinates; {int(bad.sum())} of {len(pts)} "
                        f"points have NaN or infinity (first at row {int(np.argmax(bad))}): "
                        "remove them from the scan")
    pts = pts * UNIT_SCALE[units]
    check_magnitude(pts, "file", str(p))
    return pts


def check_magnitude(pts: NDArray[np.float64], field: str, value: object) -> None:
    """Refuse finite points ``(n, 3)`` in mm with a coordinate beyond
    :data:`MAX_COORDINATE_MM`, naming the first one's row and column."""
    big = np.abs(pts) > MAX_COORDINATE_MM
    if np.any(big):
        row, col = (int(k) for k in np.argwhere(big)[0])
        raise ArgumentError(field, value, f"coordinates within ±{MAX_COORDINATE_MM:g} mm "
                            f"({MAX_COORDINATE_MM / 1e6:g} km); points beyond: "
                            f"{int(big.any(axis=1).sum())} of {len(pts)}, the first at row "
                            f"{row}, column {'xyz'[col]} = {pts[row, col]:.6g} mm: check the "
                            "file's units and columns")


def _load_mesh(p: Path) -> NDArray[np.float64]:
    try:
        import trimesh
    except ImportError as err:  # pragma: no cover - trimesh is a core dependency
        reraise_interrupt(err)  # a signal during the import
        raise BackendError("reading meshes needs trimesh: pip install trimesh") from err
    try:
        obj = trimesh.load(p, process=False)
    except Exception as err:  # trimesh raises many types on corrupt files
        raise ArgumentError("file", str(p), f"{ALLOWED}; trimesh could not read it "
                        f"({type(err).__name__}: {err})") from err
    if isinstance(obj, trimesh.Scene):
        # trimesh's Geometry declares no vertices; meshes, paths and point clouds all have them
        geoms: list[Any] = list(obj.dump()) if obj.geometry else []
        verts = [np.asarray(g.vertices, dtype=float) for g in geoms]
        return np.concatenate(verts) if verts else np.zeros((0, 3))
    return np.asarray(getattr(obj, "vertices", np.zeros((0, 3))), dtype=float)


def _load_text(p: Path) -> NDArray[np.float64]:
    """numpy's C reader for well-formed files; the line-by-line reader names bad lines."""
    try:
        with p.open(encoding="utf-8") as fh:
            head = [line.strip() for _, line in zip(range(50), fh, strict=False)]
        skip = 0
        for line in head:
            first = line.replace(",", " ").split()[:1]
            if line and line[0] not in "#/;%" and first and _is_number(first[0]):
                break
            skip += 1
        sample = head[skip] if skip < len(head) else ""
        delim = "," if "," in sample else (";" if ";" in sample else None)
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # "no data" and friends: use the line reader
            pts = np.loadtxt(p, delimiter=delim, comments=("#", "//", "%"), skiprows=skip,
                             usecols=(0, 1, 2), ndmin=2, dtype=float)
        return pts.reshape(-1, 3)
    except (ValueError, IndexError, UnicodeDecodeError, OSError, Warning):
        return _load_text_lines(p)


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _load_text_lines(p: Path) -> NDArray[np.float64]:
    rows: list[list[float]] = []
    try:
        with p.open(encoding="utf-8", errors="strict") as fh:
            for line in fh:
                text = line.strip()
                if not text or text[0] in "#/;%":
                    continue
                parts = text.replace(",", " ").replace(";", " ").split()
                try:
                    vals = [float(v) for v in parts[:3]]
                except ValueError:
                    if not rows:
                        continue  # a header line
                    raise ArgumentError("file", str(p), f"numeric x y z columns; line "
                                    f"{text[:60]!r} is not") from None
                if len(vals) < 3:
                    raise ArgumentError("file", str(p), f"three coordinates per line; line "
                                    f"{text[:60]!r} has {len(vals)}")
                rows.append(vals)
    except UnicodeDecodeError as err:
        raise ArgumentError("file", str(p), ALLOWED + "; it is not a text file") from err
    except OSError as err:
        raise ArgumentError("file", str(p), f"{ALLOWED}; reading failed ({err})") from err
    return np.array(rows, dtype=float).reshape(-1, 3)
