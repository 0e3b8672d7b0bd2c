"""Scenes from Python go through the TOML reader: the same checks and the same messages as a
scenario file run by `blockdem run`, raised as blockdem.ScenarioError (a ValueError)."""
import subprocess
import tomllib

import numpy as np
import pytest

import blockdem as bd
from blockdem.toml_writer import dumps
from conftest import column_scene


def test_module_is_the_built_package():
    assert bd.Scene and bd.Simulation and issubclass(bd.ScenarioError, ValueError)
    assert issubclass(bd.DivergenceError, RuntimeError)


def test_toml_writer_round_trips_values_exactly():
    # repr() of a double reads back to the same double: tomllib is an independent reader.
    data = {"title": 'quote " and \\ and ü', "x": 0.1 + 0.2, "tiny": 5e-324, "big": 1.7976931348623157e308,
            "n": -3, "flag": True, "v": np.array([1.0, 2.5e-7, -0.0]),
            "t": {"a": [[1, 2], [3, 4]], "inline": {"k": 1.25}},
            "rows": [{"name": "a", "sub": {"law": "linear"}}, {"name": "b"}]}
    back = tomllib.loads(dumps(data))
    assert back["x"] == 0.1 + 0.2 and back["tiny"] == 5e-324 and back["big"] == data["big"]
    assert back["title"] == data["title"] and back["n"] == -3 and back["flag"] is True
    assert back["v"] == [1.0, 2.5e-7, -0.0]
    assert back["t"] == data["t"] and back["rows"] == data["rows"]


def test_scene_reads_like_its_toml_file(source_dir):
    # The Python column and the example file describe the same scenario.
    scene = column_scene(bd)
    with open(source_dir / "scenarios/examples/column.toml", "rb") as f:
        assert tomllib.loads(scene.to_toml()) == tomllib.load(f)
    sc = scene.build()
    assert sc.block_names == ["base", "b1", "b2", "b3"]
    assert sc.stage_names == ["settle at 1 g", "settle at 10 g"]
    assert sc.joint_law_names == ["joint"] and sc.file == "<python>"


def test_errors_are_the_programs_messages(tmp_path, cli):
    # A negative density, an unknown key and a bad law name: the Python error text must be the
    # line `blockdem run` prints for the same file.
    cases = [("blocks", 1, "density", -5.0), ("blocks", 2, "colour", "red"),
             ("joint_laws", 0, "normal", {"law": "elastic", "stiffness": 1e9})]
    for table, index, key, bad in cases:
        scene = column_scene(bd)
        scene.data[table][index][key] = bad
        path = tmp_path / f"bad_{key}.toml"
        scene.file = str(path)
        scene.save(path)
        with pytest.raises(bd.ScenarioError) as err:
            scene.build()
        run = subprocess.run([str(cli), "run", str(path), "--out", str(tmp_path / "out")],
                             capture_output=True, text=True)
        assert run.returncode == 2
        assert f"blockdem: error: {err.value}" in run.stderr
        assert err.value.file == str(path)
        assert str(err.value) == f"{err.value.file}: {err.value.key}: {err.value.reason}"
        assert not (tmp_path / "out").exists()


def test_error_attributes_name_the_key():
    scene = column_scene(bd)
    scene.data["blocks"][1]["density"] = -5.0
    del scene.data["blocks"][1]["material"]
    with pytest.raises(ValueError) as err:
        scene.build()
    assert err.value.key.startswith("blocks[") and "density" in err.value.key
    assert err.value.file == "<python>"


def test_from_toml_then_change(source_dir):
    scene = bd.Scene.from_toml(source_dir / "scenarios/examples/column.toml")
    scene.data["stages"] = scene.data["stages"][:1]
    scene.box("b4", size=[0.046] * 3, position=[0.0, 0.0, 0.161], material="gypsum")
    sc = scene.build()
    assert sc.block_names[-1] == "b4" and len(sc.stage_names) == 1
    assert sc.file.endswith("column.toml")


def test_load_missing_file_is_an_error(tmp_path):
    with pytest.raises(bd.ScenarioError, match="cannot open the file"):
        bd.load(tmp_path / "missing.toml")


def test_every_block_shape_and_joint_law():
    # Box, planes and vertices blocks of one unit cube each: the same mass (density 1000).
    cube_planes = [[1, 0, 0, 0.5], [-1, 0, 0, 0.5], [0, 1, 0, 0.5], [0, -1, 0, 0.5],
                   [0, 0, 1, 0.5], [0, 0, -1, 0.5]]
    cube_vertices = [[x, y, z] for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)]
    scene = bd.Scene()
    scene.joint_law("lin", normal={"law": "linear", "stiffness": 1e9},
                    shear={"law": "linear", "stiffness": 1e8, "friction_deg": 30})
    scene.box("box", size=[1, 1, 1], density=1000.0)
    scene.planes_block("planes", cube_planes, density=1000.0, position=[3, 0, 0])
    scene.vertices_block("vertices", cube_vertices, density=1000.0, position=[6, 0, 0])
    scene.stage("free", kind="steps", steps=1)
    sim = scene.simulation()
    np.testing.assert_allclose(sim.masses, [1000.0] * 3, rtol=1e-12)
    np.testing.assert_allclose(sim.positions, [[0, 0, 0], [3, 0, 0], [6, 0, 0]], atol=1e-12)


def _scenario_files():
    import pathlib
    from conftest import SOURCE
    return sorted(pathlib.Path(SOURCE, "scenarios").rglob("*.toml"))


@pytest.mark.parametrize("path", _scenario_files(), ids=lambda p: p.name)
def test_every_shipped_scenario_reads_the_same_through_a_scene(path):
    # Rock masses, excavations, voussoir beams, strength reduction: a file read into a Scene and
    # written back builds the same scenario as the file itself.
    direct = bd.load(path)
    via = bd.Scene.from_toml(path).build()
    assert via.block_names == direct.block_names and len(via.block_names) > 0
    assert via.stage_names == direct.stage_names
    assert via.joint_law_names == direct.joint_law_names
    assert via.title == direct.title and via.warnings == direct.warnings
