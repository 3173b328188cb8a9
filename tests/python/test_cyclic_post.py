"""tbagspost.cyclic on a made-up cyclic.csv of known Masing loops: rows, cycles, a resumed run's
repeated rows, the table, the R-O fit, the report and the command line."""
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "postprocess"))
from tbagspost import cli, cyclic, hysteresis  # noqa: E402

TRUE = hysteresis.RO(K0=180.0, S_y=250.0, r=2.2)      # N/mm, N
HEADER = ("time_s,amp,cycle,ua_mm,u_mm,w_mm,S_N,Fv_N,broken_bonds,zplate_mm,steps,u_min_mm,"
          "u_max_mm,w_min_mm,w_max_mm,S_min_N,S_max_N,Fv_min_N,Fv_max_N")


def masing_rows(ua, k, cycles=3, n=200, t0=0.0, period=0.1):
    """Rows of `cycles` Masing cycles of TRUE at amplitude ua (mm), starting at u = 0 upwards."""
    S_a = float(TRUE.S(ua)[0])
    rows = []
    for c in range(1, cycles + 1):
        th = 2 * np.pi * (np.arange(n) + 0.5) / n
        u = ua * np.sin(th)
        S = np.where(np.cos(th) < 0, S_a - 2 * TRUE.S((ua - u) / 2), -S_a + 2 * TRUE.S((u + ua) / 2))
        for j in range(n):
            t = t0 + period * (c - 1 + (j + 0.5) / n)
            w = -0.01 * (c + k)
            rows.append("%.7f,%d,%d,%g,%.6f,%.5f,%.5f,318.0,0,30,100,%.6f,%.6f,%.5f,%.5f,%.5f,%.5f,317,319"
                        % (t, k, c, ua, u[j], w, S[j], u[j], u[j], w, w, S[j], S[j]))
    return rows, t0 + period * cycles


def write_run(path, resumed=False, rows_per_cycle=(200, 200, 200), edit=None):
    """A run of three amplitudes; edit(lines) may change the data lines (header and '#' lines
    kept in place) before they are written."""
    path.mkdir(parents=True, exist_ok=True)
    lines, t = [HEADER], 0.0
    for k, (ua, n) in enumerate(zip((0.25, 1.0, 3.0), rows_per_cycle), start=1):
        lines.append("# amplitude %d: u_a %g mm, 3 cycles of %d steps, rows of 100 steps" % (k, ua, 100 * n))
        rows, t_end = masing_rows(ua, k, t0=t, n=n)
        if resumed and k == 2:
            # the run stopped in amplitude 2, resumed from the checkpoint after amplitude 1
            lines += [r.replace(",318.0,", ",999.0,") for r in rows[:150]]
            lines.append("# amplitude %d: u_a %g mm" % (k, ua))
        lines += rows
        t = t_end
    if edit:
        lines = edit(lines)
    (path / "cyclic.csv").write_text("\n".join(lines) + "\n")
    (path / "log.cyclic").write_text(
        "CYCLIC: 3 amplitudes (0.25 1 3 mm), 3 cycles each, sine, from amplitude 1: 100 steps; "
        "bag 21 x 21 x 7, mean stress 35 kPa\nSAND: paper parameters\nTIMESTEP: using 1.5e-6 s\n"
        "AMPLITUDE 1 of 3: u_a 0.25 mm, f 9.55 Hz (period 69800 steps, 200 rows of 349 steps), "
        "peak speed 15 mm/s, inertial number at peak 8.2e-04\n")
    return path


def test_rows_cycles_and_a_resumed_run(tmp_path):
    plain = cyclic.CyclicRun(write_run(tmp_path / "a"))
    resumed = cyclic.CyclicRun(write_run(tmp_path / "b", resumed=True))
    assert len(resumed.csv) == len(plain.csv) == 3 * 3 * 200
    assert not (resumed.csv["Fv_N"] == 999.0).any()       # the superseded rows are gone
    assert plain.rows_per_cycle(1) == 200
    assert [(a, c) for a, c, _ in plain.cycles()] == [(a, c) for a in (1, 2, 3) for c in (1, 2, 3)]
    assert plain.conditions()["amps"][1] == (0.25, 9.55, 15.0, 8.2e-4)


