"""tbagspost/rate.py on synthetic runs: the fastest speed within the realizations' spread is
chosen; a speed whose mean S leaves the spread fails, and so does every faster one; one
realization gives no choice."""
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "postprocess"))
from tbagspost import rate  # noqa: E402


def write(folder, S, w, inertial):
    folder.mkdir(parents=True)
    u = np.arange(0, 5.0001, 0.1)
    with open(folder / "shear.csv", "w") as f:
        f.write("time_s,u_mm,w_mm,S_N,Fv_N\n")
        for k, x in enumerate(u):
            f.write("%g,%g,%g,%g,%g\n" % (k * 0.01, x, w(x), S(x), 212.0))
    (folder / "log.shear").write_text("INERTIAL: shear rate 1 1/s, mean stress 12.5 kPa, inertial "
                                      "number %.2e (quasi-static below 1e-3)\n" % inertial)


def make(root, offsets, n=3, spread=10.0):
    """n realizations; speed m's mean S shifted by offsets[m] N; each realization off by
    -spread, 0, +spread (sd = spread for n = 3)."""
    for k in range(n):
        dev = (k - 1) * spread
        for m, off in offsets.items():
            write(root / ("r%d" % (k + 1)) / ("I%d" % m),
                  lambda x, o=off, d=dev: 400 * (1 - np.exp(-x)) + o + d,
                  lambda x, d=dev: -0.05 * x + 1e-3 * d, 1.2e-4 * m)
    return root


def test_fastest_within_spread_is_chosen(tmp_path):
    root = make(tmp_path / "a", {1: 0.0, 2: 3.0, 4: 6.0, 8: 30.0})
    text, chosen = rate.report(root)
    assert chosen == 4
    rows = {r["m"]: r for r in rate.study(root)[0]}
    assert abs(rows[8]["dS"] - 30.0) < 0.5 and abs(rows[8]["sS"] - 10.0) < 0.5 and rows[8]["passed"] is False
    assert rows[4]["passed"] and abs(rows[2]["inertial"] - 2.4e-4) < 1e-9
    assert "Chosen: 4 x" in text and (root / "rate.csv").is_file()


def test_a_failing_speed_stops_the_choice(tmp_path):
    # 2x out of the spread: 4x back inside does not count
    _, chosen = rate.report(make(tmp_path / "b", {1: 0.0, 2: 25.0, 4: 2.0}))
    assert chosen == 1
    _, chosen = rate.report(make(tmp_path / "c", {1: 0.0, 2: 2.0, 4: 4.0, 8: 5.0}))
    assert chosen == 8


def test_one_realization_no_choice(tmp_path):
    text, chosen = rate.report(make(tmp_path / "d", {1: 0.0, 2: 1.0}, n=1))
    assert chosen is None and "no spread" in text


def test_inertial_number_from_the_sands_stress(tmp_path, monkeypatch):
    """With contact dumps, the sand's share of F_v (load path at mid-height) sets the sand's own
    inertial number, I / sqrt(share): a share of 0.04 makes it 5x the nominal."""
    root = make(tmp_path / "e", {1: 0.0, 2: 1.0})
    for f in root.rglob("I*"):
        (f / "dump.contacts.100").write_text("")
    monkeypatch.setattr(rate.Run, "at_step", lambda self, step, column="u_mm": 212.0 if column == "Fv_N" else 1.0)
    monkeypatch.setattr(rate.loadpath, "by_step", lambda run: {100: {"sand-sand": (0.04 * 212.0, 0.0, 10)}})
    rows = {r["m"]: r for r in rate.study(root)[0]}
    assert abs(rows[1]["share"] - 0.04) < 1e-12
    assert abs(rows[2]["inertial_sand"] - 5 * rows[2]["inertial"]) < 1e-12
    assert "| 0.04 | 1.20e-03 |" in rate.report(root)[0]


def test_the_share_is_kept_when_the_dumps_go(tmp_path, monkeypatch):
    """The share is kept beside the run with its dumps' steps: read again while the dumps are the
    same or gone (a committed study has no dumps), measured again when they changed."""
    root = make(tmp_path / "f", {1: 0.0, 2: 1.0})
    run = root / "r1" / "I1"
    (run / "dump.contacts.100").write_text("")
    share = {"value": 0.04}
    monkeypatch.setattr(rate.Run, "at_step", lambda self, step, column="u_mm": 212.0 if column == "Fv_N" else 1.0)
    monkeypatch.setattr(rate.loadpath, "by_step",
                        lambda r: {100: {"sand-sand": (share["value"] * 212.0, 0.0, 10)}})
    assert abs(rate.sand_share(run) - 0.04) < 1e-12
    assert (run / rate.SHARE_FILE).read_text().split()[1:] == ["100"]
    share["value"] = 0.5                       # kept: the same dumps are not read again
    assert abs(rate.sand_share(run) - 0.04) < 1e-12
    (run / "dump.contacts.100").unlink()       # gone: the kept share
    assert abs(rate.sand_share(run) - 0.04) < 1e-12
    (run / "dump.contacts.200").write_text("")  # other dumps: measured again
    assert abs(rate.sand_share(run) - 0.5) < 1e-12
    assert np.isnan(rate.sand_share(root / "r1" / "I2"))    # neither dumps nor a kept share


def test_the_runs_summary_gives_both_inertial_numbers(tmp_path, monkeypatch):
    """A shear run's summary line: the nominal inertial number and the sand's, I / sqrt(share),
    the share averaged over the dumps while shearing only (u > 0); none without the INERTIAL line."""
    run_dir = tmp_path / "run"
    write(run_dir, lambda x: 100.0, lambda x: 0.0, 2.0e-4)
    at = {100: 0.0, 200: 1.0, 300: 2.0}          # u (mm) of each dump step; the first before shear
    share = {100: 0.9, 200: 0.04, 300: 0.04}
    monkeypatch.setattr(rate.Run, "at_step", lambda self, step, column="u_mm": 212.0 if column == "Fv_N" else at[step])
    found = {s: {"sand-sand": (share[s] * 212.0, 0.0, 10)} for s in at}
    line = rate.describe_inertial(rate.Run(run_dir), found)
    assert "2.00e-04 nominal" in line and "1.00e-03 from the sand's own stress" in line
    assert "4 % of F_v" in line and "2 dumps" in line
    (run_dir / "log.shear").unlink()
    assert rate.describe_inertial(rate.Run(run_dir), found) is None
