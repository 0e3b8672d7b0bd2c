"""blockdem from Python: build scenes with the names of the TOML scenario files, run them stage by
stage or step by step with callbacks, read the state as NumPy arrays, and run the studies.
docs/python.md is the reference."""
import os as _os
import pathlib as _pathlib
import shutil as _shutil

from ._core import (DivergenceError, Scenario, ScenarioError, Simulation, analytic_voussoir,
                    calibrate_continuously_yielding, calibrate_normal, calibrate_shear,
                    lab_compression, lab_shear, run_scenario)
from . import _core
from .scene import Scene

__all__ = ["DivergenceError", "Scenario", "ScenarioError", "Scene", "Simulation",
           "analytic_voussoir", "calibrate_continuously_yielding", "calibrate_normal",
           "calibrate_shear", "data_dir", "lab_compression", "lab_shear", "load",
           "reproduce_boon2015", "run", "run_scenario"]


def load(path):
    """Reads and checks a TOML scenario file (as `blockdem run`)."""
    return Scenario.load(str(path))


def run(scenario, out, progress=None):
    """Runs a Scenario, a Scene or a TOML file path with every stage and writes the outputs of
    `blockdem run` into `out` (summary.json, history.csv, ...); returns a dict with status,
    message, exit_code, steps, wall_time (s), factor_of_safety, collapse (g) and summary."""
    if isinstance(scenario, Scene):
        scenario = scenario.build()
    elif not isinstance(scenario, Scenario):
        scenario = load(scenario)
    out = _pathlib.Path(out)
    existed = out.exists()
    try:
        return run_scenario(scenario, str(out), progress)
    except ValueError:
        # Some input errors show only while running (strength-reduction bounds that do not
        # bracket the failure): as `blockdem run`, leave nothing written.
        if not existed:
            _shutil.rmtree(out, ignore_errors=True)
        else:
            for name in _core.run_output_names():
                target = out / name
                if target.is_dir():
                    _shutil.rmtree(target, ignore_errors=True)
                elif target.exists():
                    target.unlink()
        raise


def data_dir():
    """The folder of blockdem's data (scenarios/, tools/): BLOCKDEM_DATA_DIR when set, else
    share/blockdem of the build folder or of the installation prefix holding this package."""
    env = _os.environ.get("BLOCKDEM_DATA_DIR")
    if env:
        return _pathlib.Path(env)
    here = _pathlib.Path(__file__).resolve().parent
    # BUILD/python/blockdem, or PREFIX/lib/python3/dist-packages/blockdem.
    for root in (here.parents[1], here.parents[3]):
        if (root / "share" / "blockdem" / "scenarios").is_dir():
            return root / "share" / "blockdem"
    raise FileNotFoundError("blockdem: no share/blockdem beside the package; set BLOCKDEM_DATA_DIR")


def reproduce_boon2015(out, cases=(), modes="both", jobs=0, scenarios=None, progress=None):
    """The reproduction of Boon, Houlsby & Utili (2015), as `blockdem reproduce boon2015
    --no-figures`: each case into out/<id>, out/report.md; one dict per case. `cases` as
    ["T2-1", "T2-1-fi"] (empty: all), modes "both", "boon2012" or "face_integrated"."""
    folder = _pathlib.Path(scenarios) if scenarios else data_dir() / "scenarios" / "boon2015"
    return _core.reproduce_boon2015(str(out), scenarios=str(folder), cases=list(cases),
                                    modes=modes, jobs=jobs, progress=progress)
