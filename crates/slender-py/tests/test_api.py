"""The Python API: array shapes, dtypes and units against closed forms, bad input, solves
that do not converge, threads, and the benchmarks' master curves."""

from __future__ import annotations

import math
import threading

import numpy as np
import pytest

import slender

from conftest import EXAMPLES, cable_scene

# A cantilever: L = 1 m, d = 10 mm steel-like, tip force small enough for linear theory.
L, D, E, NU, RHO = 1.0, 0.01, 2.0e9, 0.3, 1000.0
I = math.pi * D**4 / 64.0
A = math.pi * D**2 / 4.0
F = 1e-3 * 3.0 * E * I / L**2  # tip deflection = L/1000


def cantilever(n: int = 50, force: float = F) -> dict:
    x = np.linspace(0.0, L, n + 1)
    pts = np.stack([x, np.zeros_like(x), np.zeros_like(x)], axis=1)
    return slender.rod_scene(
        pts,
        section={"shape": "circle", "diameter": D},
        material={"young": E, "poisson": NU, "density": RHO},
        supports=[{"kind": "clamp", "vertex": "start"}],
        forces=[{"vertex": "end", "force": [0.0, 0.0, -force]}],
        name="beam",
    )


def test_shapes_dtypes_and_units() -> None:
    n = 50
    r = slender.Session(cantilever(n)).results()
    assert r.converged and r.stable
    rod = r.rods["beam"]
    expect = {
        "positions": (n + 1, 3),
        "frames": (n, 3, 3),
        "curvature": (n + 1, 2),
        "twist": (n + 1,),
        "edge_strain": (n,),
        "axial_force": (n,),
        "bending_moment": (n + 1, 2),
        "twisting_moment": (n + 1,),
        "support_forces": (1, 3),
        "support_moments": (1, 3),
        "support_positions": (1, 3),
        "applied_force": (3,),
    }
    for key, shape in expect.items():
        a = getattr(rod, key)
        assert a.shape == shape, key
        assert a.dtype == np.float64, key
    assert rod.support_vertices.dtype == np.int64
    # Frames are orthonormal rows (m1, m2, t), t along the edge.
    for j in range(n):
        fr = rod.frames[j]
        assert np.allclose(fr @ fr.T, np.eye(3), atol=1e-12)
        e = rod.positions[j + 1] - rod.positions[j]
        assert np.allclose(fr[2], e / np.linalg.norm(e), atol=1e-12)
    # Units against linear beam theory (independent closed forms):
    # tip deflection F L^3 / 3EI (m) ...
    tip = -rod.positions[-1, 2]
    assert tip == pytest.approx(F * L**3 / (3 * E * I), rel=2e-3)
    # ... the clamp reaction (N, N m) ...
    assert np.allclose(rod.support_forces[0], [0.0, 0.0, F], rtol=1e-9, atol=1e-6 * F)
    assert rod.support_moments[0][1] == pytest.approx(-F * L, rel=1e-3)
    # ... the bending moment F (L - s) (N m) at interior vertices ...
    s = rod.positions[:, 0]
    m = np.linalg.norm(rod.bending_moment, axis=1)
    inner = slice(5, n - 5)
    assert np.allclose(m[inner], F * (L - s[inner]), rtol=5e-3)
    # ... and the axial force is EA times the strain (N).
    assert np.allclose(rod.axial_force, E * A * rod.edge_strain, rtol=1e-12, atol=0.0)
    rep = rod.reports[0]
    assert rep.converged and rep.iterations >= 1
    assert rep.inertia is not None and rep.inertia[0] == 0
    assert rep.lambda_min is not None and rep.lambda_min > 0


