"""The cyclic simple shear protocol (inputs/in.cyclic) and its loop analysis on real runs: Coulomb
friction of a sliding block (tests/decks/in.coulomb) gives the closed-form loop; on a tiny bag the
plate follows u(t), F_v is held, the CSV has its rows, cycles and checkpoints, a checkpoint
resumes; bad -var values stop with a message naming the variable."""
import shutil
import sys

import numpy as np
import pytest

import lmprun

sys.path.insert(0, str(lmprun.ROOT / "postprocess"))
from tbagspost import cyclic, hysteresis  # noqa: E402

INPUTS = lmprun.INPUTS
HERE = lmprun.ROOT / "tests" / "decks"
SIZE = lmprun.TINY_BAG
PROTOCOL = dict(SIZE, amps="0.25 0.5", cycles=2, vpeak=0.03)


@pytest.mark.parametrize("mu", [0.3, 0.6])
def test_coulomb_loop_of_a_sliding_block(tmp_path, mu):
    """The block slides on a plate of friction mu under N = 90 N, cycled at 2 mm: the loop's
    half peak-to-peak force is mu N within 1 % and h_eq is 2/pi within 2 % (the elastic part of
    the contacts, about 15 um of slip distance, lowers it by d_y/u_a)."""
    res = lmprun.run(HERE / "in.coulomb", tmp_path, variables={"mu": mu, "ua": 2e-3, "tbags": lmprun.ROOT}).check()
    assert "COULOMB DONE" in res.output
    d = np.genfromtxt(tmp_path / "coulomb.csv", delimiter=",", names=True, comments="#")
    last = d[d["cycle"] == 2]
    m = hysteresis.measure(last["u_mm"], last["S_N"])
    N = last["Fv_N"].mean()
    print("mu %.2f: S_a %.4f N, mu N %.4f N, h_eq %.4f (2/pi %.4f), u_a %.4f mm"
          % (mu, m.S_a, mu * N, m.h_eq, 2 / np.pi, m.u_a))
    assert len(last) == 200 and N == pytest.approx(90, rel=0.01)
    assert m.S_a == pytest.approx(mu * N, rel=0.01)
    assert m.h_eq == pytest.approx(2 / np.pi, rel=0.02)


@pytest.fixture(scope="module")
def cycled(tiny_filled):
    """A tiny bag (9 x 9 x 5) filled, then cycled at 0.25 and 0.5 mm, 2 cycles each."""
    wd = tiny_filled
    shutil.copy(wd / "fill.data", wd / "fill.keep")
    res = lmprun.run(INPUTS / "in.cyclic", wd, variables=PROTOCOL).check()
    return wd, res


def exact_row_means(ua, NP, NR, nrows):
    """Means of u_a sin(2 pi n / NP) over each row's NR steps (the forces of the amplitude's k-th
    step see u at n = k - 1)."""
    n = np.arange(nrows * NR)
    u = ua * np.sin(2 * np.pi * n / NP)
    return u.reshape(nrows, NR).mean(axis=1)


