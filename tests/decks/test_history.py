"""fix table/time (a value tabulated against time) and in.cyclic's displacement history
(-var history FILE): the fix's value at every step against the interpolation done here, kept
across a restart; bad tables refused naming the line; on a tiny bag a sine history gives the
plate motion and the forces of in.cyclic's own sine, and a history resumes from a chunk's
checkpoint."""
import shutil

import numpy as np
import pytest

import lmprun

INPUTS = lmprun.INPUTS
SIZE = lmprun.TINY_BAG

BOX = """
units           si
atom_style      sphere
region          b block 0 1 0 1 0 1
create_box      1 b
create_atoms    1 single 0.5 0.5 0.5        # (write_restart of an empty box trips UBSan in LAMMPS)
timestep        0.1
{fix}
thermo_style    custom step f_h f_h[1] f_h[2] f_h[3] f_h[4] f_h[5]
thermo_modify   format float %.17g
thermo          1
{rest}
"""


def thermo_rows(output, ncols=7):
    rows = []
    for line in output.splitlines():
        w = line.split()
        if len(w) == ncols and w[0].isdigit():
            rows.append([float(x) for x in w])
    return np.array(rows)


def test_value_at_every_step_and_after_a_restart(tmp_path):
    """Rows (0, 0), (0.35, 2), (1.0, -1.2) in s, scale 0.5, time 0 at step 3 (dt 0.1 s): at step n
    the value is 0.5 y((n - 3) 0.1) (held before and after), [2] the next step's."""
    (tmp_path / "h.txt").write_text("# t y\n0 0\n0.35 2   # a comment\n\n1.0 -1.2\n")
    fix = "fix h all table/time h.txt scale 0.5 start 3"
    res = lmprun.run(BOX.format(fix=fix, rest="run 16\nwrite_restart r.bin"), tmp_path).check()
    d = thermo_rows(res.output)
    t = (d[:, 0] - 3) * 0.1
    want = 0.5 * np.interp(t, [0, 0.35, 1.0], [0, 2, -1.2])
    print(np.c_[d[:, 0], d[:, 1], want])
    assert len(d) == 17
    assert np.abs(d[:, 1] - want).max() < 1e-14 and np.abs(d[:, 2] - want).max() < 1e-14
    assert np.abs(d[:-1, 3] - want[1:]).max() < 1e-14
    assert (d[:, 4] == 1.0).all() and (d[:, 5] == 1.0).all() and (d[:, 6] == 3).all()
    assert "Fix table/time h: 3 rows from h.txt" in res.output
    # restarted: the redefined fix keeps the start of the run that wrote the restart (3, not 17)
    deck = "read_restart r.bin\nfix h all table/time h.txt scale 0.5\n" + \
        "thermo_style custom step f_h f_h[1] f_h[2] f_h[3] f_h[4] f_h[5]\nthermo 1\nrun 3"
    res = lmprun.run(deck, tmp_path).check()
    d = thermo_rows(res.output)
    assert (d[:, 6] == 3).all() and d[0, 0] == 16


@pytest.mark.parametrize("text,keywords,message", [
    (None, "", "h.txt: the file is missing or unreadable"),
    ("0 0\n1 1 1\n", "", "h.txt line 2: needs two columns, time and value (found 3)"),
    ("0 0\n1 x\n", "", "h.txt line 2: value 'x' is not a finite number"),
    ("0 0\n1 inf\n", "", "not a finite number"),
    ("0.5 0\n1 1\n", "", "h.txt line 1: the first time must be 0"),
    ("0 0\n1 1\n# c\n1 2\n", "", "h.txt line 4: time 1 does not increase"),
    ("0 0\n", "", "h.txt: needs at least two rows"),
    ("0 0\n1 -6\n", "scale 0.001 limit 0.005", "beyond the limit"),
    ("0 0\n1 1\n", "scale 0", "scale must be a finite non-zero number"),
    ("0 0\n1 1\n", "limit -1", "limit must be > 0"),
    ("0 0\n1 1\n", "start -4", "start must be a step >= 0 or next"),
    ("0 0\n1 1\n", "speed 3", "unknown keyword speed (scale, limit, start)"),
    ("0 0\n1 1\n", "scale", "keyword scale needs a value"),
])
def test_bad_tables_and_keywords(tmp_path, text, keywords, message):
    if text is not None:
        (tmp_path / "h.txt").write_text(text)
    res = lmprun.run(BOX.format(fix="fix h all table/time h.txt " + keywords, rest="run 1"), tmp_path)
    print(res.error_line())
    assert res.returncode != 0 and message in res.output and "fix table/time" in res.error_line()


# ---- in.cyclic -var history on the tiny bag -----------------------------------------------------
FREQ, ROWS = 200, 20          # in.cyclic's sine: 3340 steps per cycle at dt 1.5e-6 s (rows of 167)


def sine_history(path, NP, ua=0.25, dt=1.5e-6):
    """One cycle of in.cyclic's sine, a row at every step's time (the plate then moves as in.cyclic
    moves it: linear between rows that are the steps)."""
    k = np.arange(NP + 1)
    with open(path, "w") as fh:
        fh.write("# one cycle of u_a %g mm, %d steps\n" % (ua, NP))
        for a, b in zip(k * dt, ua * np.sin(2 * np.pi * k / NP)):
            fh.write("%.17g %.17g\n" % (a, b))


