"""The study commands from Python: the same reports as the program, and their closed forms."""
import json
import math
import subprocess

import pytest

import blockdem as bd


def test_analytic_voussoir_moment_equilibrium_and_the_programs_report(cli):
    # Diederichs & Kaiser (1999): the thrust times the lever arm carries the midspan moment of a
    # simply supported beam, T Z = gamma d S^2 / 8 (per unit width), to the solver's 1e-9 in n.
    span, depth, rho, g, modulus = 0.276, 0.046, 1207.0, 98.1, 4.6e8
    r = bd.analytic_voussoir(span=span, depth=depth, density=rho, gravity=g, modulus=modulus)
    assert r["thrust_N_per_m"] * r["lever_arm_m"] == pytest.approx(
        rho * g * depth * span**2 / 8, rel=1e-6)
    out = subprocess.run([str(cli), "analytic", "voussoir", "--span", str(span), "--depth",
                          str(depth), "--density", str(rho), "--gravity", str(g), "--modulus",
                          str(modulus)], check=True, capture_output=True, text=True).stdout
    assert json.loads(out) == r
    with pytest.raises(ValueError, match="density"):
        bd.analytic_voussoir(span=span, depth=depth, density=-1.0, gravity=g, modulus=modulus)


def test_lab_compression_linear_law_closed_form(tmp_path):
    # A linear joint: sigma = k_n u, so the path's peak stress is k_n u_max exactly.
    r = bd.lab_compression(normal="law=linear,stiffness=1e10", max_closure=1e-4, out=tmp_path)
    assert r["kernel"]["max_stress_Pa"] == pytest.approx(1e10 * 1e-4, rel=1e-12)
    assert r["kernel"]["secant_stiffness_Pa_per_m"] == pytest.approx(1e10, rel=1e-12)
    assert (tmp_path / "compression.csv").stat().st_size > 0
    with pytest.raises(ValueError):
        bd.lab_compression(normal="law=elastic")


def test_lab_shear_caps_at_mohr_coulomb():
    # A linear shear law under constant sigma_n slides at tau = sigma_n tan(phi) (no cohesion).
    r = bd.lab_shear(shear="law=linear,stiffness=1e9,friction_deg=30", normal_stress=1e6,
                     max_displacement=5e-3, steps=500)
    peak = r["kernel"]["peak_shear_stress_Pa"]
    assert peak == pytest.approx(1e6 * math.tan(math.radians(30)), rel=1e-6)


def test_calibrate_normal_recovers_the_generating_law(source_dir, tmp_path):
    # The synthetic file was made with a = 54050 Pa, b = 37000 1/m and 2 % noise (its header).
    r = bd.calibrate_normal(source_dir / "data/synthetic/column_compression_eq4.csv",
                            modulus=5.6e9, height=0.138, joints=3, out=tmp_path)
    assert r["exponential"]["a_Pa"] == pytest.approx(54050.0, rel=0.05)
    assert r["exponential"]["b_per_m"] == pytest.approx(37000.0, rel=0.05)
    assert json.loads((tmp_path / "calibration.json").read_text())["exponential"] == \
        r["exponential"]
    with pytest.raises(ValueError):
        bd.calibrate_normal(source_dir / "data/synthetic/column_compression_eq4.csv",
                            modulus=-1.0, height=0.138, joints=3)


def test_calibrate_shear_laws_run(source_dir):
    shear = bd.calibrate_shear(source_dir / "data/synthetic/direct_shear_eq5.csv")
    cy = bd.calibrate_continuously_yielding(source_dir / "data/synthetic/direct_shear_cy.csv")
    assert shear["command"].startswith("calibrate") and cy["command"].startswith("calibrate")


def test_reproduce_one_case(tmp_path):
    runs = bd.reproduce_boon2015(tmp_path, cases=["T2-1"], modes="boon2012", jobs=1)
    assert [r["id"] for r in runs] == ["T2-1"]
    assert runs[0]["status"] == "completed" and runs[0]["summary"]["g_max"] > 0
    assert (tmp_path / "report.md").stat().st_size > 0
    assert (tmp_path / "T2-1" / "summary.json").exists()
    with pytest.raises(ValueError):
        bd.reproduce_boon2015(tmp_path, modes="both-ish")
