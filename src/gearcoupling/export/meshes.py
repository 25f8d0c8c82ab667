"""Mesh writers, each checked by the format's own client in the tests.

- STL (binary), PLY, OBJ through trimesh; millimetres, ``z`` the coupling axis.
- GLB (glTF 2.0, metres and ``+Y`` up by the standard): scaled by 1/1000 and turned so the
  coupling axis ``z`` is ``+Y`` (``(x, y, z) -> (x, z, -y)``), smooth normals split at
  edges sharper than 30°; the glTF validator reports no error.
- 3MF: core-spec XML written here (millimetres), read by lib3mf in strict mode.
- VTU and legacy VTK: cell data ``kind`` (codes into
  :data:`~gearcoupling.parts.SURFACE_KINDS`) and ``tooth`` (``-1`` off the teeth) as
  32-bit integers, and field data naming the kinds (one integer array per kind, named by
  the kind, holding its code); read by VTK.
- Gmsh MSH 4.1 (ASCII): one surface entity per (kind, tooth), each in the physical group
  of its kind (``flank_cw``, ...) and of its tooth (``tooth_0``, ...), plus element data
  ``kind`` and ``tooth``; read by gmsh.
- Abaqus/CalculiX INP: a mesh deck of ``S3`` triangles (node set ``NALL``, element set
  ``EALL``, one element set per kind ``FLANK_CW``, ... and per tooth ``TOOTH_0``, ...),
  numbers in fields of at most 20 characters; include it in an analysis deck
  (``*INCLUDE, INPUT=hub.inp``) and add a material and ``*SHELL SECTION``: ``ccx`` runs it.
"""

from __future__ import annotations

import io
import zipfile
from pathlib import Path
from typing import cast

import numpy as np
from numpy.typing import NDArray

from ..io import (
    inp_comment,
    inp_element_lines,
    inp_id_lines,
    inp_node_lines,
    vtk_header,
    xml_text,
)
from ..parts import SURFACE_KINDS
from .job import PartJob

GLB_FROM_MM = np.array([[1e-3, 0, 0, 0], [0, 0, 1e-3, 0], [0, -1e-3, 0, 0], [0, 0, 0, 1.0]])
"""Homogeneous transform from the part frame (mm, ``z`` axis) to the glTF scene (m, Y up)."""
GLB_CREASE_DEG = 30.0
"""Normals are smooth across edges flatter than this, split at sharper ones."""


def _labels(job: PartJob) -> tuple[NDArray, NDArray]:
    """``kind, tooth`` per triangle as int32."""
    attrs = job.mesh.face_attributes
    return (np.asarray(attrs["kind"], dtype=np.int32), np.asarray(attrs["tooth"], dtype=np.int32))


def write_stl(job: PartJob, path: Path) -> None:
    """Binary STL (millimetres)."""
    job.mesh.export(str(path), file_type="stl")


def write_ply(job: PartJob, path: Path) -> None:
    """Binary PLY (millimetres)."""
    job.mesh.export(str(path), file_type="ply")


def write_obj(job: PartJob, path: Path) -> None:
    """Wavefront OBJ (millimetres)."""
    job.mesh.export(str(path), file_type="obj")


def write_glb(job: PartJob, path: Path) -> None:
    """Binary glTF in metres, ``+Y`` up, with normals (see the module docstring)."""
    from trimesh.graph import smooth_shade

    mesh = job.mesh.copy()
    mesh.apply_transform(GLB_FROM_MM)
    shaded = smooth_shade(mesh, angle=np.radians(GLB_CREASE_DEG))
    shaded.export(str(path), file_type="glb", include_normals=True)


def _xml_rows(fmt: str, rows: NDArray) -> str:
    buf = io.StringIO()
    np.savetxt(buf, rows, fmt=fmt)
    return buf.getvalue()


def write_3mf(job: PartJob, path: Path) -> None:
    """3MF core model (millimetres): one mesh object, one build item."""
    mesh = job.mesh
    core = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"
    vertices = _xml_rows('<vertex x="%.9g" y="%.9g" z="%.9g"/>', np.asarray(mesh.vertices))
    triangles = _xml_rows('<triangle v1="%d" v2="%d" v3="%d"/>', np.asarray(mesh.faces))
    model = (f'<?xml version="1.0" encoding="UTF-8"?>\n'
             f'<model unit="millimeter" xml:lang="en-US" xmlns="{core}">\n'
             f'<metadata name="Title">{xml_text(job.title)}</metadata>\n'
             f'<metadata name="Application">gearcoupling</metadata>\n'
             f'<resources>\n<object id="1" type="model" name="{job.part}">\n<mesh>\n'
             f'<vertices>\n{vertices}</vertices>\n<triangles>\n{triangles}</triangles>\n'
             f'</mesh>\n</object>\n</resources>\n'
             f'<build>\n<item objectid="1"/>\n</build>\n</model>\n')
    types = ('<?xml version="1.0" encoding="UTF-8"?>\n<Types xmlns="http://schemas.openxmlformats'
             '.org/package/2006/content-types"><Default Extension="rels" ContentType='
             '"application/vnd.openxmlformats-package.relationships+xml"/><Default Extension='
             '"model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>'
             '</Types>\n')
    rels = ('<?xml version="1.0" encoding="UTF-8"?>\n<Relationships xmlns="http://schemas.'
            'openxmlformats.org/package/2006/relationships"><Relationship Target='
            '"/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/'
            '2013/01/3dmodel"/></Relationships>\n')
    with zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED) as z:
        z.writestr("[Content_Types].xml", types)
        z.writestr("_rels/.rels", rels)
        z.writestr("3D/3dmodel.model", model)