def test_table_and_fit_recover_the_model(tmp_path):
    run = cyclic.CyclicRun(write_run(tmp_path / "a"))
    tab = cyclic.table(run)
    assert len(tab) == 9
    for t in tab:
        S_a = float(TRUE.S(t["ua_nominal_mm"])[0])
        assert t["K_eq_N_per_mm"] == pytest.approx(S_a / t["ua_nominal_mm"], rel=2e-3)
        assert t["h_eq"] == pytest.approx(float(TRUE.damping(S_a)), rel=0.02)
    f = cyclic.fit(run)
    assert f.model.K0 == pytest.approx(TRUE.K0, rel=0.01)
    assert f.model.S_y == pytest.approx(TRUE.S_y, rel=0.01)
    assert f.model.r == pytest.approx(TRUE.r, rel=0.01)


def test_report_and_command_line(tmp_path, capsys):
    a = write_run(tmp_path / "F5500")
    b = write_run(tmp_path / "F1960")
    assert cli.main([str(a), str(b)]) == 0
    out = tmp_path / "figures"
    for name in ("cyclic-loops.png", "cyclic-curves.png", "cyclic-settlement.png", "cyclic_table.csv",
                 "ro_parameters.csv", "report.md"):
        assert (out / name).is_file(), name
    report = (out / "report.md").read_text()
    assert "| 318 | 180 +- " in report and "| 0.25 |" in report and "peak plate speed 15 mm/s" in report
    p = np.genfromtxt(out / "ro_parameters.csv", delimiter=",", names=True, dtype=None, encoding="utf-8")
    assert np.allclose(p["K0_N_per_mm"], TRUE.K0, rtol=0.01) and np.allclose(p["r"], TRUE.r, rtol=0.01)


def test_missing_or_bad_csv(tmp_path):
    with pytest.raises(SystemExit, match="no .*cyclic.csv"):
        cyclic.read_csv(tmp_path / "cyclic.csv")
    (tmp_path / "cyclic.csv").write_text("time_s,u_mm\n1,2\n3,4\n")
    with pytest.raises(SystemExit, match="lacks the columns"):
        cyclic.read_csv(tmp_path / "cyclic.csv")


def test_rate_check(tmp_path, capsys):
    """postprocess/tbagspost/check_cyclic_rate.py: the same loops pass; S 10 % higher fails on K_eq."""
    from tbagspost import check_cyclic_rate as check
    a = write_run(tmp_path / "fast")
    b = write_run(tmp_path / "slow")
    assert check.main([str(a), str(b)]) == 0
    assert "K_eq 0.0 %" in capsys.readouterr().out
    d = np.genfromtxt(b / "cyclic.csv", delimiter=",", names=True, comments="#")
    d["S_N"] *= 1.1
    with open(b / "cyclic.csv", "w") as fh:
        fh.write(HEADER + "\n")
        np.savetxt(fh, d, delimiter=",", fmt="%.7g")
    assert check.main([str(a), str(b)]) == 1
    assert "K_eq 10.0 %" in capsys.readouterr().out


# ---- the analysis fails loudly, never silently (issue 49, section 4) ----------------------------
def data_index(lines, k):
    """The index in lines of data row k (0-based, '#' lines and the header skipped)."""
    return [i for i, line in enumerate(lines) if i and not line.startswith("#")][k]


def set_field(lines, k, column, value):
    i = data_index(lines, k)
    f = lines[i].split(",")
    f[HEADER.split(",").index(column)] = value
    lines[i] = ",".join(f)
    return lines


@pytest.mark.parametrize("column", ["S_N", "u_mm"])
def test_a_non_finite_value_names_its_row(tmp_path, column):
    run = write_run(tmp_path / "a", edit=lambda ls: set_field(ls, 450, column, "nan"))
    with pytest.raises(SystemExit, match=r"data row 451 .*amplitude 1, cycle 3.* no finite %s" % column):
        cyclic.CyclicRun(run)


