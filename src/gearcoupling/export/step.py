"""STEP files of the OpenCASCADE solids of hub and sleeve
(:func:`gearcoupling.parts.part_solid`): AP214, millimetres. OpenCASCADE comes from the
``step`` extra (``cadquery-ocp-novtk``) and is imported at the call.
"""

from __future__ import annotations

import os
import sys
from contextlib import contextmanager
from pathlib import Path

from ..errors import BackendError
from ..interrupts import reraise as reraise_interrupt
from ..io import step_text
from ..parts import check_tolerance, part_solid, shape_volume


def _step_control():
    try:
        from OCP import STEPControl
    except ImportError as err:
        reraise_interrupt(err)  # a signal during the import
        raise BackendError("STEP export needs OpenCASCADE: pip install 'gearcoupling[step]' "
                           "(cadquery-ocp-novtk)") from err
    return STEPControl


@contextmanager
def _quiet_stdout():
    """Silence OpenCASCADE's C++ messages on file descriptor 1 (they would mix with the
    CLI's list of written files)."""
    sys.stdout.flush()
    try:
        saved = os.dup(1)
    except OSError:  # no real stdout (embedded interpreter)
        yield
        return
    with open(os.devnull, "w") as null:
        os.dup2(null.fileno(), 1)
        try:
            yield
        finally:
            os.dup2(saved, 1)
            os.close(saved)


def write_step(shape, path: str | Path, *, name: str = "part") -> Path:
    """Write an OpenCASCADE shape to a STEP file (AP214, millimetres), its product named
    ``name`` in printable ASCII (:func:`~gearcoupling.io.step_text`)."""
    step = _step_control()
    from OCP.IFSelect import IFSelect_ReturnStatus
    from OCP.Interface import Interface_Static

    step.STEPControl_Controller.Init_s()
    Interface_Static.SetCVal_s("write.step.unit", "MM")
    Interface_Static.SetCVal_s("write.step.schema", "AP214IS")
    Interface_Static.SetCVal_s("write.step.product.name", step_text(name))
    # no 2-D parameter curves: readers rebuild them from the 3-D edges and surfaces
    Interface_Static.SetIVal_s("write.surfacecurve.mode", 0)
    with _quiet_stdout():
        writer = step.STEPControl_Writer()
        writer.Transfer(shape, step.STEPControl_StepModelType.STEPControl_AsIs)
        status = writer.Write(str(path))
    if status != IFSelect_ReturnStatus.IFSelect_RetDone:
        raise BackendError(f"OpenCASCADE could not write {path}")
    return Path(path)


def write_step_assembly(parts, path: str | Path, *, name: str = "assembly") -> Path:
    """Write OpenCASCADE shapes as one STEP assembly (AP214, millimetres) named ``name``:
    ``parts`` are ``(name, shape, placement)``, ``placement`` a ``(4, 4)`` rigid transform
    (mm) of the shape's own frame. Each shape is a product of its own name (printable ASCII,
    :func:`~gearcoupling.io.step_text`) placed by its component's location (XCAF), so a
    reader finds every part by name where it was placed (a shape given twice is written
    twice, each copy its own product)."""
    step = _step_control()
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Copy
    from OCP.gp import gp_Trsf
    from OCP.IFSelect import IFSelect_ReturnStatus
    from OCP.Interface import Interface_Static
    from OCP.STEPCAFControl import STEPCAFControl_Writer
    from OCP.TCollection import TCollection_ExtendedString
    from OCP.TDataStd import TDataStd_Name
    from OCP.TDocStd import TDocStd_Document
    from OCP.TopLoc import TopLoc_Location
    from OCP.XCAFDoc import XCAFDoc_DocumentTool

    step.STEPControl_Controller.Init_s()
    Interface_Static.SetCVal_s("write.step.unit", "MM")
    Interface_Static.SetCVal_s("write.step.schema", "AP214IS")
    Interface_Static.SetIVal_s("write.surfacecurve.mode", 0)
    doc = TDocStd_Document(TCollection_ExtendedString("XmlOcaf"))
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    top = tool.NewShape()
    TDataStd_Name.Set_s(top, TCollection_ExtendedString(step_text(name)))
    seen: list = []
    for label, shape, placement in parts:
        m = [[float(v) for v in row] for row in placement]
        trsf = gp_Trsf()
        trsf.SetValues(*m[0], *m[1], *m[2])
        if any(shape.IsSame(other) for other in seen):
            shape = BRepBuilderAPI_Copy(shape).Shape()
        seen.append(shape)
        part = tool.AddShape(shape, False)
        TDataStd_Name.Set_s(part, TCollection_ExtendedString(step_text(label)))
        component = tool.AddComponent(top, part, TopLoc_Location(trsf))
        TDataStd_Name.Set_s(component, TCollection_ExtendedString(step_text(label)))
    tool.UpdateAssemblies()
    with _quiet_stdout():
        writer = STEPCAFControl_Writer()
        writer.SetNameMode(True)
        writer.Transfer(doc, step.STEPControl_StepModelType.STEPControl_AsIs)
        status = writer.Write(str(path))
    if status != IFSelect_ReturnStatus.IFSelect_RetDone:
        raise BackendError(f"OpenCASCADE could not write {path}")
    return Path(path)


def read_step_volume(path: str | Path) -> float:
    """Volume (mm³) of the solids in a STEP file, read back with OpenCASCADE."""
    step = _step_control()
    from OCP.IFSelect import IFSelect_ReturnStatus

    with _quiet_stdout():
        reader = step.STEPControl_Reader()
        status = reader.ReadFile(str(path))
        if status == IFSelect_ReturnStatus.IFSelect_RetDone:
            reader.TransferRoots()
    if status != IFSelect_ReturnStatus.IFSelect_RetDone:
        raise BackendError(f"OpenCASCADE could not read {path}")
    return shape_volume(reader.OneShape())


def write_step_job(job, path: Path) -> None:
    """STEP AP214 B-spline solid of the part (``step`` extra)."""
    tol = check_tolerance(job.spec, job.tolerance_mm)
    shape = part_solid(job.spec, job.part, tol, job.teeth)
    write_step(shape, path, name=job.title)


__all__ = ["read_step_volume", "write_step", "write_step_assembly", "write_step_job"]