def _kind_field_data() -> dict[str, NDArray]:
    return {name: np.array([code], dtype=np.int32) for code, name in enumerate(SURFACE_KINDS)}


def write_vtu(job: PartJob, path: Path) -> None:
    """VTK XML unstructured grid (zlib-compressed binary) with labels and kind names."""
    import meshio

    kind, tooth = _labels(job)
    mesh = meshio.Mesh(np.asarray(job.mesh.vertices, dtype=float),
                       [("triangle", np.asarray(job.mesh.faces, dtype=np.int64))],
                       cell_data={"kind": [kind], "tooth": [tooth]})
    mesh.write(str(path), file_format="vtu")
    # meshio writes no <FieldData>: add it (ASCII) as the first child of the grid
    arrays = "".join(f'<DataArray type="Int32" Name="{name}" NumberOfTuples="1" '
                     f'format="ascii">{int(code[0])}</DataArray>\n'
                     for name, code in _kind_field_data().items())
    text = path.read_text()
    head, sep, tail = text.partition("<UnstructuredGrid>\n")
    if not sep:
        raise RuntimeError("meshio's VTU layout changed: no <UnstructuredGrid> line")
    path.write_text(f"{head}{sep}<FieldData>\n{arrays}</FieldData>\n{tail}")


def write_vtk(job: PartJob, path: Path) -> None:
    """Legacy VTK 4.2 (binary, big-endian) with labels and kind names."""
    mesh = job.mesh
    kind, tooth = _labels(job)
    pts = np.asarray(mesh.vertices, dtype=">f8")
    faces = np.asarray(mesh.faces)
    m = len(faces)
    cells = np.column_stack([np.full(m, 3), faces]).astype(">i4")
    fields = _kind_field_data()
    with open(path, "wb") as fh:
        fh.write(f"# vtk DataFile Version 4.2\n{vtk_header(f'{job.title} (mm)')}\nBINARY\n"
                 f"DATASET UNSTRUCTURED_GRID\nFIELD FieldData {len(fields)}\n".encode())
        for name, code in fields.items():
            fh.write(f"{name} 1 1 int\n".encode())
            fh.write(code.astype(">i4").tobytes() + b"\n")
        fh.write(f"POINTS {len(pts)} double\n".encode() + pts.tobytes() + b"\n")
        fh.write(f"CELLS {m} {4 * m}\n".encode() + cells.tobytes() + b"\n")
        fh.write(f"CELL_TYPES {m}\n".encode() + np.full(m, 5, dtype=">i4").tobytes() + b"\n")
        fh.write(f"CELL_DATA {m}\n".encode())
        for name, values in (("kind", kind), ("tooth", tooth)):
            fh.write(f"SCALARS {name} int 1\nLOOKUP_TABLE default\n".encode())
            fh.write(values.astype(">i4").tobytes() + b"\n")


def _msh_entities(kind: NDArray, tooth: NDArray) -> tuple[NDArray, NDArray]:
    """Surface entities: unique ``(kind, tooth)`` pairs ``(E, 2)`` and each face's index."""
    pairs, entity = np.unique(np.column_stack([kind, tooth]), axis=0, return_inverse=True)
    return pairs, entity.ravel()


def msh_group_names(kind: NDArray, tooth: NDArray) -> dict[int, str]:
    """Physical tag -> name of the groups a mesh gets: kinds ``code + 1``, then teeth."""
    n_kinds = len(SURFACE_KINDS)
    names = {code + 1: name for code, name in enumerate(SURFACE_KINDS) if np.any(kind == code)}
    names.update({n_kinds + 1 + int(k): f"tooth_{int(k)}" for k in np.unique(tooth[tooth >= 0])})
    return names


