"""postprocess/tbagspost/project_time.py: the projection of the paper-size run from measured loop times, checked
against a hand computation on synthetic logs; missing or truncated logs give a clear message."""
import os
import re
import sys
from pathlib import Path

import pytest

ROOT = Path(os.environ.get("TBAGS_ROOT", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(ROOT / "postprocess"))
from tbagspost import project_time as pt  # noqa: E402
sys.path.insert(0, str(ROOT / "launcher"))
from tbagsrun.presets import COMPRESS_SHARED  # noqa: E402  (what the launcher passes as --shared)

LOOP = "Loop time of %g on %d procs for %d steps with %d atoms\n"
TIMESTEP = "TIMESTEP: Rayleigh 1.1e-05 s, bond 7.8e-06 s; using %g s\n"


def make(tmp_path, costs={1: 1e-6, 2: 0.6e-6}, dt=2e-6):
    """The estimate's layout on a demo-size bag: the run's bag and fill logs, the checkpoint's
    compression (39,000 steps) and short shear, stretches at P ranks (a run 0, then the timed run)."""
    (tmp_path / "log.bag").write_text("BAG 21 x 21 x 7: 1282 particles, 2560 bonds (formula: 1282, 2560)\n")
    (tmp_path / "log.fill").write_text(LOOP % (1, 2, 2000, 3156) * 10 + LOOP % (10, 2, 40000, 3156))
    est = tmp_path / "estimate"
    (est / "state").mkdir(parents=True)
    (est / "state" / "log.shear").write_text(TIMESTEP % dt + LOOP % (50, 2, 39000, 3156) + LOOP % (0, 2, 0, 3156)
                                             + LOOP % (5, 2, 3333, 3156))
    for p, c in costs.items():
        d = est / ("np%d" % p)
        d.mkdir()
        (d / "log.shear").write_text(TIMESTEP % dt + LOOP % (0.0, p, 0, 3156) + LOOP % (c * 25000 * 3156, p, 25000, 3156))
    return est


def test_counts_match_the_decks():
    assert pt.bag_particles(81, 81, 17) == 17922 and pt.sand_grains(81, 81, 17) == 97130
    assert pt.bag_particles(21, 21, 7) == 1282 and pt.sand_grains(21, 21, 7) == 1874


def test_timestep_from_the_run(tmp_path):
    est = make(tmp_path, dt=1e-6)
    r = pt.project(est, ranks=1, fraction=COMPRESS_SHARED)
    assert r["dt"] == 1e-6 and r["shear_steps"] == pytest.approx(0.015 / (0.004 * 1e-6))
    log = est / "state" / "log.shear"
    log.write_text(log.read_text().replace("TIMESTEP", "TIME"))
    with pytest.raises(SystemExit, match="no TIMESTEP line"):
        pt.project(est, ranks=1, fraction=COMPRESS_SHARED)


def test_projection_by_hand(tmp_path):
    r = pt.project(make(tmp_path), ranks=4, fraction=COMPRESS_SHARED)
    atoms = 17922 + 97130
    assert r["atoms"] == atoms and r["fill_steps"] == 60000 and r["comp_steps"] == 39000
    steps_load = 39000 * 15 / 5 + 0.015 / (0.004 * 2e-6)
    rows = {p: row for p, *row in r["rows"]}
    assert rows[1][0] == pytest.approx(1e-6) and rows[2][0] == pytest.approx(0.6e-6)
    assert rows[2][2] == pytest.approx(60000 * atoms * 0.6e-6 / 3600)
    assert rows[2][3] == pytest.approx(steps_load * atoms * 0.6e-6 / 3600)
    assert rows[4][1] and rows[4][0] == pytest.approx(0.3e-6)     # extrapolated, ideal from 2
    assert not rows[2][1]
    text = pt.report(r)
    assert "* extrapolated" in text and "97130" not in text and "115052 particles" in text


def test_shared_compression_counted_once(tmp_path):
    """The compression's thermo rows give the steps before the force reaches the shared fraction
    of the smallest load (on the demo bag's plan): run once, not per load."""
    est = make(tmp_path)
    log = est / "state" / "log.shear"
    lightest = 1960 * 19 * 19 / 79 ** 2
    rows = "".join("%8d %g %.6f -0.001 0 0 100\n" % (k * 2000, k * 0.003, f * lightest)
                   for k, f in enumerate([0, 0, 0.2, 0.5, 0.85, 0.89, 0.91, 1.2, 3.0]))
    head = "   Step Time v_Fmeas v_w f_top[9] v_conv CPULeft\n"
    log.write_text(log.read_text().replace("Loop time of 50", head + rows + "Loop time of 50", 1))
    assert pt.shared_steps(log, 0.9 * lightest) == 10000
    r = pt.project(est, ranks=2, fraction=COMPRESS_SHARED)
    assert r["shared"] == 10000 and r["shared_paper"] == 30000
    steps_load = (39000 - 10000) * 15 / 5 + 0.015 / (0.004 * 2e-6)
    row = {p: row for p, *row in r["rows"]}[2]
    assert row[2] == pytest.approx((60000 + 30000) * (17922 + 97130) * 0.6e-6 / 3600)
    assert row[3] == pytest.approx(steps_load * (17922 + 97130) * 0.6e-6 / 3600)
    assert pt.total_steps(r) == 60000 + 30000 + 3 * steps_load
    assert "30000 shared by the loads" in pt.report(r)


def test_shared_part_counted_from_its_own_log(tmp_path):
    """A checkpoint whose compression continued from the loads' shared part (./tbags shear paper):
    the part's own steps (compress/log.shear beside the estimate) are the shared ones, and the
    compression is the part plus the checkpoint's first run; without the part's log, a clear stop."""
    est = make(tmp_path)
    log = est / "state" / "log.shear"
    log.write_text("read_restart    ../../compress/compress.restart\n" + log.read_text())
    with pytest.raises(SystemExit, match="continued from a shared part, but there is no"):
        pt.project(est, ranks=2, fraction=COMPRESS_SHARED)
    (tmp_path / "compress").mkdir()
    (tmp_path / "compress" / "log.shear").write_text(LOOP % (40, 2, 30000, 3156))
    r = pt.project(est, ranks=2, fraction=COMPRESS_SHARED)
    assert r["comp_steps"] == 69000 and r["shared"] == 30000 and r["shared_paper"] == 90000
    assert pt.total_steps(r) == 60000 + 90000 + 3 * (39000 * 3 + 0.015 / (0.004 * 2e-6))


def test_missing_and_truncated(tmp_path):
    with pytest.raises(SystemExit, match="no bag.json and no BAG line"):
        pt.project(tmp_path / "estimate", 1, COMPRESS_SHARED)
    est = make(tmp_path)
    (est / "state" / "log.shear").write_text(TIMESTEP % 2e-6 + "LAMMPS (4 Feb 2025)\n")
    with pytest.raises(SystemExit, match="no completed run"):
        pt.project(est, 1, COMPRESS_SHARED)


SECTIONS = """
Section |  min time  |  avg time  |  max time  |%varavg| %total
---------------------------------------------------------------
Pair    | {pair:<10} | {pair:<10} | {pair:<10} |   0.0 | 40.00
Bond    | {bond:<10} | {bond:<10} | {bond:<10} |   0.0 | 20.00
Neigh   | 0.1        | 0.1        | 0.1        |   0.0 |  1.00
Comm    | {comm:<10} | {comm_avg:<10} | {comm_avg:<10} |   0.0 |  5.00
Output  | 0          | 0          | 0          |   0.0 |  0.00
Modify  | 3          | 3          | 3          |   0.0 | 30.00
Other   |            | 0.4        |            |       |  4.00

Nlocal:         {nloc} ave  {nloc} max  {nloc} min
Nghost:         {ngh} ave  {ngh} max  {ngh} min
Neighs:         {nei} ave  {neimax} max  {nei} min
"""


def test_scaling_model_on_a_checkpoint(tmp_path):
    """The model's costs come from the 1- and 2-rank stretches' sections and counts; the
    decomposition runs' statistics are checked against the counts (a lattice of touching spheres
    as the checkpoint: postprocess/tbagspost/scaling.py's test has its hand counts)."""
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from test_scaling import lattice
    est = make(tmp_path, costs={1: 1e-6, 2: 0.6e-6})
    state = est / "state"
    lattice(state).path.rename(state / "state.data")
    (state / "shear.csv").write_text("time_s,u_mm,w_mm,S_N,Fv_N,broken_bonds,zplate_mm\n0,0,0,0,0,0,12\n1,0.02,0,1,1,0,12\n")
    steps = 100
    (est / "np1" / "log.shear").write_text(TIMESTEP % 2e-6 + LOOP % (10.0, 1, steps, 128) + SECTIONS.format(
        pair=2.88, bond=0.64, comm=0.0, comm_avg=0.0, nloc=128, ngh=0, nei=288, neimax=288))
    (est / "np2" / "log.shear").write_text(TIMESTEP % 2e-6 + LOOP % (6.0, 2, steps, 128) + SECTIONS.format(
        pair=1.44, bond=0.32, comm=0.48, comm_avg=0.9, nloc=64, ngh=32, nei=144, neimax=152))
    d = est / "decomp" / "np4"
    d.mkdir(parents=True)
    (d / "log.shear").write_text("  2 by 2 by 1 MPI processor grid\n" + LOOP % (1.0, 4, 5, 128) + SECTIONS.format(
        pair=1, bond=1, comm=1, comm_avg=1, nloc=32, ngh=40, nei=72, neimax=80))
    r = pt.project(est, ranks=2, fraction=COMPRESS_SHARED)
    m = pt.model(est, r)
    c = m["costs"]
    assert c["c_pair"] == pytest.approx(2.88 / steps / 288) and c["c_bond"] == pytest.approx(0.64 / steps / 64)
    assert c["c_atom"] == pytest.approx((10.0 - 2.88 - 0.64) / steps / 128)
    # 2 ranks split the 8 x 8 x 2 lattice 1 x 2 x 1: 64 owned, 32 ghosts each (the brick grown by
    # 10 mm reaches two rows of 8 x 2 of the other)
    assert c["c_ghost"] == pytest.approx(0.48 / steps / 32)
    assert m["checks"] == {4: []}
    rows = {row["ranks"]: row for row in m["rows"]}
    assert rows[1]["efficiency"] == pytest.approx(1.0) and rows[4]["grid"] == (2, 2, 1)
    assert rows[1]["step"] == pytest.approx(10.0 / steps)
    text = pt.report(r, m)
    assert "agree (means within 2 %" in text and "efficiency" in text
    (d / "log.shear").write_text((d / "log.shear").read_text().replace("40 ave  40 max", "40 ave  50 max"))
    assert "DIFFER: ghosts max 40, LAMMPS Nghost 50" in pt.report(r, pt.model(est, r))


def test_stages_restored_from_committed_states(tmp_path):
    """The fill and the shared part restored from committed states (no log.fill, no
    compress/log.shear, as on a new machine): nothing to run for them; the shared part's steps are
    the step its restart was written at (the checkpoint's first thermo row)."""
    est = make(tmp_path)
    (tmp_path / "log.fill").unlink()
    (tmp_path / "fill.data").write_text("LAMMPS data file\n")
    (tmp_path / "compress").mkdir()
    (tmp_path / "compress" / "compress.restart").write_bytes(b"restart")
    log = est / "state" / "log.shear"
    log.write_text("read_restart    ../../compress/compress.restart\n"
                   "Step v_Fmeas\n 30000 0.5\n 31000 0.9\n" + log.read_text())
    r = pt.project(est, ranks=2, fraction=COMPRESS_SHARED)
    assert r["fill_steps"] == 0 and r["shared"] == 30000 and r["comp_steps"] == 69000
    assert r["restored"] == ["the fill", "the shared part of the compression"]
    assert all(row[3] == 0 for row in r["rows"])            # fill + shared part: 0 h here
    assert pt.total_steps(r) == 3 * (39000 * 3 + 0.015 / (0.004 * 2e-6))
    assert "not run here: the fill and the shared part" in pt.report(r)
    (tmp_path / "fill.data").unlink()
    with pytest.raises(SystemExit, match="no .*log.fill"):
        pt.project(est, ranks=2, fraction=COMPRESS_SHARED)
