"""`blockdem run` (bd.run) and Simulation.run_stage drive the stages with one driver: the same
scenario gives the same steps per stage, the same factor of safety and the same collapse bracket,
bit for bit (each front end is the other's oracle)."""
import blockdem as bd
from conftest import cohesive_block_scene


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
    # The trials placed by the extrapolated critical factor, alike in both.
    assert (fos["search"], fos["extrapolated"]) == (stages[-1]["search"],
                                                    stages[-1]["extrapolated"])
    assert fos["search"] == "extrapolate"


def test_collapse_search_is_the_same_in_both_front_ends(tmp_path):
    # A cohesive block loaded until it slides (conftest.py), with a wide bracket.
    sc = cohesive_block_scene(bd, collapse_tolerance=0.5).build()
    run = bd.run(sc, tmp_path)
    stages = stages_of_simulation(sc)
    assert run["status"] == "collapsed" and run["exit_code"] == 0
    assert run["steps_per_stage"] == [s["steps"] for s in stages]
    collapse = stages[-1]["collapse"]
    assert run["collapse"] == (collapse["last_stable"], collapse["first_failed"])
    assert len(run["summary"]["collapse"]["trials"]) == collapse["trials"]