def test_bad_input_names_the_field() -> None:
    good = cantilever(10)
    cases = []
    bad = cantilever(10)
    bad["rods"][0]["material"]["young"] = -1.0
    cases.append((bad, "rods[0].material.young"))
    bad = cantilever(10)
    bad["rods"][0]["material"]["yuong"] = 1.0
    cases.append((bad, "rods[0].material.yuong"))
    bad = cantilever(10)
    bad["rods"][0]["supports"][0]["vertex"] = 99
    cases.append((bad, "rods[0].supports[0].vertex"))
    bad = cantilever(10)
    bad["gravity"] = [0.0, float("nan"), 0.0]
    cases.append((bad, "gravity[1]"))
    bad = cantilever(10)
    bad["rods"][0]["section"]["diameter"] = 0.0
    cases.append((bad, "rods[0].section"))
    for scene, field in cases:
        with pytest.raises(ValueError) as e:
            slender.Session(scene)
        assert field in str(e.value), (field, str(e.value))
        assert isinstance(e.value, slender.SceneError)
    with pytest.raises(ValueError, match=r"rods\[0\]\.centerline\.points"):
        slender.rod_scene(np.zeros((4, 2)), section={"shape": "circle", "diameter": 0.01})
    s = slender.Session(good)
    with pytest.raises(ValueError, match="gravity"):
        s.set_gravity([0.0, 0.0, float("inf")])
    with pytest.raises(ValueError, match=r"supports\[5\]"):
        s.move_support(0, 5, translation=[0.0, 0.0, 0.01])
    with pytest.raises(ValueError, match="translation"):
        s.move_support(0, 0, translation=[0.0, 0.01])
    with pytest.raises(ValueError, match="kind"):
        s.add_support(0, {"kind": "hook", "vertex": 3})
    with pytest.raises(ValueError):
        slender.load_scene(EXAMPLES / "scene.schema.json")


def test_not_converged_is_reported_not_returned() -> None:
    # A heavy tip load that one Newton iteration per step with tiny steps cannot reach.
    scene = cantilever(20, force=200 * F)
    scene["solver"] = {"max_iterations": 2, "min_load_step": 0.5}
    with pytest.raises(slender.NotConvergedError) as e:
        slender.solve(scene)
    steps = e.value.results
    assert not steps[0].converged
    rep = steps[0].rods[0].reports[0]
    assert not rep.converged and rep.reason
    s = slender.Session(scene)
    assert not s.results().converged
    # An edit that does not converge keeps the last equilibrium and says so.
    ok = slender.Session(cable_scene(40))
    ok_before = ok.results().rods[0].positions
    ok_scene = cable_scene(40)
    ok_scene["solver"] = {"max_iterations": 1, "min_load_step": 0.5}
    weak = slender.Session(ok_scene)
    before = weak.results()
    with pytest.raises(slender.NotConvergedError) as e:
        weak.move_support(0, 1, translation=[-0.3, 0.2, 0.1])
    assert not e.value.report.converged
    after = weak.results()
    assert np.array_equal(after.rods[0].positions, before.rods[0].positions)
    rep = weak.move_support(0, 1, translation=[-0.3, 0.2, 0.1], check=False)
    assert not rep.converged and rep.reason
    assert ok_before.shape == (41, 3)


def _drag(session: slender.Session, moves: int) -> np.ndarray:
    for k in range(moves):
        sign = 1.0 if k % 2 == 0 else -1.0
        session.move_support(0, 1, translation=[0.0, 0.02 * sign, 0.01])
    return session.results().rods[0].positions


def test_two_threads_solve_at_once() -> None:
    moves = 12
    expected = [_drag(slender.Session(cable_scene(100, clips)), moves) for clips in [(), (50,)]]
    sessions = [slender.Session(cable_scene(100, clips)) for clips in [(), (50,)]]
    out: list = [None, None]
    errors: list = []

    def work(i: int) -> None:
        try:
            out[i] = _drag(sessions[i], moves)
        except Exception as e:  # pragma: no cover - reported below
            errors.append(e)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    for i in range(2):
        # Same bits as the same edits made one thread at a time.
        assert np.array_equal(out[i], expected[i])


def test_panic_becomes_an_exception() -> None:
    from slender import _slender

    with pytest.raises(slender.SolverPanic, match="boom"):
        _slender._panic_for_test("boom")
    assert issubclass(slender.SolverPanic, RuntimeError)