def test_protocol_on_a_tiny_bag(cycled):
    wd, res = cycled
    d = cyclic.read_csv(wd / "cyclic.csv")
    assert "CYCLED: 2 amplitudes" in res.output
    for k, ua in ((1, 0.25), (2, 0.5)):
        rows = d[d["amp"] == k]
        # 200 rows per cycle, cycles 1 and 2, each row the mean of its NR steps
        assert len(rows) == 400 and list(np.unique(rows["cycle"])) == [1, 2]
        assert (rows["ua_mm"] == ua).all()
        NR = int(rows["steps"][0])
        assert (rows["steps"] == NR).all()
        # the plate follows u(t) exactly (to the CSV's 5 decimals of a mm)
        exact = exact_row_means(ua, 200 * NR, NR, 400)
        print("amplitude %g mm: max |u - exact| %.2e mm, F_v %.2f..%.2f N"
              % (ua, np.abs(rows["u_mm"] - exact).max(), rows["Fv_N"].min(), rows["Fv_N"].max()))
        assert np.abs(rows["u_mm"] - exact).max() < 2e-5
        # F_v held: each cycle's mean within 0.5 % of the target, the rows' means within 1 % rms
        # and 6 % at most (a row of 0.2-0.5 ms can hold a slip collapse of this bag's 153 grains,
        # which the servo recovers within the row; measured up to 5.1 %)
        target = 5500 * 7 * 7 / 79 ** 2
        err = (rows["Fv_N"] - target) / target
        for c in (1, 2):
            assert abs(rows["Fv_N"][rows["cycle"] == c].mean() - target) < 0.005 * target
        assert np.sqrt(np.mean(err ** 2)) < 0.01 and np.abs(err).max() < 0.06
        # a loop that dissipates, and a stiffness that falls with the amplitude
        m = hysteresis.measure(rows["u_mm"][200:], rows["S_N"][200:])
        assert 0.02 < m.h_eq < 2 / np.pi and m.K_eq > 0
    k1 = hysteresis.measure(*[d[d["amp"] == 1][c][200:] for c in ("u_mm", "S_N")]).K_eq
    k2 = hysteresis.measure(*[d[d["amp"] == 2][c][200:] for c in ("u_mm", "S_N")]).K_eq
    assert k2 < k1
    assert (wd / "cyclic.restart.a1").exists() and (wd / "cyclic.restart.a2").exists()
    assert "inertial number at peak" in res.output


def test_analysis_of_the_run(cycled, tmp_path):
    """./tbags plot on the run: figures, tables and a report with the R-O parameters."""
    wd, _ = cycled
    written, text = cyclic.write([cyclic.CyclicRun(wd)], tmp_path)
    names = {p.name for p in written}
    assert {"cyclic-loops.png", "cyclic-curves.png", "cyclic-settlement.png", "cyclic_table.csv",
            "ro_parameters.csv", "report.md"} <= names
    assert "| 0.25 |" in text and "K_0 (N/mm)" in text
    table = np.genfromtxt(tmp_path / "cyclic_table.csv", delimiter=",", names=True, dtype=None,
                          encoding="utf-8")
    assert len(table) == 4


def test_triangle_wave(cycled, tmp_path):
    """-var wave triangle: u(t) is a triangle of the same amplitude (constant speed between tips)."""
    wd, _ = cycled
    shutil.copy(wd / "fill.keep", tmp_path / "fill.data")
    lmprun.run(INPUTS / "in.cyclic", tmp_path, variables=dict(SIZE, amps="0.25", cycles=1, vpeak=0.03,
                                                              wave="triangle")).check()
    d = cyclic.read_csv(tmp_path / "cyclic.csv")
    NR = int(d["steps"][0])
    n = np.arange(200 * NR)
    tri = 0.25 * np.arcsin(np.sin(2 * np.pi * n / (200 * NR))) * 2 / np.pi
    assert np.abs(d["u_mm"] - tri.reshape(200, NR).mean(axis=1)).max() < 2e-5
    # the peak speed is vpeak: period = 4 u_a / vpeak
    assert 200 * NR * 1.5e-6 == pytest.approx(4 * 0.25e-3 / 0.03, rel=0.01)


def test_same_on_one_and_two_ranks(cycled, tmp_path):
    """Compression and one cycle on 1 and 2 ranks give the same CSV, digit for digit (the plate's
    motion is computed from the step number on every rank; forces agree to round-off)."""
    wd, _ = cycled
    csv = {}
    for ranks in (1, 2):
        run_dir = tmp_path / str(ranks)
        run_dir.mkdir()
        shutil.copy(wd / "fill.keep", run_dir / "fill.data")
        lmprun.run(INPUTS / "in.cyclic", run_dir, np_ranks=ranks,
                   variables=dict(SIZE, amps="0.25", cycles=1, vpeak=0.03, rows=20)).check()
        csv[ranks] = (run_dir / "cyclic.csv").read_text()
    assert csv[1] == csv[2] and len(csv[1].splitlines()) == 23


