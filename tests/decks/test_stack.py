"""A stack of two bags with a film sheet between them (inputs/in.cyclic -var bags 2, the films of
inputs/stack.lmp), cycled on a tiny bag (9 x 9 x 5): with a film that grips both bags the stack is
two bags in series (one bag of double height: half the stiffness); with a slippery film the top
bag slides on it at mu (F_v + its weight); 1 and 2 ranks agree; a checkpoint resumes; the split
of the plate's displacement adds up; bad -var values stop with a message."""
import shutil
import sys

import numpy as np
import pytest

import lmprun

sys.path.insert(0, str(lmprun.ROOT / "postprocess"))
from tbagspost import cyclic, stack  # noqa: E402

INPUTS = lmprun.INPUTS
SIZE = lmprun.TINY_BAG
PROTOCOL = dict(SIZE, amps="0.1 0.25", cycles=2, vpeak=0.03)
# the first amplitude alone, for the runs whose checks read amplitude 1 only (the suite's time: the
# 0.25 mm cycles are 70 % of a run's cycling)
FIRST = dict(PROTOCOL, amps="0.1")
G = 9.81


@pytest.fixture(scope="module")
def fill(tiny_filled):
    return tiny_filled / "fill.data"


def cycle(fill, wd, np_ranks=1, protocol=PROTOCOL, **variables):
    wd.mkdir(parents=True, exist_ok=True)
    shutil.copy(fill, wd / "fill.data")
    res = lmprun.run(INPUTS / "in.cyclic", wd, np_ranks=np_ranks,
                     variables=dict(protocol, **variables)).check()
    (wd / "screen.cyclic.txt").write_text(res.output)
    return res


def bag_mass(fill):
    """The mass of one filled bag (kg) from its data file (diameter, density per atom)."""
    lines = fill.read_text().splitlines()
    start = lines.index(next(l for l in lines if l.startswith("Atoms"))) + 2
    m = 0.0
    for line in lines[start:]:
        if not line.strip():
            break
        f = line.split()
        m += np.pi / 6 * float(f[3]) ** 3 * float(f[4])
    return m


@pytest.fixture(scope="module")
def single(fill, tmp_path_factory):
    wd = tmp_path_factory.mktemp("single")
    cycle(fill, wd)
    return cyclic.CyclicRun(wd)


@pytest.fixture(scope="module")
def gripped(fill, tmp_path_factory):
    wd = tmp_path_factory.mktemp("gripped")
    res = cycle(fill, wd, protocol=FIRST, bags=2, film_mu="1e10")
    return stack.StackRun(wd), res


@pytest.fixture(scope="module")
def sliding(fill, tmp_path_factory):
    wd = tmp_path_factory.mktemp("sliding")
    res = cycle(fill, wd, bags=2, film_mu=0.05)
    return stack.StackRun(wd), res


def last_cycle(run, amp):
    return [t for t in stack.split_table(run) if t["amp"] == amp][-1]


def k_eq(run, amp):
    return [t for t in cyclic.table(run) if t["amp"] == amp][-1]["K_eq_N_per_mm"]


def test_gripping_film_makes_two_bags_in_series(single, gripped):
    """Film friction 1e10 on both faces: nothing slides across the film; what moves across it is
    the elastic give of its contacts (8 % of u_a on this tiny bag, a loop without area: h_eq
    under 0.05), and the stack's K_eq at 0.1 mm is half the single bag's within 10 % (two equal
    bags in series, one bag of double height; measured 0.54: the lower bag carries the upper
    one's weight as well, and the film's contacts add compliance)."""
    run, res = gripped
    assert "STACK: 2 bags" in res.output and "FILMS: 1 between 2 bags, friction 1e10 above and 1e10 below" in res.output
    t = last_cycle(run, 1)
    ratio = k_eq(run, 1) / k_eq(single, 1)
    print("gripped: slip fraction %.4f, bag shears %.4f + %.4f mm; K_eq stack %.2f, single %.2f N/mm, "
          "ratio %.3f" % (t["slip_fraction"], t["bag1_mm"], t["bag2_mm"], k_eq(run, 1), k_eq(single, 1), ratio))
    assert t["slip_fraction"] < 0.1 and abs(t["film1_h_eq"]) < 0.05
    assert ratio == pytest.approx(0.5, rel=0.10)
    # both bags take about half of the plate's displacement
    assert t["bag1_mm"] == pytest.approx(t["bag2_mm"], rel=0.25)


