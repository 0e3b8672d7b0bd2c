"""A scene built in Python and the same TOML file run by `blockdem run` give bit-identical outputs
(the same reader, the same world, the same step)."""
import json
import subprocess

import pytest

import blockdem as bd
from conftest import column_scene


def test_python_scene_matches_toml_run_bit_for_bit(tmp_path, cli, source_dir):
    toml_file = source_dir / "scenarios/examples/column.toml"
    cli_out, py_out = tmp_path / "cli", tmp_path / "python"
    subprocess.run([str(cli), "run", str(toml_file), "--out", str(cli_out), "--quiet",
                    "--no-figures"], check=True)
    r = bd.run(column_scene(bd), py_out)
    assert r["status"] == "completed" and r["exit_code"] == 0
    for name in ["history.csv", "blocks.csv", "contacts.csv"]:
        assert (py_out / name).read_bytes() == (cli_out / name).read_bytes(), name
    for vtk in (cli_out / "vtk").iterdir():
        assert (py_out / "vtk" / vtk.name).read_bytes() == vtk.read_bytes(), vtk.name
    a = json.loads((cli_out / "summary.json").read_text())
    b = json.loads((py_out / "summary.json").read_text())
    assert b == r["summary"]
    # Only where the scenario came from and the wall time differ, and report.md, which names
    # where the scenario came from.
    assert (cli_out / "report.md").exists() and (py_out / "report.md").exists()
    for s in (a, b):
        del s["wall_time_s"], s["scenario"]
        s["files"] = [f for f in s["files"] if f["path"] != "report.md"]
    assert a == b


def test_run_accepts_a_path_and_reports_progress(tmp_path, source_dir):
    lines = []
    r = bd.run(source_dir / "scenarios/examples/column.toml", tmp_path, progress=lines.append)
    assert r["status"] == "completed" and r["steps"] == sum(r["steps_per_stage"])
    assert any("settle at 10 g" in line for line in lines)
    assert (tmp_path / "summary.json").exists()


def test_a_run_without_stages_is_an_input_error(tmp_path):
    scene = column_scene(bd)
    del scene.data["stages"]
    try:
        bd.run(scene, tmp_path / "out")
    except bd.ScenarioError as e:
        assert e.key == "stages"
    else:
        raise AssertionError("no error")
    assert not (tmp_path / "out").exists()


def test_rock_mass_from_a_scene_matches_the_program(tmp_path, cli, source_dir):
    # The tunnel (joint sets, an excavation) read into a Scene, capped at 200 steps a stage like
    # `blockdem run --max-steps 200`: the same outputs, bit for bit (a stage cut short is
    # reported as not converged by both).
    toml_file = source_dir / "scenarios/examples/tunnel.toml"
    cli_out, py_out = tmp_path / "cli", tmp_path / "python"
    done = subprocess.run([str(cli), "run", str(toml_file), "--out", str(cli_out), "--quiet",
                           "--no-figures", "--max-steps", "200"])
    scenario = bd.Scene.from_toml(toml_file).build()
    scenario.limit_steps(200)
    r = bd.run(scenario, py_out)
    assert r["exit_code"] == done.returncode == 3 and r["status"] == "not_converged"
    for name in ["history.csv", "blocks.csv", "contacts.csv"]:
        assert (py_out / name).read_bytes() == (cli_out / name).read_bytes(), name


def test_an_input_error_found_while_running_keeps_the_run(tmp_path, source_dir):
    # Factor bounds that do not bracket the failure are found only by the search: as `blockdem
    # run`, the run ends with status input_error and exit code 2, the message names the stage's
    # key, and what the run wrote before the stage stays, with the state before it saved.
    scene = bd.Scene.from_toml(source_dir / "scenarios/examples/planar_sliding.toml")
    scene.data["stages"][2]["factor_bounds"] = [2.0, 3.0]  # F = 1.45 fails at both
    r = bd.run(scene, tmp_path / "out")
    assert r["status"] == "input_error"
    assert r["exit_code"] == 2
    assert "stages[3].factor_bounds" in r["message"]
    for kept in ("summary.json", "history.csv", "checkpoint.bdck"):
        assert (tmp_path / "out" / kept).exists(), kept
    assert r["summary"]["stages"][2]["status"] == "input_error"