def test_incremental_edits() -> None:
    s = slender.Session(cable_scene(40))
    p0, _ = s.pose(0, 1)
    rep = s.move_support(0, 1, translation=[-0.1, 0.0, 0.0])
    assert rep.converged and rep.iterations > 0
    p1, _ = s.pose(0, 1)
    assert np.allclose(p1 - p0, [-0.1, 0.0, 0.0])
    r = s.results()
    assert np.allclose(r.rods[0].positions[-1], p1)
    rep = s.add_support(0, {"kind": "clip", "at": 0.5})
    assert rep.converged
    assert len(s.results().rods[0].support_kinds) == 3
    rep = s.remove_support(0, 2)
    assert rep.converged
    rep = s.set_gravity([0.0, 0.0, -2 * 9.81])
    assert rep.converged
    # Weight balance: the clamps carry the doubled weight (N).
    rod = s.results().rods[0]
    weight = 1400.0 * math.pi * 0.006**2 / 4 * 1.0 * 2 * 9.81
    assert rod.support_forces[:, 2].sum() == pytest.approx(weight, rel=1e-9)
    saved = s.saved()
    assert slender.Session(saved).results().converged


def test_master_curves_against_closed_forms() -> None:
    # Small Γ: the linear beam under its weight, dy/L = Γ/8.
    e = slender.heavy_elastica(1e-3, n=20)
    assert e["dy"] == pytest.approx(1e-3 / 8, rel=1e-3)
    assert e["shape"].shape == (21, 2) and e["shape"].dtype == np.float64
    # The lateral-buckling narrow-strip limit 12.854 (1 - ν) sqrt(2 (1 + ν)); at w/L = 0.01
    # the warping stiffness still raises it by 0.7 %.
    nu = 0.35
    g = slender.lateral_buckling_critical_gamma(0.01, nu, "vlasov_beam")
    assert g == pytest.approx(12.854 * (1 - nu) * math.sqrt(2 * (1 + nu)), rel=1e-2)
    assert g > 12.854 * (1 - nu) * math.sqrt(2 * (1 + nu))
    rec = slender.cantilever_case(10.0, n_elements=20)
    assert rec["converged"] and abs(rec["rel_error"]) < 1e-2
    with pytest.raises(ValueError, match="material"):
        slender.cantilever_case(10.0, material="steel")
    with pytest.raises(ValueError, match="gamma"):
        slender.heavy_elastica(-1.0)


def test_flat_cable_connector_drag() -> None:
    """A flat cable's connector dragged from Python reaches the equilibrium of the scene's
    own motion stage (the same move, which `slender solve` makes in two steps), its edge
    stays at the connector, and the clamps carry the strip's weight."""
    scene = EXAMPLES / "flat_cable_two_connectors.toml"
    by_motion = slender.solve(scene)
    s = slender.Session(scene)
    p0, r0 = s.shell_pose(0, 1)
    for _ in range(2):  # the stage: translate = [0, -0.02, 0] in 2 steps
        rep = s.move_shell_clamp(0, 1, translation=[0.0, -0.01, 0.0])
        assert rep.converged and rep.iterations > 0 and rep.structures == []
    p1, r1 = s.shell_pose(0, 1)
    assert np.allclose(p1 - p0, [0.0, -0.02, 0.0], rtol=0.0, atol=1e-15)
    assert np.allclose(r1, r0, rtol=0.0, atol=1e-15)
    shell = s.results().shells[0]
    # Same equilibrium as the motion stage to 1e-9 of the length (the targets differ in
    # their last bits: p0 − 0.01 − 0.01 against p0 − 0.02).
    want = by_motion[-1].shells[0].positions
    assert np.abs(shell.positions - want).max() <= 1e-9 * 0.3
    # Weight ρ h w L g (N) carried by the two clamps.
    weight = 2000.0 * 0.3e-3 * 0.02 * 0.3 * 9.81
    assert np.linalg.norm(shell.clamp_force - [0.0, weight, 0.0]) <= 1e-6 * weight
    # Back to the start by an absolute pose: the first equilibrium again.
    rep = s.move_shell_clamp(0, 1, position=p0)
    assert rep.converged
    back = s.results().shells[0].positions
    assert np.abs(back - by_motion[0].shells[0].positions).max() <= 1e-9 * 0.3
    # Bad input names the field and changes nothing.
    with pytest.raises(slender.SceneError, match=r"shells\[0\]\.clamps\[5\]"):
        s.move_shell_clamp(0, 5, translation=[0.0, 0.01, 0.0])
    with pytest.raises(slender.SceneError, match="translation"):
        s.move_shell_clamp(0, 1, translation=[0.0, float("nan"), 0.0])
    with pytest.raises(slender.SceneError, match=r"shells\[3\]"):
        s.shell_pose(3, 0)
    assert np.array_equal(s.results().shells[0].positions, back)