def test_slippery_film_slides_at_mu(fill, sliding):
    """Film friction 0.05: the top bag slides on the film. The force through the film is
    mu (F_v + the top bag's weight) within 1 %; the slip takes over 80 % of the plate's
    amplitude at 0.25 mm; the plate's S_a adds the top bag's inertia, m u_a (2 pi f)^2
    = m vpeak^2 / u_a, to mu (F_v + W) (within 5 %)."""
    run, _ = sliding
    m = bag_mass(fill)
    for amp, ua in ((1, 0.1e-3), (2, 0.25e-3)):
        t = last_cycle(run, amp)
        fv = t["Fv_mean_N"]
        friction = 0.05 * (fv + m * G)
        S_a = [c for c in cyclic.table(run) if c["amp"] == amp][-1]["S_a_N"]
        expected = friction + m * 0.03 ** 2 / ua
        print("u_a %g mm: film force %.4f N (mu (F_v + W) %.4f), slip fraction %.3f, S_a %.4f "
              "(friction + inertia %.4f), film h_eq %.3f" % (ua * 1e3, t["film1_force_N"], friction,
                                                             t["slip_fraction"], S_a, expected, t["film1_h_eq"]))
        assert t["film1_force_N"] == pytest.approx(friction, rel=0.01)
        assert S_a == pytest.approx(expected, rel=0.05)
    t = last_cycle(run, 2)
    assert t["slip_fraction"] > 0.8
    assert t["film1_h_eq"] > 0.5    # a nearly rigid-plastic loop (2/pi for a perfect one)


def test_split_adds_up(sliding):
    """Plate displacement = bottom plate slip + bag shears + film slips + top plate slip, row by
    row (the parts are differences of the same face displacements: to round-off)."""
    run, _ = sliding
    p = run.parts(run.csv)
    total = p["plate_bottom"] + p["bag1"] + p["film1"] + p["bag2"] + p["plate_top"]
    assert np.abs(total - p["u"]).max() < 1e-6
    assert np.allclose(p["film1"], p["film1_below"] + p["film1_above"], atol=1e-9)


def test_one_and_two_ranks_agree(fill, sliding, tmp_path):
    """The stack on 2 ranks against the 1-rank run: the same measured results (film force within
    0.5 %, slip fraction within 0.01, S_a within 2 %, F_v within 0.1 %). Not digit for digit: while
    the bags settle under gravity the film rattles in its 0.2 mm clearance, and a round-off
    difference of the rank sums (1e-11 m of the film's height after 6,000 steps) grows to 1e-7 m
    by 16,000 steps (measured with full-precision output); tests/decks/test_film.py compares a
    film's run on 1 and 2 ranks to round-off. The 2-rank run has the first amplitude only (the
    same protocol up to its end)."""
    one, _ = sliding
    wd = tmp_path / "np2"
    cycle(fill, wd, np_ranks=2, protocol=FIRST, bags=2, film_mu=0.05)
    two = stack.StackRun(wd)
    assert len(two.csv) == np.count_nonzero(one.csv["amp"] == 1)
    for amp in (1,):
        a, b = last_cycle(one, amp), last_cycle(two, amp)
        ca = [c for c in cyclic.table(one) if c["amp"] == amp][-1]
        cb = [c for c in cyclic.table(two) if c["amp"] == amp][-1]
        print("amp %d: film force %.4f / %.4f N, slip fraction %.4f / %.4f, S_a %.4f / %.4f N"
              % (amp, a["film1_force_N"], b["film1_force_N"], a["slip_fraction"], b["slip_fraction"],
                 ca["S_a_N"], cb["S_a_N"]))
        assert b["film1_force_N"] == pytest.approx(a["film1_force_N"], rel=0.005)
        assert b["slip_fraction"] == pytest.approx(a["slip_fraction"], abs=0.01)
        assert cb["S_a_N"] == pytest.approx(ca["S_a_N"], rel=0.02)
        assert cb["Fv_mean_N"] == pytest.approx(ca["Fv_mean_N"], rel=0.001)


