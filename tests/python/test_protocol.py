"""tbagspost/protocol.py on synthetic runs: the fastest approach whose compressed state (w at F_v,
paired by fill) and start of shear stay within the fills' spread is chosen; a shift of w at F_v,
of S, or F_v off its target fails a variant and every faster one; a short fill is compared fill
by fill; missing lines stop with one message."""
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "postprocess"))
from tbagspost import protocol  # noqa: E402

DT = 1.5e-6


def write_run(folder, steps, w0, S_off, fv=596.0):
    folder.mkdir(parents=True)
    u = np.arange(0, 1.0001, 0.05)
    with open(folder / "shear.csv", "w") as f:
        f.write("time_s,u_mm,w_mm,S_N,Fv_N\n")
        for k, x in enumerate(u):
            f.write("%.9g,%g,%g,%g,%g\n" % (steps * DT + k * 1e-3, x, w0 - 0.02 * x, 80 * (1 - np.exp(-5 * x)) + S_off, fv))
    (folder / "log.shear").write_text("TIMESTEP: Hertz ... using %g s\nCOMPRESSED: F_v 596.10 N (target 596.00), "
                                      "w -3.000 mm\n" % DT)


def write_fill(folder, settle, e, coordination):
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "log.fill").write_text(
        "SETTLED: after %d steps, KE per particle 1e-07 J\nFILL 28 x 28 x 7: 20000 grains, void ratio 0.6810, "
        "coordination %.2f, max overlap 0.01 mm (sand-sand) 0.01 mm (any), KE per particle 1e-07 J, bond ends 1 of 1; "
        "void ratio measured %.4f (inner box 130.00 x 130.00 x 25.00 mm)\n" % (settle, coordination, e))


def make(root, shifts, n=3, sd_w=0.05, sd_S=4.0, fv=None, settle=40000):
    """n fills whose w at F_v differ by (k - 1) sd_w and S by (k - 1) sd_S; approach k mm/s
    shifted by shifts[k] = (dw, dS) in every fill."""
    for r in range(n):
        dev = r - 1
        write_fill(root / ("r%d" % (r + 1)), settle + 5000 * dev, 0.80 + 0.01 * dev, 4.5 + 0.05 * dev)
        for k, (dw, dS) in shifts.items():
            write_run(root / ("r%d" % (r + 1)) / ("V%d" % k), 70000 * 20 // k, -3.0 + dev * sd_w + dw,
                      dev * sd_S + dS, (fv or {}).get(k, 596.0))
    return root


def test_fastest_within_the_spread_is_chosen(tmp_path):
    root = make(tmp_path / "a", {20: (0, 0), 50: (0.01, 1.0), 100: (0.03, 2.0), 200: (0.2, 2.0)})
    text, chosen = protocol.report(root)
    assert chosen == 100
    rows = {r["k"]: r for r in protocol.study(root)[0]}
    assert rows[200]["dw"] == pytest.approx(0.2) and rows[200]["sd_w_pooled"] == pytest.approx(0.05)
    assert rows[200]["passed"] is False and rows[100]["passed"] is True
    assert rows[50]["steps"] == pytest.approx(28000)
    # dw as a void ratio: (1 + e) dw / H_in, e 0.79/0.80/0.81, H_in 25 mm
    assert rows[200]["de"] == pytest.approx(1.80 * 0.2 / 25, rel=1e-3)
    assert "Chosen: an approach at 100 mm/s" in text and (root / "protocol.csv").is_file()


def test_a_failing_variant_stops_the_choice_and_each_measure_can_fail_it(tmp_path):
    # S shifted by 3 sd at 50 mm/s: 100 mm/s back inside does not count
    assert protocol.report(make(tmp_path / "b", {20: (0, 0), 50: (0, 12.0), 100: (0, 0)}))[1] == 20
    # F_v held 0.5 % off its target at 50 mm/s
    assert protocol.report(make(tmp_path / "c", {20: (0, 0), 50: (0, 0)}, fv={50: 599.0}))[1] == 20
    assert protocol.report(make(tmp_path / "d", {20: (0, 0), 50: (0, 0)}))[1] == 50


def test_one_realization_no_choice(tmp_path):
    text, chosen = protocol.report(make(tmp_path / "e", {20: (0, 0), 50: (0, 0)}, n=1))
    assert chosen is None and "no spread" in text


def test_a_short_fill_is_compared_fill_by_fill(tmp_path):
    root = make(tmp_path / "f", {20: (0, 0), 50: (0, 0)})
    short = make(tmp_path / "g", {20: (0.01, 0.5)}, settle=20000)
    text, _ = protocol.report(root, short)
    rows, chosen, fills = protocol.study(root, short)
    assert rows[-1]["label"] == "short fill" and rows[-1]["passed"] is True and chosen == 50
    settle = next(f for f in fills if f["key"] == "settle")
    assert settle["diff"] == pytest.approx(-20000) and settle["sd"] == pytest.approx(5000)
    assert "| settle | 4e+04 | 2e+04 |" in text
    shifted = make(tmp_path / "h", {20: (0.2, 0)}, settle=20000)
    assert protocol.study(root, shifted)[0][-1]["passed"] is False


def test_missing_lines_stop_with_one_message(tmp_path):
    root = make(tmp_path / "i", {20: (0, 0), 50: (0, 0)})
    (root / "r2" / "log.fill").write_text("nothing here\n")
    with pytest.raises(SystemExit, match=r"no FILL line in .*r2/log.fill"):
        protocol.study(root)
    with pytest.raises(SystemExit, match="no approach folders"):
        protocol.study(tmp_path / "empty")
