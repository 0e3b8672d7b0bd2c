"""Shared paths for the Python tests: the source tree (scenarios, examples) and the build folder
(the blockdem program), from BLOCKDEM_SOURCE_DIR / BLOCKDEM_BUILD_DIR (set by ctest)."""
import math
import os
import pathlib

import pytest

SOURCE = pathlib.Path(os.environ.get("BLOCKDEM_SOURCE_DIR",
                                     pathlib.Path(__file__).resolve().parents[2]))
BUILD = pathlib.Path(os.environ.get("BLOCKDEM_BUILD_DIR", SOURCE / "build"))


@pytest.fixture
def source_dir():
    return SOURCE


@pytest.fixture
def cli():
    """The blockdem program of the same build."""
    path = BUILD / "blockdem"
    if not path.exists():
        pytest.skip(f"no blockdem program in {BUILD}")
    return path


def column_scene(bd):
    """scenarios/examples/column.toml, written with the Scene API: three 46 mm gypsum cubes on a
    fixed base, settled at 1 g then 10 g."""
    scene = bd.Scene(title="Three-block column on a fixed base")
    scene.settings(damping=0.7, rounding_distance=2e-4)
    scene.material("gypsum", density=1207.0)
    scene.joint_law("joint", normal={"law": "linear", "stiffness": 10e9},
                    shear={"law": "linear", "stiffness": 1e9, "friction_deg": 40})
    scene.block("base", material="gypsum", size=[0.2, 0.2, 0.05], position=[0.0, 0.0, -0.025],
                motion="fixed")
    for i, z in enumerate([0.023, 0.069, 0.115], start=1):
        scene.block(f"b{i}", material="gypsum", size=[0.046, 0.046, 0.046],
                    position=[0.0, 0.0, z])
    scene.stage("settle at 1 g", gravity=[0.0, 0.0, -9.81])
    scene.stage("settle at 10 g", gravity=[0.0, 0.0, -98.1])
    return scene


def cohesive_block_scene(bd, collapse_tolerance):
    """A 0.5 kg block (0.1 x 0.1 x 0.02 m) on a fixed plane, gravity tilted 30 degrees, joint
    friction 20 degrees and cohesion 453.2 Pa: settled at 1 g, then loaded towards 10 g with a
    collapse search (it slides near 5 g)."""
    th = math.radians(30)
    d = [math.sin(th), 0.0, -math.cos(th)]
    scene = bd.Scene()
    scene.settings(damping=0.7, contact_mode="boon2012")
    scene.joint_law("j", normal={"law": "linear", "stiffness": 1e10},
                    shear={"law": "linear", "stiffness": 1e9, "friction_deg": 20,
                           "cohesion": 453.2})
    scene.box("base", size=[1.0, 0.3, 0.05], position=[0, 0, -0.025], density=2500.0,
              motion="fixed")
    scene.box("block", size=[0.1, 0.1, 0.02], position=[0, 0, 0.01], density=2500.0)
    scene.stage("settle", gravity=[9.81 * x for x in d])
    scene.stage("load", gravity=[10 * 9.81 * x for x in d], ramp_steps=2000, find_collapse=True,
                collapse_tolerance=collapse_tolerance)
    return scene
