"""The examples of examples/python/ run in their short versions and write what they say."""
import csv
import subprocess
import sys

import pytest


@pytest.mark.parametrize("name, outputs", [
    ("column_history.py", ["column_history.csv"]),
    ("voussoir_gravity_path.py", ["sag_history.csv", "sag_vs_gravity.png"]),
    ("stiffness_study.py", ["stiffness_study.csv", "stiffness_study.png"]),
])
def test_example_runs(name, outputs, source_dir, tmp_path):
    run = subprocess.run([sys.executable, str(source_dir / "examples/python" / name), "--out",
                          str(tmp_path), "--short"], capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    for out in outputs:
        assert (tmp_path / out).stat().st_size > 0, out


def test_column_history_settles_to_the_closed_form(source_dir, tmp_path):
    # The recorded top-block height ends at its start minus the three joints' closures
    # (3 + 2 + 1) W / (k_n A), W = rho g a^3 (linear joints), within 2 %.
    subprocess.run([sys.executable, str(source_dir / "examples/python/column_history.py"),
                    "--out", str(tmp_path)], check=True, capture_output=True)
    with open(tmp_path / "column_history.csv") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) > 5
    edge, rho, g, kn = 0.046, 1207.0, 9.81, 10e9
    drop = 6 * rho * g * edge**3 / (kn * edge**2)
    final = float(rows[-1]["top_z_m"])
    assert 2.5 * edge - final == pytest.approx(drop, rel=0.02)
