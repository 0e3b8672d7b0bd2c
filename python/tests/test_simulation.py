"""Simulation: stages, steps, callbacks and the state arrays, checked against closed forms
(free fall, Newton's second law, the closure of a loaded linear joint) and equilibrium."""
import numpy as np
import pytest

import blockdem as bd
from conftest import cohesive_block_scene, column_scene

G = 9.81
RHO = 1207.0
EDGE = 0.046
K_N = 10e9  # normal stiffness of the column's joints (Pa/m)


def free_block(gravity=(0.0, 0.0, 0.0), dt=1e-4):
    scene = bd.Scene()
    scene.settings(gravity=list(gravity), time_step=dt)
    scene.joint_law("j", normal={"law": "linear", "stiffness": 1e9},
                    shear={"law": "linear", "stiffness": 1e8})
    scene.box("cube", size=[1, 1, 1], density=1000.0, position=[0, 0, 10])
    scene.stage("fly", kind="steps", steps=1000)
    return scene.simulation()


def test_free_fall_closed_form():
    # z(t) = z0 - g t^2 / 2. Leapfrog with velocities at half steps advances x by (v + g dt) dt
    # from rest: after n steps z = z0 - g dt^2 n (n + 1) / 2, exact up to rounding (1e-12 m).
    dt, n = 1e-4, 500
    sim = free_block(gravity=(0.0, 0.0, -G), dt=dt)
    assert sim.step(n) == n
    assert sim.step_count == n and sim.time == pytest.approx(n * dt, rel=1e-12)
    z = sim.positions[0, 2]
    assert z == pytest.approx(10.0 - G * dt**2 * n * (n + 1) / 2, abs=1e-12)
    assert abs(z - (10.0 - G * (n * dt) ** 2 / 2)) <= G * n * dt * dt  # O(dt) from the closed form
    np.testing.assert_allclose(sim.displacements[0], [0, 0, z - 10.0], atol=1e-15)


def test_callback_every_n_steps_changes_the_load_and_stops():
    # No gravity; from step 200 a force F pushes the 1000 kg cube along x. Newton: after k more
    # steps v = F k dt / m exactly (constant acceleration, no damping).
    dt, m, F = 1e-4, 1000.0, 50.0
    sim = free_block(dt=dt)
    seen = []

    def callback(s, k):
        seen.append(k)
        if k == 200:
            s.set_external_force("cube", [F, 0.0, 0.0])
        if k == 700:
            return False  # stop
        return None

    r = sim.run_stage(callback=callback, every=100)
    assert seen == [100, 200, 300, 400, 500, 600, 700]
    assert r["stopped"] and not r["converged"] and r["steps"] == 700
    assert "stopped" in r["message"]
    assert sim.velocities[0, 0] == pytest.approx(F / m * 500 * dt, rel=1e-9)
    assert sim.next_stage == 1


def test_step_callback_and_errors():
    sim = free_block()
    calls = []
    assert sim.step(350, callback=lambda s, k: calls.append((k, s.step_count)), every=100) == 350
    assert calls == [(100, 100), (200, 200), (300, 300)]
    assert sim.step(100, callback=lambda s, k: False, every=10) == 10
    with pytest.raises(ValueError):
        sim.step(10, callback=lambda s, k: None, every=0)

    def broken(s, k):
        raise RuntimeError("from the callback")
    with pytest.raises(RuntimeError, match="from the callback"):
        sim.step(20, callback=broken, every=5)
    with pytest.raises(KeyError):
        sim.set_external_force("nobody", [0, 0, 0])
    with pytest.raises(IndexError):
        sim.run_stage(5)