def flat_cable(force: list) -> dict:
    """A weightless 0.2 m strip clamped at its start, a force at the middle of its free edge."""
    return {
        "shells": [{
            "name": "flat", "length": 0.2, "width": 0.01, "thickness": 5e-4,
            "material": {"young": 5e9, "poisson": 0.3, "density": 1000.0},
            "elements": 8, "width_elements": 2, "grading": {"kind": "uniform"},
            "forces": [{"station": 8, "column": 1, "force": force}],
        }]
    }


def test_flat_cable_force_edit_matches_a_cold_solve() -> None:
    """A flat cable's point force edited from Python ends where a session of the scene with
    that force starts (loaded from the flat strip), and bad input names the field."""
    s = slender.Session(flat_cable([0.0, -0.005, 0.0]))
    rep = s.set_shell_force(0, 0, [0.0, -0.02, 0.004])
    assert rep.converged and rep.structures == []
    here = s.results().shells[0].positions
    cold = slender.Session(flat_cable([0.0, -0.02, 0.004])).results().shells[0].positions
    assert np.abs(here[-1] - s.results().shells[0].positions[0]).max() > 0.02  # a large deflection
    assert np.abs(here - cold).max() <= 1e-9 * 0.2
    assert s.scene()["shells"][0]["forces"][0]["force"] == [0.0, -0.02, 0.004]
    with pytest.raises(slender.SceneError, match=r"shells\[0\]\.forces\[2\]"):
        s.set_shell_force(0, 2, [0.0, 0.0, 1.0])
    with pytest.raises(slender.SceneError, match=r"shells\[0\]\.forces\[0\]\.force"):
        s.set_shell_force(0, 0, [0.0, float("nan"), 0.0])
    assert np.array_equal(s.results().shells[0].positions, here)


def test_flat_cable_force_added_and_removed() -> None:
    """A force added to a flat cable at a grid vertex ends where a session of the scene with it
    starts; removed, the strip is back where it was; bad input names the field."""
    s = slender.Session(flat_cable([0.0, -0.005, 0.0]))
    first = s.results().shells[0].positions.copy()
    rep = s.add_shell_force(0, 4, 0, [0.0, 0.01, 0.002])
    assert rep.converged and rep.structures == []
    scene = flat_cable([0.0, -0.005, 0.0])
    scene["shells"][0]["forces"].append({"station": 4, "column": 0, "force": [0.0, 0.01, 0.002]})
    cold = slender.Session(scene).results().shells[0].positions
    here = s.results().shells[0].positions
    assert np.abs(here - first).max() > 1e-3
    assert np.abs(here - cold).max() <= 1e-9 * 0.2
    assert s.scene()["shells"][0]["forces"][1] == {"station": 4, "column": 0, "force": [0.0, 0.01, 0.002]}
    with pytest.raises(slender.SceneError, match=r"shells\[0\]\.forces\[2\]\.station"):
        s.add_shell_force(0, 9, 0, [0.0, 0.0, 1.0])
    with pytest.raises(slender.SceneError, match=r"shells\[0\]\.forces\[2\]\.column"):
        s.add_shell_force(0, 1, 3)
    with pytest.raises(slender.SceneError, match=r"shells\[0\]\.forces\[5\]"):
        s.remove_shell_force(0, 5)
    assert np.array_equal(s.results().shells[0].positions, here)
    rep = s.remove_shell_force(0, 1)
    assert rep.converged
    assert len(s.scene()["shells"][0]["forces"]) == 1
    assert np.abs(s.results().shells[0].positions - first).max() <= 1e-9 * 0.2