def test_resume_a_stack(sliding, tmp_path):
    """The checkpoint after amplitude 1 resumes amplitude 2: the films come back where they were
    (position, displacement, velocity), the stack rows of amplitude 2 are written again and the
    reader keeps the later ones; they match the straight run's closely."""
    run, _ = sliding
    for f in ("cyclic.csv", "stack.txt", "cyclic.restart.a1"):
        shutil.copy(run.path / f, tmp_path)
    res = lmprun.run(INPUTS / "in.cyclic", tmp_path, variables=dict(
        PROTOCOL, bags=2, film_mu=0.05, restart="cyclic.restart.a1", start=2)).check()
    (tmp_path / "screen.cyclic.txt").write_text(res.output)
    assert "AMPLITUDE 2 of 2" in res.output and "AMPLITUDE 1 of" not in res.output
    resumed = stack.StackRun(tmp_path)
    assert len(resumed.csv) == len(run.csv)
    a, b = last_cycle(run, 2), last_cycle(resumed, 2)
    print("straight: slip fraction %.4f, film force %.4f N; resumed %.4f, %.4f N"
          % (a["slip_fraction"], a["film1_force_N"], b["slip_fraction"], b["film1_force_N"]))
    assert b["slip_fraction"] == pytest.approx(a["slip_fraction"], abs=0.01)
    assert b["film1_force_N"] == pytest.approx(a["film1_force_N"], rel=0.005)
    s_a, s_b = run.stack, resumed.stack
    assert np.abs(s_a["film1_x"][-1] - s_b["film1_x"][-1]) < 0.02 * 0.25e-3


def test_analysis_of_stack_and_single(single, sliding, tmp_path, capsys):
    """./tbags plot on the stack and the single bag: the cyclic figures and tables with both runs,
    the stack's split figure and table, and the stack section of the report."""
    from tbagspost import cli
    run, _ = sliding
    assert cli.main([str(single.path), str(run.path), "-o", str(tmp_path)]) == 0
    report = (tmp_path / "report.md").read_text()
    assert "## Stack: 2 bags, film friction 0.05 above, 0.05 below" in report
    assert "2 bags |" in report    # the stack's rows in the cyclic tables
    for name in ("cyclic-loops.png", "cyclic-curves.png", "stack-split-%s.png" % run.name,
                 "stack_split-%s.csv" % run.name):
        assert (tmp_path / name).stat().st_size > 0, name


@pytest.mark.parametrize("var,message", [
    ({"bags": 2}, "a stack needs the film's friction against the bags, -var film_mu MU"),
    ({"bags": 2, "film_mu": -0.1}, "a stack needs the film's friction"),
    ({"bags": 2, "film_mu": 0.1, "film_mu_below": -2}, "film_mu_below must be >= 0"),
    ({"bags": 2, "film_mu": 0.1, "film_gap": -0.001}, "the bags would overlap the film"),
    ({"bags": 2, "film_mu": 0.1, "film_t": 0}, "film_t and film_rho must be > 0"),
    ({"bags": 1.5}, "bags must be a whole number >= 1"),
    ({"bags": 0}, "bags must be a whole number >= 1"),
])
def test_bad_variables(fill, tmp_path, var, message):
    shutil.copy(fill, tmp_path / "fill.data")
    res = lmprun.run(INPUTS / "in.cyclic", tmp_path, variables=dict(PROTOCOL, **var))
    print(res.error_line() or res.output[-300:])
    assert res.returncode != 0 and message in res.output