def write_msh(job: PartJob, path: Path) -> None:
    """Gmsh MSH 4.1 (ASCII) with entities and named physical groups per kind and tooth."""
    mesh = job.mesh
    kind, tooth = _labels(job)
    pts = np.asarray(mesh.vertices, dtype=float)
    faces = np.asarray(mesh.faces, dtype=np.int64)
    pairs, entity = _msh_entities(kind, tooth)
    groups = msh_group_names(kind, tooth)
    n_kinds = len(SURFACE_KINDS)
    # every node is classified on the first entity that uses it
    owner = np.full(len(pts), len(pairs), dtype=np.int64)
    np.minimum.at(owner, faces.ravel(), np.repeat(entity, 3))
    out = io.StringIO()
    out.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n")
    out.write(f"$PhysicalNames\n{len(groups)}\n")
    out.writelines(f'2 {tag} "{name}"\n' for tag, name in groups.items())
    out.write("$EndPhysicalNames\n$Entities\n")
    out.write(f"0 0 {len(pairs)} 0\n")
    by_face = np.argsort(entity, kind="stable")
    face_blocks = np.split(by_face, np.searchsorted(entity[by_face], np.arange(1, len(pairs))))
    by_node = np.argsort(owner, kind="stable")
    node_blocks = np.split(by_node, np.searchsorted(owner[by_node], np.arange(1, len(pairs))))
    for e, ((k, t), idx) in enumerate(zip(pairs, face_blocks, strict=True)):
        box = pts[faces[idx].ravel()]
        tags = [k + 1] if t < 0 else [k + 1, n_kinds + 1 + t]
        lo, hi = box.min(axis=0), box.max(axis=0)
        out.write(f"{e + 1} {lo[0]:.17g} {lo[1]:.17g} {lo[2]:.17g} {hi[0]:.17g} {hi[1]:.17g} "
                  f"{hi[2]:.17g} {len(tags)} {' '.join(map(str, tags))} 0\n")
    out.write("$EndEntities\n$Nodes\n")
    used = [(e, nodes) for e, nodes in enumerate(node_blocks) if nodes.size]
    out.write(f"{len(used)} {len(pts)} 1 {len(pts)}\n")
    for e, nodes in used:
        out.write(f"2 {e + 1} 0 {nodes.size}\n")
        np.savetxt(out, nodes + 1, fmt="%d")
        np.savetxt(out, pts[nodes], fmt="%.17g")
    out.write("$EndNodes\n$Elements\n")
    out.write(f"{len(pairs)} {len(faces)} 1 {len(faces)}\n")
    for e, idx in enumerate(face_blocks):
        out.write(f"2 {e + 1} 2 {idx.size}\n")
        np.savetxt(out, np.column_stack([idx + 1, faces[idx] + 1]), fmt="%d")
    out.write("$EndElements\n")
    for name, values in (("kind", kind), ("tooth", tooth)):
        out.write(f'$ElementData\n1\n"{name}"\n1\n0\n3\n0\n1\n{len(faces)}\n')
        # in the order of the element blocks (readers such as meshio ignore the tags)
        np.savetxt(out, np.column_stack([by_face + 1, values[by_face]]), fmt="%d")
        out.write("$EndElementData\n")
    path.write_text(out.getvalue())


def write_inp(job: PartJob, path: Path) -> None:
    """Abaqus/CalculiX mesh deck: S3 triangles and element sets per kind and tooth."""
    mesh = job.mesh
    kind, tooth = _labels(job)
    lines = [inp_comment(f"gearcoupling {job.title}: surface mesh in mm, S3 triangles"),
             "** element sets per surface kind and per tooth. Add a material and *SHELL "
             "SECTION to run."]
    lines += inp_node_lines(np.asarray(mesh.vertices, dtype=float))
    lines += inp_element_lines(np.asarray(mesh.faces, dtype=np.int64), "S3")
    for code, name in enumerate(SURFACE_KINDS):
        if np.any(kind == code):
            lines += [f"*ELSET, ELSET={name.upper()}", *inp_id_lines(np.flatnonzero(kind == code)
                                                                     + 1)]
    for k in np.unique(tooth[tooth >= 0]):
        lines += [f"*ELSET, ELSET=TOOTH_{int(k)}", *inp_id_lines(np.flatnonzero(tooth == k) + 1)]
    path.write_text("\n".join(lines) + "\n")


def read_mesh(path: str | Path):
    """Read a written part back in the part frame (mm, ``z`` axis):
    ``(vertices, faces, cell_data, cell_sets)``.

    For trimesh formats ``cell_data``/``cell_sets`` are empty and vertices are merged.
    """
    import meshio
    import trimesh

    path = Path(path)
    ext = path.suffix.lower().lstrip(".")
    if ext in ("stl", "ply", "obj", "glb", "3mf"):
        m = cast("trimesh.Trimesh", trimesh.load(str(path), force="mesh", file_type=ext))
        if ext == "glb":
            m.apply_transform(np.linalg.inv(GLB_FROM_MM))
            m.merge_vertices(merge_tex=True, merge_norm=True)
        return np.asarray(m.vertices), np.asarray(m.faces), {}, {}
    m = meshio.read(str(path), file_format={"msh": "gmsh", "inp": "abaqus"}.get(ext))
    tri = [c for c in m.cells if c.type == "triangle"]
    faces = np.concatenate([c.data for c in tri])
    data = {k: np.concatenate(v) for k, v in m.cell_data.items()}
    sets = {k: np.concatenate(v) for k, v in m.cell_sets.items()}
    return np.asarray(m.points), faces, data, sets
