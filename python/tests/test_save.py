"""Simulation.save and Simulation.load: a simulation saved between two stages and loaded again
goes on bit for bit as the one never saved (the oracle), a scenario whose later stages differ
branches from it, and one that differs before the saved stage is refused with the reason."""
import numpy as np
import pytest

import blockdem as bd


def planar(source_dir):
    return bd.Scene.from_toml(source_dir / "scenarios/examples/planar_sliding.toml")


def state(sim):
    return (sim.positions, sim.orientations, sim.velocities, sim.angular_velocities,
            sim.step_count, sim.time)


def same(a, b):
    for x, y in zip(a, b):
        if isinstance(x, np.ndarray):
            np.testing.assert_array_equal(x, y)
        else:
            assert x == y


def test_a_loaded_simulation_goes_on_bit_for_bit(tmp_path, source_dir, capfd):
    sc = planar(source_dir).build()
    sim = bd.Simulation(sc)
    sim.run_stage(progress=False)
    saved = tmp_path / "settled.bdsim"
    sim.save(saved)
    again = bd.Simulation.load(saved, sc)
    assert "restarting from" in capfd.readouterr().err
    assert again.next_stage == sim.next_stage == 1
    same(state(again), state(sim))
    # Both run the tilt and the strength reduction: the same states and the same factor.
    sim.run_stage(progress=False)
    again.run_stage(progress=False)
    same(state(again), state(sim))
    f = sim.run_stage(progress=False)["factor_of_safety"]
    assert again.run_stage(progress=False)["factor_of_safety"] == f


def test_a_scenario_whose_later_stages_differ_branches(tmp_path, source_dir, capfd):
    sim = bd.Simulation(planar(source_dir).build())
    sim.run_stage(progress=False)
    sim.run_stage(progress=False)
    saved = tmp_path / "tilted.bdsim"
    sim.save(saved)
    # Another bracket for the strength reduction (stage 3): the state before it is the same.
    scene = planar(source_dir)
    scene.data["stages"][2]["tolerance"] = 0.05
    branch = bd.Simulation.load(saved, scene.build())
    err = capfd.readouterr().err
    assert "stages 1 to 2 are the same" in err and "from stage 3" in err, err
    same(state(branch), state(sim))
    r = branch.run_stage(progress=False)
    # tan 40 / tan 30 = 1.453 (Hoek & Bray's planar sliding) within the wider bracket.
    assert r["last_stable"] <= np.tan(np.radians(40)) / np.tan(np.radians(30)) <= r["first_failed"]
    assert r["first_failed"] - r["last_stable"] <= 0.05


def test_a_scenario_that_differs_before_the_saved_stage_is_refused(tmp_path, source_dir):
    sim = bd.Simulation(planar(source_dir).build())
    sim.run_stage(progress=False)
    saved = tmp_path / "settled.bdsim"
    sim.save(saved)
    scene = planar(source_dir)
    scene.data["stages"][0]["damping"] = 0.5  # the settling stage the saved state ran
    with pytest.raises(ValueError, match="the stages up to the checkpoint.s, must be those of the run that wrote it"):
        bd.Simulation.load(saved, scene.build())


def test_a_file_that_is_not_a_saved_simulation_is_refused(tmp_path, source_dir):
    sc = planar(source_dir).build()
    junk = tmp_path / "junk.bdsim"
    junk.write_bytes(b"not a checkpoint at all")
    with pytest.raises(ValueError, match="junk.bdsim"):
        bd.Simulation.load(junk, sc)
    with pytest.raises(TypeError):
        bd.Simulation.load(junk, None)