def test_fixed_frequency(cycled, tmp_path):
    """-var freq F: that frequency (rounded to whole steps per row) instead of vpeak's."""
    wd, _ = cycled
    shutil.copy(wd / "fill.keep", tmp_path / "fill.data")
    res = lmprun.run(INPUTS / "in.cyclic", tmp_path, variables=dict(SIZE, amps="0.25", cycles=1, freq=20)).check()
    line = [l for l in res.output.splitlines() if l.startswith("AMPLITUDE 1 of 1")][0]
    print(line)
    f = float(line.split(" f ")[1].split()[0])
    assert f == pytest.approx(20, rel=0.005) and "period 33400 steps" in line


@pytest.mark.parametrize("var,message", [
    ({"amps": "0.5 0.25"}, "amps must be > 0 and increasing"),
    ({"amps": "0 0.5"}, "amps must be > 0 and increasing"),
    ({"amps": "-1"}, "amps must be > 0 and increasing"),
    ({"amps": "0.25 0.25"}, "amps must be > 0 and increasing"),
    ({"amps": "0.5 5.5"}, "the bag is too small for amps"),
    ({"freq": 0}, "freq must be > 0 Hz"),
    ({"freq": -2}, "freq must be > 0 Hz"),
    ({"vpeak": 0}, "vpeak must be > 0"),
    ({"cycles": 0}, "cycles must be a whole number"),
    ({"cycles": 1.5}, "cycles must be a whole number"),
    ({"rows": 10}, "rows (CSV rows per cycle) must be"),
    ({"wave": "square"}, "wave must be sine or triangle"),
    ({"freq": 1e7}, "a CSV row would be shorter than a step"),
    ({"start": 3}, "start 3 is beyond the 2 amplitudes"),
    ({"Fv": -3}, "Fv must be > 0"),
    # a missing checkpoint whose name has a dot: LAMMPS's if cannot compare it with 'none' (it
    # stopped with 'Invalid Boolean syntax' until 2026-12-05)
    ({"restart": "cyclic.restart.a9", "start": 2}, "no restart file cyclic.restart.a9"),
])
def test_bad_variables(tmp_path, var, message):
    res = lmprun.run(INPUTS / "in.cyclic", tmp_path, variables=dict(PROTOCOL, **var))
    print(res.error_line() or res.output[-300:])
    assert res.returncode != 0 and message in res.output


def test_resume_needs_start(cycled, tmp_path):
    wd, _ = cycled
    shutil.copy(wd / "cyclic.restart.a1", tmp_path)
    res = lmprun.run(INPUTS / "in.cyclic", tmp_path, variables=dict(PROTOCOL, restart="cyclic.restart.a1"))
    assert res.returncode != 0 and "a resumed run needs -var start K+1" in res.output


def test_cycles_after_the_shared_compression(cycled, tmp_path):
    """in.cyclic shares the compression as in.shear (between_plates.lmp): a part made at 1.96 kN's
    stress, continued at 5.50 kN's, reaches its own F_v (not the part's) and cycles with it held."""
    import re
    wd, _ = cycled
    shutil.copy(wd / "fill.keep", tmp_path / "fill.data")
    v = dict(SIZE, amps="0.25", cycles=1, vpeak=0.03)
    part = lmprun.run(INPUTS / "in.cyclic", tmp_path, variables=dict(v, Fpaper=1960, compress_to=0.9)).check()
    assert "COMPRESSION PART" in part.output and not (tmp_path / "cyclic.csv").exists()
    res = lmprun.run(INPUTS / "in.cyclic", tmp_path, variables=dict(v, Fpaper=5500, compress_from="compress.restart")).check()
    fv, target = map(float, re.search(r"^COMPRESSED: F_v (\S+) N \(target (\S+)\)", res.output, re.M).groups())
    d = cyclic.read_csv(tmp_path / "cyclic.csv")
    print("COMPRESSED %.2f N (target %.2f); cycled F_v mean %.2f N" % (fv, target, d["Fv_N"][1:].mean()))
    assert target == pytest.approx(5500 * 7 * 7 / 79 ** 2) and abs(fv - target) < 0.005 * target
    assert abs(d["Fv_N"][1:].mean() - target) < 0.01 * target and "CYCLED" in res.output