@pytest.fixture(scope="module")
def both(tiny_filled, tmp_path_factory):
    """The tiny bag cycled once at 0.25 mm by in.cyclic's sine, and by the same sine as a history."""
    base = tmp_path_factory.mktemp("history")
    runs = {}
    for name in ("cyclic", "history"):
        wd = base / name
        wd.mkdir()
        shutil.copy(tiny_filled / "fill.data", wd / "fill.data")
        v = dict(SIZE, amps="0.25", cycles=1, freq=FREQ, rows=ROWS)
        if name == "history":
            sine_history(wd / "sine.txt", 3340)
            v = dict(SIZE, history="sine.txt", hrow=167 * 1.5e-6, hchunks=2)
        runs[name] = (wd, lmprun.run(INPUTS / "in.cyclic", wd, variables=v).check())
    return runs


def test_a_sine_history_is_in_cyclics_own_sine(both):
    wd, res = both["cyclic"]
    hd, hres = both["history"]
    assert "period 3340 steps, 20 rows of 167 steps" in res.output
    assert "HISTORY: sine.txt" in hres.output and "20 rows of 167 steps, 2 chunks" in hres.output
    assert "HISTORY CHUNK 2 of 2 DONE" in hres.output and (hd / "cyclic.restart.h1").is_file()
    c = np.genfromtxt(wd / "cyclic.csv", delimiter=",", names=True, comments="#")
    h = np.genfromtxt(hd / "history.csv", delimiter=",", names=True, comments="#")
    assert len(c) == len(h) == 20
    du, dS = np.abs(c["u_mm"] - h["u_mm"]).max(), np.abs(c["S_N"] - h["S_N"]).max()
    span = c["S_N"].max() - c["S_N"].min()
    print("sine history against in.cyclic's sine: max |du| %.2g mm, max |dS| %.2g N of a %.1f N span"
          % (du, dS, span))
    assert du <= 1e-5 and dS <= 1e-3 * span
    assert np.allclose(h["th_s"], (np.arange(20) * 167 + 83) * 1.5e-6, rtol=0, atol=1e-12)


def test_a_history_resumes_from_a_chunk(both, tmp_path):
    hd, _ = both["history"]
    for f in ("history.csv", "cyclic.restart.h1", "sine.txt"):
        shutil.copy(hd / f, tmp_path)
    res = lmprun.run(INPUTS / "in.cyclic", tmp_path, variables=dict(
        SIZE, history="sine.txt", hrow=167 * 1.5e-6, hchunks=2, restart="cyclic.restart.h1",
        start=2)).check()
    assert "HISTORY CHUNK 1 of" not in res.output and "HISTORY CHUNK 2 of 2 DONE" in res.output
    straight = np.genfromtxt(hd / "history.csv", delimiter=",", names=True, comments="#")
    again = np.genfromtxt(tmp_path / "history.csv", delimiter=",", names=True, comments="#")
    assert len(again) == 30 and (again["chunk"][20:] == 2).all()
    assert np.abs(again["u_mm"][20:] - straight["u_mm"][10:]).max() < 1e-5
    span = straight["S_N"].max() - straight["S_N"].min()
    assert np.abs(again["S_N"][20:] - straight["S_N"][10:]).max() < 0.05 * span


@pytest.mark.parametrize("text,message", [
    (None, "no history file sine.txt"),
    ("0 0.1\n0.01 0.2\n", "must start at u = 0 mm"),
    ("0 0\n0.01 6\n", "beyond the limit"),
])
def test_bad_histories(tiny_filled, tmp_path, text, message):
    shutil.copy(tiny_filled / "fill.data", tmp_path / "fill.data")
    if text is not None:
        (tmp_path / "sine.txt").write_text(text)
    res = lmprun.run(INPUTS / "in.cyclic", tmp_path, variables=dict(SIZE, history="sine.txt"))
    print(res.error_line())
    assert res.returncode != 0 and message in res.output


def test_a_bad_table_stops_every_rank_with_the_reason(tmp_path):
    """On 2 ranks: rank 0 reads the file; every rank stops with its reason (error->all)."""
    (tmp_path / "h.txt").write_text("0 0\n1 1\n0.5 2\n")
    res = lmprun.run(BOX.format(fix="fix h all table/time h.txt", rest="run 1"), tmp_path, np_ranks=2)
    assert res.returncode != 0 and "h.txt line 3: time 0.5 does not increase" in res.output


def test_the_value_on_two_ranks_is_rank_zeros(tmp_path):
    fix = "fix h all table/time h.txt scale 0.5 start 3"
    rows = []
    for ranks in (1, 2):
        wd = tmp_path / str(ranks)
        wd.mkdir()
        (wd / "h.txt").write_text("0 0\n0.35 2\n1.0 -1.2\n")
        rows.append(thermo_rows(lmprun.run(BOX.format(fix=fix, rest="run 16"), wd, np_ranks=ranks).check().output))
    assert len(rows[0]) == 17 and (rows[0] == rows[1]).all()
