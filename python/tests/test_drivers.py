"""`blockdem run` (bd.run) and Simulation.run_stage drive the stages with one driver: the same
scenario gives the same steps per stage, the same factor of safety and the same collapse bracket,
bit for bit (each front end is the other's oracle)."""
import numpy as np

import blockdem as bd

G = 9.81


def stages_of_simulation(scenario):
    """Every stage through Simulation.run_stage, up to the first that fails (as a run stops)."""
    sim = bd.Simulation(scenario)
    results = []
    for _ in range(sim.stage_count):
        results.append(sim.run_stage())
        if not results[-1]["converged"]:
            break
    return results


def test_strength_reduction_is_the_same_in_both_front_ends(tmp_path, source_dir):
    sc = bd.load(source_dir / "scenarios/examples/planar_sliding.toml")
    run = bd.run(sc, tmp_path)
    stages = stages_of_simulation(sc)
    assert run["status"] == "completed"
    assert run["steps_per_stage"] == [s["steps"] for s in stages]
    assert run["factor_of_safety"] == stages[-1]["factor_of_safety"]
    fos = run["summary"]["factor_of_safety"]
    assert (fos["last_stable"], fos["first_failed"]) == (stages[-1]["last_stable"],
                                                         stages[-1]["first_failed"])


def cohesive_block():
    # A cohesive block on a plane under gravity tilted 30 degrees, loaded until it slides
    # (test_simulation.py's collapse search, with a wider bracket).
    th, c = np.radians(30), 453.2
    d = [np.sin(th), 0.0, -np.cos(th)]
    scene = bd.Scene()
    scene.settings(damping=0.7, contact_mode="boon2012")
    scene.joint_law("j", normal={"law": "linear", "stiffness": 1e10},
                    shear={"law": "linear", "stiffness": 1e9, "friction_deg": 20,
                           "cohesion": c})
    scene.box("base", size=[1.0, 0.3, 0.05], position=[0, 0, -0.025], density=2500.0,
              motion="fixed")
    scene.box("block", size=[0.1, 0.1, 0.02], position=[0, 0, 0.01], density=2500.0)
    scene.stage("settle", gravity=[G * x for x in d])
    scene.stage("load", gravity=[10 * G * x for x in d], ramp_steps=2000, find_collapse=True,
                collapse_tolerance=0.5)
    return scene.build()


def test_collapse_search_is_the_same_in_both_front_ends(tmp_path):
    sc = cohesive_block()
    run = bd.run(sc, tmp_path)
    stages = stages_of_simulation(sc)
    assert run["status"] == "collapsed" and run["exit_code"] == 0
    assert run["steps_per_stage"] == [s["steps"] for s in stages]
    collapse = stages[-1]["collapse"]
    assert run["collapse"] == (collapse["last_stable"], collapse["first_failed"])
    assert len(run["summary"]["collapse"]["trials"]) == collapse["trials"]