def test_column_settles_with_the_closed_form_closures():
    # Equilibrium: the joint under block i carries the weight above it, (4 - i) W with
    # W = rho g a^3; a linear joint closes by F / (k_n A), A = a^2 (docs: column.toml).
    sim = column_scene(bd).simulation()
    r = sim.run_stage(0)
    assert r["converged"]
    c = sim.contacts()
    n = sim.contact_count
    assert n == 3
    assert c["blocks"].shape == (n, 2) and c["point"].shape == (n, 3)
    assert c["normal"].shape == (n, 3) and c["shear_force"].shape == (n, 3)
    for key in ["normal_force", "closure", "area", "normal_stress", "sliding", "broken"]:
        assert c[key].shape == (n,)
    W = RHO * G * EDGE**3
    names = sim.block_names
    for (a, b), fn, closure, area in zip(c["blocks"], c["normal_force"], c["closure"], c["area"]):
        above = 4 - max(a, b)  # blocks at and above the upper one: b1 is index 1
        assert names[min(a, b)] in ("base", "b1", "b2")
        assert fn == pytest.approx(above * W, rel=1e-3)
        assert area == pytest.approx(EDGE**2, rel=1e-6)
        assert closure == pytest.approx(above * W / (K_N * EDGE**2), rel=1e-2)
    np.testing.assert_allclose(np.linalg.norm(c["normal"], axis=1), 1.0, rtol=1e-12)
    # Every free block is at rest in equilibrium: contact forces balance the weights.
    m = sim.masses
    np.testing.assert_allclose(sim.contact_forces[1:, 2], m[1:] * G, rtol=1e-3)
    q = sim.orientations
    assert q.shape == (4, 4)
    np.testing.assert_allclose(np.linalg.norm(q, axis=1), 1.0, rtol=1e-12)
    assert sim.rotations.shape == (4, 3) and sim.angular_velocities.shape == (4, 3)
    assert np.abs(sim.velocities).max() < 1e-4
    # The arrays are copies: writing to one does not move the block.
    p = sim.positions
    p[:] = 0.0
    assert sim.positions[1, 2] == pytest.approx(0.023, abs=1e-4)
    # Gravity from Python.
    sim.gravity = [0.0, 0.0, -2 * G]
    np.testing.assert_allclose(sim.gravity, [0.0, 0.0, -2 * G])
    sim.step(1)
    # One step later the joints still carry about one weight each while gravity pulls two: the
    # net force on each block is about its weight, of the order of the mean contact force.
    assert sim.equilibrium()["unbalanced_force_ratio"] > 0.1


@pytest.mark.parametrize("normal", [{"law": "linear", "stiffness": 10e9},
                                    {"law": "exponential", "preset": "eq4"}])
@pytest.mark.parametrize("shear", [{"law": "linear", "stiffness": 1e9, "friction_deg": 40},
                                   {"law": "stress_linear", "friction_deg": 40},
                                   {"law": "degrading"},
                                   {"law": "continuously_yielding", "friction_deg": 40}])
def test_every_joint_law_holds_a_block_in_equilibrium(normal, shear):
    # One cube on a fixed base: at equilibrium the contact carries its weight (Newton).
    scene = bd.Scene()
    scene.settings(damping=0.7)
    scene.joint_law("j", normal=normal, shear=shear)
    scene.box("base", size=[0.2, 0.2, 0.05], position=[0, 0, -0.025], density=RHO, motion="fixed")
    scene.box("cube", size=[EDGE] * 3, position=[0, 0, EDGE / 2], density=RHO)
    scene.stage("settle", gravity=[0, 0, -G])
    sim = scene.simulation()
    assert sim.run_stage()["converged"]
    assert sim.contacts()["normal_force"].sum() == pytest.approx(RHO * G * EDGE**3, rel=1e-3)


def test_strength_reduction_stage(source_dir):
    # Planar sliding, Hoek & Bray: F = tan 40 / tan 30 = 1.453 (scenarios/examples).
    sc = bd.load(source_dir / "scenarios/examples/planar_sliding.toml")
    sim = bd.Simulation(sc)
    sim.run_stage(progress=False)
    sim.run_stage(progress=False)
    before = sim.positions
    lines = []
    r = sim.run_stage(progress=lines.append)
    assert r["factor_of_safety"] == pytest.approx(np.tan(np.radians(40)) / np.tan(np.radians(30)),
                                                  abs=0.03)
    assert r["last_stable"] < r["first_failed"]
    np.testing.assert_array_equal(sim.positions, before)
    # Status lines from inside the trials, each named with its factor.
    assert lines and all(line.startswith("[3/3] factor of safety F = ") for line in lines), lines
    # Every trial has a line (its first check's at once), so each factor tried is named.
    assert len({line.split(": step")[0] for line in lines}) == r["trials"], lines
    with pytest.raises(TypeError):
        sim.run_stage(0, progress="loud")