def test_add_and_remove_a_force() -> None:
    """A force added at an arc length lands on the nearest vertex and ends where a session of
    the scene with that force starts; removed, the first equilibrium comes back."""
    s = slender.Session(cantilever(force=F))
    first = s.results().rods[0].positions.copy()
    rep = s.add_force(0, 0.51 * L, [0.0, 2.0 * F, 0.0])
    assert rep.converged and rep.structures == [0]
    added = s.scene()["rods"][0]["forces"][1]
    assert added["vertex"] == 25 and added["force"] == [0.0, 2.0 * F, 0.0]  # 50 elements
    scene = cantilever(force=F)
    scene["rods"][0]["forces"].append({"vertex": 25, "force": [0.0, 2.0 * F, 0.0]})
    cold = slender.Session(scene).results().rods[0].positions
    assert np.abs(s.results().rods[0].positions - cold).max() <= 1e-12
    rep = s.remove_force(0, 1)
    assert rep.converged and len(s.scene()["rods"][0]["forces"]) == 1
    assert np.abs(s.results().rods[0].positions - first).max() <= 1e-12
    with pytest.raises(slender.SceneError, match=r"rods\[0\]\.forces\.at"):
        s.add_force(0, 2.0 * L)
    with pytest.raises(slender.SceneError, match=r"rods\[0\]\.forces\[3\]"):
        s.remove_force(0, 3)


def test_follower_force_edit_matches_a_cold_solve() -> None:
    """The follower example's tip force (as at rest) edited in a session ends where a session
    of the file with the new value starts; a dead force of that value ends elsewhere."""
    s = slender.Session(EXAMPLES / "follower_cantilever.toml")
    rep = s.set_force(0, 0, [0.0, 3.0, 0.0])
    assert rep.converged and rep.structures == [0]
    scene = slender.load_scene(EXAMPLES / "follower_cantilever.toml")
    scene["rods"][0]["forces"][0]["force"] = [0.0, 3.0, 0.0]
    cold = slender.Session(scene).results().rods[0].positions
    here = s.results().rods[0].positions
    assert np.abs(here - cold).max() <= 1e-9
    scene["rods"][0]["forces"][0]["follower"] = False
    dead = slender.Session(scene).results().rods[0].positions
    assert np.abs(here - dead).max() > 1e-2


def test_moment_edit_matches_a_cold_solve() -> None:
    """The clipped-cable example's twisting moment, edited to a new axis in a session, ends
    where a session of the file with the new value starts; a bad index names the moment."""
    s = slender.Session(EXAMPLES / "clipped_cable.toml")
    before = s.results().rods[0].positions.copy()
    rep = s.set_moment(0, 0, [0.02, 0.0, 0.005])
    assert rep.converged and len(rep.structures) == 1
    assert s.scene()["rods"][0]["moments"][0]["moment"] == [0.02, 0.0, 0.005]
    scene = slender.load_scene(EXAMPLES / "clipped_cable.toml")
    scene["rods"][0]["moments"][0]["moment"] = [0.02, 0.0, 0.005]
    cold = slender.Session(scene).results().rods[0].positions
    here = s.results().rods[0].positions
    assert np.abs(here - cold).max() <= 1e-9
    assert np.abs(here - before).max() > 1e-4
    with pytest.raises(slender.SceneError, match=r"rods\[0\]\.moments\[2\]"):
        s.set_moment(0, 2, [0.0, 0.0, 1.0])
    # A second moment added at 0.6 m (the file's nearest vertex), then removed: the session
    # is back where it was.
    rep = s.add_moment(0, 0.6, [0.0, 0.01, 0.0])
    assert rep.converged and len(s.scene()["rods"][0]["moments"]) == 2
    added = s.scene()["rods"][0]["moments"][1]
    scene["rods"][0]["moments"].append(added)
    cold = slender.Session(scene).results().rods[0].positions
    assert np.abs(s.results().rods[0].positions - cold).max() <= 1e-9
    rep = s.remove_moment(0, 1)
    assert rep.converged and len(s.scene()["rods"][0]["moments"]) == 1
    assert np.abs(s.results().rods[0].positions - here).max() <= 1e-9


