"""The viewer's contact-pressure colours: the surface model at the shown pose, computed by
the public ``gc.load`` (the viewer's scene solves nothing)."""

import numpy as np
import pytest

from gearcoupling.clearance import sweep
from gearcoupling.errors import ArgumentError
from gearcoupling.loading.inputs import tooth_compliance
from gearcoupling.loading.models.surface import solve_surface
from gearcoupling.viewer import scene as vs
from gearcoupling.viewer.nodes import pose_loads


def test_pressure_colours_follow_the_surface_model(renzo):
    loads = pose_loads(renzo, 1.0, 0.0)
    st = vs.pose_state(renzo, 1.0, 0.0, loads=loads)
    assert st.pressure_MPa.shape == (2, renzo.tooth.teeth)
    assert np.all(st.pressure_MPa[0] == 0)  # positive torque loads the ccw flanks
    ref = solve_surface(renzo, sweep(renzo, 1.0, [0.0], tolerance_mm=vs.VIEW_SWEEP_TOLERANCE_MM),
                        torque_Nm=renzo.load.torque_Nm, compliance=tooth_compliance(renzo))
    assert np.allclose(st.pressure_MPa[1], ref["interior_pressure_MPa"][:, 0], rtol=1e-9)
    cols = vs.flank_colors(st, "pressure", 0.02, renzo)
    grey = np.all(cols == np.asarray(vs.NO_CONTACT_RGB, np.uint8), axis=-1)
    assert np.array_equal(grey, st.pressure_MPa <= 0)
    # more pressure, redder
    loaded = np.flatnonzero(st.pressure_MPa[1] > 0)
    lo, hi = loaded[np.argmin(st.pressure_MPa[1, loaded])], loaded[np.argmax(
        st.pressure_MPa[1, loaded])]
    assert int(cols[1, hi, 0]) >= int(cols[1, lo, 0])
    entries = vs.legend(0.02, mode="pressure")
    assert entries[-1][0] == "no load" and "allowable" in entries[-2][0]
    # the clearance modes are unchanged by the new one
    assert np.array_equal(vs.flank_colors(st, "clearance", 0.02, renzo),
                          vs.clearance_colors(st.clearance_mm, 0.02))
    assert vs.pose_state(renzo, 1.0, 0.0).pressure_MPa is None
    with pytest.raises(ArgumentError, match="loads"):  # loads of another pose
        vs.pose_state(renzo, 1.0, 5.0, loads=loads)


def test_scene_in_pressure_mode_shows_the_loads_of_gc_load(renzo):
    viser = pytest.importorskip("viser")
    import gearcoupling as gc
    from gearcoupling.viewer.html import free_port
    from gearcoupling.viewer.nodes import CouplingScene, ViewSettings

    server = viser.ViserServer(host="127.0.0.1", port=free_port(), verbose=False)
    try:
        scene = CouplingScene(server, renzo, ViewSettings(misalignment_deg=1.0, psi_deg=10.0,
                                                          color_mode="pressure"))
        ref = gc.load(renzo, 1.0, [10.0], model="surface",
                      tolerance_mm=vs.VIEW_SWEEP_TOLERANCE_MM)
        assert np.array_equal(scene.state.pressure_MPa[1], ref.interior_pressure_MPa[:, 0])
        cols = vs.pressure_colors(scene.state.pressure_MPa,
                                  renzo.material.hub.allowable_contact_stress_MPa)
        assert tuple(scene._flanks[1][0].color) == tuple(int(c) for c in cols[1, 0])
    finally:
        server.stop()