def test_a_cut_last_row_is_dropped_and_its_cycle_left_out(tmp_path, capsys):
    """An interrupted run: its last row cut short (NaN) and its last cycle incomplete."""
    def cut(lines):
        lines = lines[:-120]                       # the run stopped in amplitude 3, cycle 3
        lines[-1] = lines[-1][:20]                 # while writing a row
        return lines
    run = cyclic.CyclicRun(write_run(tmp_path / "a", edit=cut))
    assert [(a, c) for a, c, _ in run.cycles()] == [(a, c) for a in (1, 2, 3) for c in (1, 2, 3)][:-1]
    assert "amplitude 3, cycle 3 has 79 of its 200 rows" in capsys.readouterr().err


def test_amplitudes_with_other_rows_per_cycle_are_all_kept(tmp_path):
    run = cyclic.CyclicRun(write_run(tmp_path / "a", rows_per_cycle=(200, 100, 400)))
    assert [(a, c) for a, c, _ in run.cycles()] == [(a, c) for a in (1, 2, 3) for c in (1, 2, 3)]
    assert [len(r) for _, _, r in run.cycles()] == [200] * 3 + [100] * 3 + [400] * 3
    assert len(cyclic.table(run)) == 9


def test_rows_missing_in_a_cycle_or_a_whole_cycle_stop_with_its_name(tmp_path):
    drop = lambda a, b: (lambda ls: [x for i, x in enumerate(ls) if not data_index(ls, a) <= i < data_index(ls, b)])  # noqa: E731,E501
    with pytest.raises(SystemExit, match="amplitude 1, cycle 1 has 150 rows, the deck writes 200"):
        cyclic.CyclicRun(write_run(tmp_path / "a", edit=drop(0, 50))).cycles()
    with pytest.raises(SystemExit, match="amplitude 1 has no cycle 1 .*next cycle is 2"):
        cyclic.CyclicRun(write_run(tmp_path / "b", edit=drop(0, 200))).cycles()
    with pytest.raises(SystemExit, match="amplitude 2 has no cycle 2 .*next cycle is 3"):
        cyclic.CyclicRun(write_run(tmp_path / "c", edit=drop(800, 1000))).cycles()


def test_a_window_that_is_not_one_cycle_is_refused():
    th = lambda cycles: np.linspace(0, 2 * np.pi * cycles, int(200 * cycles) + 1)  # noqa: E731
    loop = lambda t: (np.sin(t), 100 * np.sin(t + 0.3))  # noqa: E731
    assert hysteresis.measure(*loop(th(1.0))).h_eq == pytest.approx(np.sin(0.3) / 2, rel=1e-3)
    with pytest.raises(ValueError, match="turns 3 times: more than one cycle"):
        hysteresis.measure(*loop(th(1.5)))
    for part in (0.75, 1.25):
        with pytest.raises(ValueError, match="does not close"):
            hysteresis.measure(*loop(th(part)))
    u, S = loop(th(1.0))
    with pytest.raises(ValueError, match="wrong way round"):
        hysteresis.measure(u[::-1], S[::-1])
    # a period of the drive with drift (a film's creeping slip) is a loop: not refused
    t = th(1.0)
    assert hysteresis.measure(np.sin(t) + 0.2 * t / t[-1], 100 * np.sin(t + 0.3), one_period=True).h_eq > 0
    with pytest.raises(ValueError, match="not finite"):
        hysteresis.measure(np.append(u, np.nan), np.append(S, 1.0))


def test_a_reversed_loop_in_a_run_names_its_cycle(tmp_path):
    flip = lambda ls: [set_field(ls, k, "S_N", "%g" % -float(ls[data_index(ls, k)].split(",")[6]))  # noqa: E731
                       for k in range(200, 400)][-1]
    run = cyclic.CyclicRun(write_run(tmp_path / "a", edit=flip))
    with pytest.raises(SystemExit, match="amplitude 1, cycle 2: the loop runs the wrong way round"):
        cyclic.table(run)