def test_torque_velocity_and_settings_bindings():
    # A free 1 m cube of 1000 kg in zero gravity: I = m a^2 / 6 about any axis. A torque T for
    # k steps gives omega = T k dt / I; a velocity v moves it by v t (closed forms, round-off).
    dt, m = 1e-4, 1000.0
    sim = free_block(dt=dt)
    assert sim.time_step == 0.0 and sim.broken_bonds == 0
    sim.set_external_torque(0, [0.0, 0.0, 10.0])
    sim.step(100)
    assert sim.time_step == dt
    assert sim.angular_velocities[0, 2] == pytest.approx(10.0 * 100 * dt / (m / 6), rel=1e-9)
    sim.set_external_torque("cube", [0.0, 0.0, 0.0])
    x0 = sim.positions[0, 0]
    sim.set_velocity("cube", [2.0, 0.0, 0.0])
    sim.step(50)
    assert sim.positions[0, 0] - x0 == pytest.approx(2.0 * 50 * dt, rel=1e-9)
    sim.damping = 0.5
    assert sim.damping == 0.5
    with pytest.raises(ValueError):
        sim.damping = 1.0
    with pytest.raises(IndexError):
        sim.set_velocity(3, [0, 0, 0])


def test_divergence_raises_and_restores_the_last_good_state():
    # Faster than settings.max_speed (100 m/s) is divergence: the world goes back to its last
    # checkpoint (taken at the stage start) and DivergenceError reaches Python.
    sim = free_block()
    start = sim.positions
    sim.set_velocity("cube", [0.0, 1.0, 0.0])
    sim.run_stage(callback=lambda s, k: False, every=10)  # checkpoint at the stage start
    assert sim.step_count == 10
    sim.set_velocity("cube", [500.0, 0.0, 0.0])
    with pytest.raises(bd.DivergenceError, match="moves at 500 m/s"):
        sim.step(5)
    assert sim.step_count == 0
    np.testing.assert_array_equal(sim.positions, start)
    np.testing.assert_array_equal(sim.velocities, [[0.0, 1.0, 0.0]])


def test_results_do_not_depend_on_threads():
    # The step is deterministic for any thread count (docs/architecture.md): bit-identical.
    states = []
    for threads in (1, 2):
        sc = column_scene(bd).build()
        sc.threads = threads
        assert sc.threads == threads
        sim = bd.Simulation(sc)
        sim.run_stage(0)
        states.append((sim.positions, sim.orientations, sim.contacts()["normal_force"]))
    for a, b in zip(*states):
        np.testing.assert_array_equal(a, b)
    sc = column_scene(bd).build()
    with pytest.raises(ValueError):
        sc.threads = -1
    with pytest.raises(ValueError):
        sc.limit_steps(0)


def test_collapse_search_of_a_cohesive_block():
    # A 0.5 kg block on a plane, gravity tilted 30 degrees, joint friction 20 degrees and
    # cohesion c: it slides when m g (sin 30 - cos 30 tan 20) > c A, so the collapse load is
    # g* = c A / (m (sin 30 - cos 30 tan 20)) = 5.00 g for c = 453.2 Pa (Mohr-Coulomb). The
    # search brackets it within 5 % (measured: 4.94-5.01 g in mode boon2012, each trial ramping
    # from the last stable one: docs/stability.md, "Collapse load").
    th, phi, c = np.radians(30), np.radians(20), 453.2
    m, area = 2500 * 0.1 * 0.1 * 0.02, 0.01
    g_star = c * area / (m * (np.sin(th) - np.cos(th) * np.tan(phi))) / G
    sim = cohesive_block_scene(bd, collapse_tolerance=0.1).simulation()
    assert sim.run_stage()["converged"]  # 1 g < g*: the bond holds
    r = sim.run_stage()
    assert r["mechanism"] and not r["converged"]
    lo, hi = r["collapse"]["last_stable"], r["collapse"]["first_failed"]
    assert lo < hi and hi - lo <= 0.1
    assert 0.5 * (lo + hi) == pytest.approx(g_star, rel=0.05)


def bonded_incline(cohesion):
    """A 4 x 2 x 3 m rock mass cut by one joint J1 dipping 30 degrees east through its centre,
    the part below it fixed; J1 has friction 20 degrees and `cohesion`. The upper part (12 m3,
    W = 2500 g 12) rests on 2 x 4 / cos 30 m2 of J1 and needs the cohesion
    c* = W (sin 30 - cos 30 tan 20) / A = 5,888 Pa (a block on an incline with cohesion)."""
    scene = bd.Scene()
    scene.settings(rounding_distance=0.005)
    scene.joint_law("rough", normal={"law": "linear", "stiffness": 1e9},
                    shear={"law": "linear", "stiffness": 1e8, "friction_deg": 40})
    scene.joint_law("bonded", normal={"law": "linear", "stiffness": 1e9},
                    shear={"law": "linear", "stiffness": 1e8, "friction_deg": 20,
                           "cohesion": cohesion})
    scene.rock_mass(region={"min": [0, 0, 0], "max": [4, 2, 3]}, density=2500, law="rough")
    scene.joint_set(name="J1", dip_deg=30, dip_direction_deg=90, spacing=100,
                    origin=[2, 1, 1.5], law="bonded")
    scene.boundary(faces=["z_min"])
    scene.stage("consolidate", gravity=[0, 0, -G], ramp_steps=2000, damping=0.7,
                max_steps=20000)
    return scene.simulation()