def test_force_edit_matches_a_cold_solve() -> None:
    """A tip force edited in a session ends where a session of the scene with that force
    starts (loads ramped from rest), and the weightless tip moves by F L³/(3EI)."""
    s = slender.Session(cantilever(force=F))
    tip0 = s.results().rods[0].positions[-1].copy()
    rep = s.set_force(0, 0, [0.0, 0.0, -2.0 * F])
    assert rep.converged and rep.structures == [0]
    tip = s.results().rods[0].positions[-1]
    cold = slender.Session(cantilever(force=2.0 * F)).results().rods[0].positions[-1]
    assert np.abs(tip - cold).max() <= 1e-12
    # Linear regime (F gives a tip deflection of L/1000): doubling F doubles it.
    assert tip0[2] - tip[2] == pytest.approx(F * L**3 / (3 * E * I), rel=2e-3)
    assert s.scene()["rods"][0]["forces"][0]["force"] == [0.0, 0.0, -2.0 * F]
    with pytest.raises(slender.SceneError, match=r"rods\[0\]\.forces\[4\]"):
        s.set_force(0, 4, [0.0, 0.0, 1.0])


def _elastic_catenary_sag(l0: float, q: float, ea: float, span: float) -> float:
    """Mid-length sag (m) of an elastic catenary (Irvine): rest length l0, weight q per rest
    length, axial stiffness ea, supports at one height span apart."""
    lo, hi = 1e-12, 1e6
    for _ in range(200):
        h = math.sqrt(lo * hi)
        if h * l0 / ea + 2.0 * h / q * math.asinh(q * l0 / (2.0 * h)) < span:
            lo = h
        else:
            hi = h
    h = math.sqrt(lo * hi)
    v = 0.5 * q * l0
    return q * l0 * l0 / (8.0 * ea) + h / q * (math.sqrt(1.0 + (v / h) ** 2) - 1.0)


def test_cable_length_paid_out_from_python() -> None:
    """A cord built with `rod_scene` (a polyline) hangs between two pins; paying cable out
    from Python gives the elastic catenary of the new length, and bad lengths name the
    field."""
    d, e, rho = 5e-4, 3e7, 1200.0
    area = math.pi * d * d / 4.0
    pts = np.linspace([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], 81)
    scene = slender.rod_scene(
        pts,
        section={"shape": "circle", "diameter": d},
        material={"young": e, "poisson": 0.45, "density": rho},
        supports=[
            {"kind": "pin", "vertex": "start"},
            {"kind": "pin", "vertex": "end"},
            {"kind": "twist_hold", "vertex": "start"},
        ],
        gravity=(0.0, 0.0, -9.81),
        name="cord",
    )
    s = slender.Session(scene)
    s.move_support(0, 1, translation=[-0.2, 0.0, 0.0])
    for l0 in (1.2, 0.95):
        rep = s.set_length(0, l0)
        assert rep.converged and rep.stable
        assert abs(s.length(0) - l0) <= 1e-12
        sag = -s.results().rods[0].positions[40][2]
        exact = _elastic_catenary_sag(l0, rho * area * 9.81, e * area, 0.8)
        assert abs(sag - exact) <= 1e-3 * exact, (l0, sag, exact)
    before = s.results().rods[0].positions
    with pytest.raises(slender.SceneError, match=r"rods\[0\]\.centerline\.length"):
        s.set_length(0, -1.0)
    with pytest.raises(slender.SceneError, match=r"rods\[2\]"):
        s.length(2)
    assert np.array_equal(s.results().rods[0].positions, before)


