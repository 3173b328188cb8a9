"""The fabric study's arithmetic on made-up data: the empty bag's share of the load at the filled
bag's gap (tbagspost.fabric), the sand-alone bounds of S/F_v from a triaxial peak ratio
(tbagspost.bounds), the design presets' comparison of two fabrics (tbagspost.fabrics), and the
presets' fabric choices (launcher/tbagsrun/presets.py)."""
import math
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "postprocess"))
sys.path.insert(0, str(ROOT / "launcher"))
from tbagspost import bounds, fabric, fabrics  # noqa: E402
from tbagsrun.presets import PRESETS  # noqa: E402


def press_csv(path, fabric_name, rows):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("# press.csv: gap0_mm 24.0 H_mm 25.000 fabric %s vpress 0.02\n"
                    "gap_mm,Fv_N,S_N,steps,Fv_min_N,Fv_max_N\n# Fix print output\n" % fabric_name
                    + "".join("%g,%g,0,100,%g,%g\n" % (g, f, f, f) for g, f in rows))


def test_empty_share_at_the_filled_gap(tmp_path):
    # filled: 0 N at 24 mm, 20 N at 23, 60 N at 22 -> 40 N at 22.5 mm; empty: 4 N at 22 mm, 2 at 23
    press_csv(tmp_path / "f" / "press.csv", "woven", [(25, 0), (24, 0), (23, 20), (22, 60)])
    press_csv(tmp_path / "e" / "press.csv", "woven", [(24, 0), (23, 2), (22, 4), (12.5, 100)])
    r = fabric.alone(tmp_path / "e" / "press.csv", tmp_path / "f" / "press.csv", 40.0)
    assert r["gap_filled_mm"] == pytest.approx(22.5)
    assert r["F_empty"] == pytest.approx(3.0) and r["share"] == pytest.approx(0.075)
    assert r["F_empty_end"] == 100 and r["gap_end_mm"] == 12.5
    # an empty bag not yet touched at that gap carries nothing
    assert fabric.force_at([20.0, 19.0], [0.0, 5.0], 22.5) == 0.0
    with pytest.raises(ValueError):
        fabric.alone(tmp_path / "e" / "press.csv", tmp_path / "f" / "press.csv", 1000.0)


def test_sand_bounds_from_the_peak_ratio(tmp_path):
    report = tmp_path / "report.md"
    report.write_text("| start (paper) | 0.31 | 0.05 | 1.8 | 0.6 | 0.6 | 0.5 | 0.7 | 2.306 / 4.560 (-49.4 %) | "
                      "2.284 / 4.240 (-46.1 %) | 2.192 / 4.120 (-46.8 %) | yes |\n"
                      "| best | 0.83 | 0.24 | 1.8 | 0.1 | 0.1 | 0.1 | 0.2 | 3.0 / 4.560 (x) | 3.5 / 4.2 (x) | yes |\n")
    b = bounds.sand_bounds("paper", report)
    assert b["sin"] == pytest.approx(1.306 / 3.306) and b["tan"] == pytest.approx(math.tan(math.asin(1.306 / 3.306)))
    assert bounds.sand_bounds("calibrated", report)["sin"] == pytest.approx(2.5 / 4.5)
    with pytest.raises(ValueError):
        bounds.peak_ratio("toyoura", report)
    # several samples per pressure: the mean, not its standard deviation
    report.write_text("| best | 0.38 | 0.42 | 4.98 | 0.09 | 0.08 | 0.09 | 0.09 | 4.388 +- 0.028 / 4.560 (-3.8 %) | "
                      "4.132 +- 0.202 / 4.240 (-2.6 %) | 4.033 +- 0.053 / 4.120 (-2.1 %) | yes |\n")
    assert bounds.peak_ratio("calibrated", report) == 4.388
    # the repository's own reports: the paper sand peaks near sin phi 0.39, the calibrated near 0.62
    assert bounds.sand_bounds("paper")["sin"] == pytest.approx(0.395, abs=0.01)
    assert bounds.sand_bounds("calibrated")["sin"] == pytest.approx(0.621, abs=0.01)


def design_figures(folder, k0, keq, heq):
    folder.mkdir(parents=True)
    (folder / "ro_parameters.csv").write_text(
        "run,Fv_N,K0_N_per_mm,K0_sd,Sy_N,Sy_sd,r,r_sd,rms_tips,rms_loops\nF5500,318,%g,1,400,1,3,0.1,0.1,0.1\n" % k0)
    (folder / "cyclic_table.csv").write_text(
        "run,Fv_N,amp,cycle,ua_nominal_mm,ua_mm,S_a_N,K_eq_N_per_mm,W_d_J,h_eq,Fv_mean_N,w_end_mm\n"
        + "".join("F5500,318,1,%d,0.25,0.25,100,%g,0.01,%g,318,0\n" % (c, keq * (1 + 0.1 * c), heq) for c in (1, 2, 3)))


def test_two_fabrics_compared(tmp_path):
    design_figures(tmp_path / "solid", 500, 400, 0.10)
    design_figures(tmp_path / "woven", 100, 120, 0.25)
    fa, fb, cyc, ro = fabrics.compare({"solid": tmp_path / "solid", "woven": tmp_path / "woven"})
    assert (fa, fb) == ("solid", "woven")
    assert len(cyc) == 1 and cyc[0]["K_eq_solid"] == pytest.approx(520)    # the last cycle
    assert cyc[0]["K_ratio"] == pytest.approx(0.3) and cyc[0]["h_diff"] == pytest.approx(0.15)
    assert ro[0]["K0_N_per_mm_ratio"] == pytest.approx(0.2)
    text = fabrics.write(tmp_path, {"solid": tmp_path / "solid", "woven": tmp_path / "woven"})
    assert "| F5500 | 0.25 | 520.0 | 156.0 | 0.30 | 0.100 | 0.250 | +0.150 |" in text
    assert (tmp_path / "fabrics.csv").exists()


def test_presets_choose_their_fabrics():
    for name in ("demo", "trends", "quasistatic", "paper"):
        assert "fabric solid" in PRESETS[name].defaults_said["fabric"], name
        assert not PRESETS[name].fabrics
    for name in ("cyclic", "stack"):
        assert PRESETS[name].fabrics == ("solid", "woven"), name


def test_fabric_command_refuses_gap_final():
    """./tbags fabric -var gap_final (which in.press reads as the end of every press) is refused,
    saying where each press ends (before, the strength press stopped with a Python TypeError:
    gap_final given twice)."""
    from tbagsrun import LaunchError, fabric as command
    assert command.parse(["--size", "9", "9", "5"]).size == [9, 9, 5]
    with pytest.raises(LaunchError, match="empty bags are pressed to half their height"):
        command.parse(["-var", "gap_final", "0.9"])