def test_resume_at_the_next_amplitude(cycled, tmp_path):
    """A run interrupted during amplitude 2 (its checkpoint after amplitude 1, its CSV with 150 of
    amplitude 2's rows written) continues through ./tbags shear --resume's step for a cyclic run
    (stages.stage_run): in.cyclic restarts from cyclic.restart.a1 with amplitude 2 (-var start 2,
    not amplitude 1 again) and the CSV ends with as many rows as the straight run's; the plate
    follows the straight run's u, and S matches it closely (a fresh force evaluation at the
    restart: not bit-identical). A CSV with amplitude 2 appended after the interrupted rows (the
    deck resumed by hand) reads as the launcher's: the reader keeps the later rows."""
    sys.path.insert(0, str(lmprun.ROOT / "launcher"))
    from tbagsrun import stages
    wd, _ = cycled
    straight = cyclic.read_csv(wd / "cyclic.csv")
    lines = (wd / "cyclic.csv").read_text().splitlines()
    first2 = next(k for k, line in enumerate(lines) if line.split(",")[1:2] == ["2"])
    (tmp_path / "cyclic.csv").write_text("\n".join(lines[:first2 + 150]) + "\n")    # cut in amplitude 2
    shutil.copy(wd / "cyclic.restart.a1", tmp_path)
    (tmp_path / "screen.cyclic.txt").write_text("AMPLITUDE 1 DONE\n")
    (tmp_path / ".cyclic.vars").write_text(stages.vars_key(PROTOCOL))
    said = []
    stages.stage_run(tmp_path, "cyclic", 1, PROTOCOL, said.append, resume=True)
    print("\n".join(said))
    assert said[0].endswith("resuming from cyclic.restart.a1") and any("CYCLED" in s for s in said)
    screen = (tmp_path / "screen.cyclic.txt").read_text()
    assert "AMPLITUDE 1 of" not in screen and "AMPLITUDE 2 of 2" in screen
    assert (tmp_path / "screen.cyclic.txt.1").is_file()
    # the launcher keeps the rows up to the checkpoint; the deck alone appends amplitude 2 after
    # whatever the CSV holds: the reader keeps the later of two rows at the same time
    raw = np.genfromtxt(tmp_path / "cyclic.csv", delimiter=",", names=True, comments="#")
    resumed = cyclic.read_csv(tmp_path / "cyclic.csv")
    assert len(raw) == len(resumed) == len(straight)
    new2 = [line for line in (tmp_path / "cyclic.csv").read_text().splitlines() if line.split(",")[1:2] == ["2"]]
    (tmp_path / "appended.csv").write_text("\n".join(lines[:first2 + 150] + new2) + "\n")
    appended = cyclic.read_csv(tmp_path / "appended.csv")
    assert len(appended) == len(straight) and np.array_equal(appended["S_N"], resumed["S_N"])
    assert np.all(np.diff(resumed["time_s"]) > 0)
    assert np.array_equal(resumed["amp"], straight["amp"]) and np.array_equal(resumed["cycle"], straight["cycle"])
    a2, b2 = straight[straight["amp"] == 2], resumed[resumed["amp"] == 2]
    assert np.abs(a2["u_mm"] - b2["u_mm"]).max() < 1e-5
    span = a2["S_N"].max() - a2["S_N"].min()
    print("resumed amplitude 2: max |S - S_straight| %.3f N of a %.1f N span"
          % (np.abs(a2["S_N"] - b2["S_N"]).max(), span))
    assert np.abs(a2["S_N"][:20] - b2["S_N"][:20]).max() < 0.05 * span