def needed_cohesion():
    weight = 2500.0 * G * 12.0
    area = 2.0 * 4.0 / np.cos(np.radians(30.0))
    return weight * (np.sin(np.radians(30.0)) - np.cos(np.radians(30.0)) * np.tan(np.radians(20.0))) / area


@pytest.mark.parametrize("factor", [0.9, 1.1])
def test_set_laws_elastic_then_real(factor):
    # Consolidated with J1 elastic (its twin made on first use: the scenario has no elastic
    # stage), the bond survives gravity whatever its cohesion; given its real law, it breaks
    # and the block slides when c = 0.9 c*, and holds without moving when c = 1.1 c*.
    c_star = needed_cohesion()
    assert c_star == pytest.approx(5888.0, abs=1.0)
    sim = bonded_incline(factor * c_star)
    sim.set_laws([{"joint_set": "J1", "law": "elastic"}])
    assert sim.run_stage()["converged"]
    assert sim.broken_bonds == 0
    sim.set_laws([{"joint_set": "J1", "law": "bonded"}], reset_displacements=True)
    sim.step(20000)
    moved = np.abs(sim.displacements).max()
    if factor < 1.0:
        assert sim.broken_bonds > 0 and moved > 1e-2
    else:
        assert sim.broken_bonds == 0 and moved < 1e-6


def test_set_laws_refuses_unknown_names():
    sim = bonded_incline(1e4)
    with pytest.raises(KeyError, match="J1"):
        sim.set_laws([{"joint_set": "J9", "law": "bonded"}])
    with pytest.raises(KeyError, match="nonsense"):
        sim.set_laws([{"joint_set": "J1", "law": "nonsense"}])
    with pytest.raises(ValueError, match="unknown key"):
        sim.set_laws([{"joint_set": "J1", "law": "bonded", "speed": 1}])
    with pytest.raises(ValueError, match="either"):
        sim.set_laws([{"joint_set": "J1", "group": "rock", "law": "bonded"}])


def test_simulation_of_none_is_a_type_error():
    with pytest.raises(TypeError, match="Scenario"):
        bd.Simulation(None)


def test_settings_changed_after_building_are_refused(source_dir):
    # The simulation's scenario is the one its world was built from: a setting changed there
    # would be ignored, so it is refused, naming the key; a scenario not yet built takes it.
    sc = bd.load(source_dir / "scenarios/examples/planar_sliding.toml")
    sc.threads = 1
    sim = bd.Simulation(sc)
    for change in (lambda: setattr(sim.scenario, "threads", 2),
                   lambda: sim.scenario.limit_steps(10)):
        with pytest.raises(ValueError) as err:
            change()
        assert "before building the Simulation" in str(err.value)
    sc.threads = 2  # the caller's own scenario: a copy was built, this one is free
    assert sc.threads == 2 and sim.scenario.threads == 1


def test_namespace_holds_only_blockdem_names():
    public = {n for n in dir(bd) if not n.startswith("_")}
    assert not public & {"os", "pathlib", "shutil"}
    assert set(bd.__all__) <= public


def test_two_threads_stepping_one_simulation():
    # One simulation stepped from two threads at once: the second is refused while the first
    # steps (or waits for Python's lock and steps after it); no crash, and every step taken is
    # counted once. Free fall, so the state after N steps is known: z = z0 - g dt^2 N (N + 1) / 2.
    import threading
    dt = 1e-4
    sim = free_block(gravity=(0.0, 0.0, -G), dt=dt)
    taken, refused = [], []

    def work():
        try:
            taken.append(sim.step(2000, callback=lambda s, k: None, every=50))
        except RuntimeError as e:
            refused.append(str(e))

    threads = [threading.Thread(target=work) for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    n = sum(taken)
    assert len(taken) + len(refused) == 2 and n >= 2000
    assert all("another thread" in r for r in refused)
    assert sim.step_count == n
    assert sim.positions[0, 2] == pytest.approx(10.0 - G * dt**2 * n * (n + 1) / 2, abs=1e-12)