def test_an_obstacle_moved_from_python_carries_the_cable() -> None:
    """A round bar pushed up 4 cm under a taut cable from Python: the cable ends where the
    same scene ends with both clamps moved down instead (support moves, not the obstacle
    code), and bad moves name the obstacle."""

    def scene() -> dict:
        return {
            "gravity": [0.0, 0.0, -9.81],
            "rods": [
                {
                    "name": "cable",
                    "elements": 40,
                    "centerline": {
                        "kind": "straight",
                        "start": [0.0, 0.0, 0.0],
                        "direction": [1.0, 0.0, 0.0],
                        "length": 1.0,
                    },
                    "section": {"shape": "circle", "diameter": 0.006},
                    "material": {"young": 2.0e8, "poisson": 0.4, "density": 1400.0},
                    "supports": [
                        {"kind": "clamp", "vertex": "start"},
                        {"kind": "clamp", "vertex": "end"},
                    ],
                }
            ],
            "obstacles": [
                {
                    "name": "bar",
                    "shape": {
                        "kind": "cylinder",
                        "point": [0.45, 0.0, -0.05],
                        "axis": [0.0, 1.0, 0.0],
                        "radius": 0.02,
                    },
                }
            ],
            "contact": {"activation": 1e-4},
        }

    s = slender.Session(scene())
    rep = s.move_obstacle(0, translation=[0.0, 0.0, 0.07])
    assert rep.converged and rep.stable
    assert np.allclose(s.obstacle_reference(0), [0.45, 0.0, 0.02], atol=1e-15)
    ref = slender.Session(scene())
    for support in (0, 1):
        ref.move_support(0, support, translation=[0.0, 0.0, -0.07])
    moved = s.results().rods[0].positions
    expected = ref.results().rods[0].positions + np.array([0.0, 0.0, 0.07])
    assert np.abs(moved - expected).max() < 1e-7
    with pytest.raises(slender.SceneError, match=r"obstacles\[1\]"):
        s.move_obstacle(1, translation=[0.0, 0.0, 0.01])
    with pytest.raises(slender.SceneError, match=r"obstacles\[3\]"):
        s.obstacle_reference(3)
    assert np.array_equal(s.results().rods[0].positions, moved)


def test_a_coarse_cable_through_a_thin_bar_is_reported() -> None:
    """A 0.5 m cantilever of 4 elements sags onto a 1 cm bar off its vertices and runs through
    it (edge 2, the same case as the Rust scene test); with 100 elements it rests on the bar
    and nothing is reported."""

    def scene(elements: int) -> dict:
        return {
            "gravity": [0.0, 0.0, -9.81],
            "rods": [
                {
                    "name": "cable",
                    "elements": elements,
                    "centerline": {
                        "kind": "straight",
                        "start": [0.0, 0.0, 0.0],
                        "direction": [1.0, 0.0, 0.0],
                        "length": 0.5,
                    },
                    "section": {"shape": "circle", "diameter": 0.006},
                    "material": {"young": 1.0e9, "poisson": 0.4, "density": 1500.0},
                    "supports": [{"kind": "clamp", "vertex": "start"}],
                }
            ],
            "obstacles": [
                {
                    "name": "bar",
                    "shape": {
                        "kind": "cylinder",
                        "point": [0.3125, 0.0, -0.02],
                        "axis": [0.0, 1.0, 0.0],
                        "radius": 0.01,
                    },
                }
            ],
        }

    coarse = slender.Session(scene(4)).results()
    assert coarse.converged
    through = coarse.edges_through_obstacles
    assert len(through) == 1, through
    e = through[0]
    assert (e["rod"], e["shell"], e["edge"], e["vertices"], e["obstacle"]) == (
        "cable", False, 2, [2, 3], "bar")
    # The deepest point is inside the bar by the depth reported.
    r = math.hypot(e["position"][0] - 0.3125, e["position"][2] + 0.02)
    assert abs(0.01 - r - e["depth"]) < 1e-9 and 1e-3 < e["depth"] < 0.01
    fine = slender.Session(scene(100)).results()
    assert fine.converged and fine.edges_through_obstacles == []
