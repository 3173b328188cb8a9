"""inputs/in.fill on a small bag: the exact count at void ratio 0.68 +/- 0.01, equal number
fractions of the ten sizes, settled with small overlaps and every bag bond intact."""
import re
import shutil
from pathlib import Path

import numpy as np
import pytest

import lmprun

SIZES = 0.00360465 + 0.000310078 * np.arange(10)


def test_fill_small_bag(tmp_path):
    lmprun.run(lmprun.ROOT / "inputs" / "in.bag", tmp_path, variables={"nx": 11, "ny": 11, "nz": 5}).check()
    res = lmprun.run(lmprun.ROOT / "inputs" / "in.fill", tmp_path, variables={
        "nx": 11, "ny": 11, "nz": 5, "tbags": lmprun.ROOT}).check()
    line = [l for l in res.output.splitlines() if l.startswith("FILL ") and "PLAN" not in l][0]
    print(line)
    w = line.replace(",", "").split()
    grains, e = int(w[6]), float(w[10])
    assert float(w[15]) < 0.01 * SIZES[0] * 1000    # sand-sand overlap, mm
    inner = 9 * 9 * 3 * 0.005 ** 3
    assert grains == round(inner / (1.68 * np.mean(np.pi / 6 * SIZES ** 3)))
    assert abs(e - 0.68) < 0.01 and "ERROR" not in res.output and "not settled" not in res.output
    assert "SETTLED: after" in res.output
    # sizes in the data file: equal number fractions (within one grain)
    data = (tmp_path / "fill.data").read_text()
    atoms = data[data.index("Atoms"):data.index("Velocities")].splitlines()[2:]
    rows = np.array([[float(x) for x in l.split()[:7]] for l in atoms if l.strip()])
    sand = rows[rows[:, 2] == 2]    # bpm/sphere: id molecule type diameter density x y z
    counts = [np.sum(np.isclose(sand[:, 3], d, rtol=1e-6)) for d in SIZES]
    assert len(sand) == grains and max(counts) - min(counts) <= 1, counts
    e_exact = inner / np.sum(np.pi / 6 * sand[:, 3] ** 3) - 1
    assert abs(e - e_exact) < 1e-4, (e, e_exact)
    # the void ratio measured in the settled bag (not the count's formula): the deck's inner box
    # between the mean planes of the six faces, recomputed here from the data file, and a second
    # measure, the convex hull of the bag particles shrunk by their radius (Steiner's formula for
    # a box-like body: it counts the sides' bulge); both within 0.03 of the nominal value
    from scipy.spatial import ConvexHull
    measured = float(line.split("void ratio measured ")[1].split()[0])
    bag = np.array([[float(x) for x in l.split()[5:8]] for l in atoms if l.strip() and l.split()[2] == "1"])
    s, r = 0.005, 0.0025
    dims = []
    for k in range(3):
        lo = bag[bag[:, k] < bag[:, k].min() + 0.25 * s, k].mean()
        hi = bag[bag[:, k] > bag[:, k].max() - 0.25 * s, k].mean()
        dims.append(hi - lo - s)
    vs = np.sum(np.pi / 6 * sand[:, 3] ** 3)
    e_faces = np.prod(dims) / vs - 1
    hull = ConvexHull(bag)
    outer = [d + 2 * r for d in dims]
    e_hull = (hull.volume - hull.area * r + 4 * r * r * sum(outer) - 8 * r ** 3) / vs - 1
    print("void ratio: nominal %.4f, measured (faces) %.4f, here %.4f, hull %.4f; inner box %s mm"
          % (e, measured, e_faces, e_hull, ["%.2f" % (d * 1000) for d in dims]))
    assert abs(measured - e_faces) < 1e-3
    assert abs(e_faces - e) < 0.03 and abs(e_hull - e) < 0.03


def test_paper_bag_holds_the_papers_count(tmp_path):
    """81 x 81 x 17: 97,130 grains, 9,713 of each size (doc/tbags_model.rst section 2), e = 0.68 +/- 0.01."""
    lmprun.run(lmprun.ROOT / "inputs" / "in.bag", tmp_path).check()
    res = lmprun.run(lmprun.ROOT / "inputs" / "in.fill", tmp_path, variables={
        "tbags": lmprun.ROOT, "plan_only": 1}).check()
    line = [l for l in res.output.splitlines() if l.startswith("FILL PLAN")][0]
    print(line)
    w = line.replace(",", "").split()
    assert int(w[2]) == 97130 and "(9713 to 9713 of each size)" in line and abs(float(w[-1]) - 0.68) < 0.01


def test_bad_count(tmp_path):
    lmprun.run(lmprun.ROOT / "inputs" / "in.bag", tmp_path, variables={"nx": 5, "ny": 5, "nz": 5}).check()
    res = lmprun.run(lmprun.ROOT / "inputs" / "in.fill", tmp_path, variables={
        "nx": 5, "ny": 5, "nz": 5, "tbags": lmprun.ROOT, "per_size": 0})
    assert res.returncode != 0 and "per_size must be >= 1" in res.output


def sand_rows(path):
    """Sand grains of a fill.data, sorted by id: id, diameter, x, y, z."""
    data = Path(path).read_text()
    atoms = data[data.index("Atoms"):data.index("Velocities")].splitlines()[2:]
    rows = np.array([[float(x) for x in l.split()[:8]] for l in atoms if l.strip()])
    sand = rows[rows[:, 2] == 2]
    sand = sand[np.argsort(sand[:, 0])]
    return sand[:, [0, 3, 5, 6, 7]]


SMALL = {"nx": 7, "ny": 7, "nz": 5, "nsettle": 2000, "ke_tol": 1.0, "vtol": 1.0}


def test_settles_until_the_top_face_rests(tmp_path):
    """The settling runs nsettle steps, then chunks until the kinetic energy and the top face's
    mean sinking speed (over the last chunk) are below their limits, up to settle_max; a limit
    the bag cannot meet runs to settle_max with progress lines and a warning, a loose one stops
    at nsettle."""
    lmprun.run(lmprun.ROOT / "inputs" / "in.bag", tmp_path, variables=SMALL).check()
    tight = dict(SMALL, tbags=lmprun.ROOT, settle_chunk=1000, settle_max=5000, vtol=1e-12)
    out = lmprun.run(lmprun.ROOT / "inputs" / "in.fill", tmp_path, variables=tight).check().output
    progress = [l for l in out.splitlines() if l.startswith("SETTLING:")]
    print("\n".join(progress))
    assert [int(l.split()[1]) for l in progress] == [2000, 3000, 4000, 5000]
    assert "100 %" in progress[-1] and "WARNING: in.fill: not settled after 5000 steps" in out
    speeds = [float(l.split("sinking at ")[1].split()[0]) for l in progress]
    assert all(abs(v) < 1000 for v in speeds) and len(set(speeds)) == 4    # measured, mm/s
    out = lmprun.run(lmprun.ROOT / "inputs" / "in.fill", tmp_path, variables=dict(tight, vtol=1.0)).check().output
    assert "SETTLED: after 2000 steps" in out and out.count("SETTLING:") == 1 and "not settled" not in out
    bad = lmprun.run(lmprun.ROOT / "inputs" / "in.fill", tmp_path, variables=dict(tight, nsettle=2500))
    assert bad.returncode != 0 and "nsettle must be >= 1, a multiple of settle_chunk" in bad.output


def test_seed_changes_the_packing(tmp_path):
    """-var seed gives another random packing (not round-off): the same grains (count and sizes),
    other positions; the same seed gives the same packing."""
    lmprun.run(lmprun.ROOT / "inputs" / "in.bag", tmp_path, variables=SMALL).check()
    fills = {}
    for name, seed in (("a", 4821), ("b", 4822), ("c", 4821)):
        lmprun.run(lmprun.ROOT / "inputs" / "in.fill", tmp_path, variables=dict(
            SMALL, tbags=lmprun.ROOT, seed=seed, out="fill.%s.data" % name)).check()
        fills[name] = sand_rows(tmp_path / ("fill.%s.data" % name))
    a, b, c = fills["a"], fills["b"], fills["c"]
    moved = np.linalg.norm(a[:, 2:] - b[:, 2:], axis=1)
    print("%d grains; seeds 4821 and 4822: median position difference %.2f mm" % (len(a), np.median(moved) * 1e3))
    assert len(a) == len(b) > 50 and np.array_equal(np.sort(a[:, 1]), np.sort(b[:, 1]))
    assert np.median(moved) > 1e-3          # a millimetre and more: another packing
    assert np.array_equal(a, c)             # the seed, not chance, decides


def test_sand_parameter_sets(tmp_path):
    """-var sand paper|calibrated: the paper's sand, or the one calibration/fit.py wrote to
    calibration/results/sand_calibrated.lmp; a changed fit file changes the decks' friction."""
    lmprun.run(lmprun.ROOT / "inputs" / "in.bag", tmp_path, variables=SMALL).check()
    fit = (lmprun.ROOT / "calibration" / "results" / "sand_calibrated.lmp").read_text()
    mu = float(re.search(r"variable sand_mu equal (\S+)", fit).group(1))
    mur = float(re.search(r"variable sand_mur equal (\S+)", fit).group(1))

    def coeff(root, sand):
        lmprun.run(lmprun.ROOT / "inputs" / "in.fill", tmp_path, variables=dict(
            SMALL, tbags=root, sand=sand, nsettle=10)).check()
        # the settling pair_coeff of the sand as LAMMPS ran it (variables substituted)
        log = (tmp_path / "log.lammps").read_text()
        line = [l for l in log.splitlines() if l.startswith("pair_coeff") and " 2 2 " in l][-1]
        w = line.split()
        return float(w[w.index("friction") + 1]), float(w[w.index("rolling") + 1])

    assert coeff(lmprun.ROOT, "paper") == (0.31, 0.05)
    assert coeff(lmprun.ROOT, "calibrated") == (mu, mur)
    # a copy of the tree with another fit: the deck follows the file
    other = tmp_path / "tree"
    shutil.copytree(lmprun.ROOT / "inputs", other / "inputs")
    (other / "calibration" / "results").mkdir(parents=True)
    (other / "calibration" / "results" / "sand_calibrated.lmp").write_text(
        fit.replace("sand_mu equal %s" % re.search(r"sand_mu equal (\S+)", fit).group(1), "sand_mu equal 0.555"))
    assert coeff(other, "calibrated") == (0.555, mur)
    res = lmprun.run(lmprun.ROOT / "inputs" / "in.fill", tmp_path, variables=dict(SMALL, tbags=lmprun.ROOT, sand="toyoura"))
    assert res.returncode != 0 and "sand must be paper or calibrated (got toyoura)" in res.output


def test_time_step_follows_the_grains_modulus(tmp_path):
    """inputs/sand.lmp's rule: a deck's dt0 (its step for grains up to the paper's 1.8 GPa) times
    sqrt(1.8 GPa / E) for stiffer grains, -var dt overriding; the fill's 2e-6 s follows it too.
    The shear decks give dt0 (not dt) before they include sand.lmp, and use dt after it."""
    fit = (lmprun.ROOT / "calibration" / "results" / "sand_calibrated.lmp").read_text()
    tree = tmp_path / "tree"
    shutil.copytree(lmprun.ROOT / "inputs", tree / "inputs")
    (tree / "calibration" / "results").mkdir(parents=True)
    (tree / "calibration" / "results" / "sand_calibrated.lmp").write_text(
        re.sub(r"sand_E equal \S+", "sand_E equal 7.2e9", fit))
    deck = tmp_path / "in.dt"
    deck.write_text("variable dt0 index 1.5e-6\ninclude ${tbags}/inputs/sand.lmp\n"
                    "print \"DT=${dt}\" file dt.txt\n")

    def dt(sand, **extra):
        lmprun.run(deck, tmp_path, variables=dict(tbags=tree, sand=sand, **extra)).check()
        return float((tmp_path / "dt.txt").read_text().split("=")[1])

    assert dt("paper") == 1.5e-6                      # bit for bit: the paper's runs are unchanged
    assert dt("calibrated") == pytest.approx(0.75e-6, rel=1e-12)
    assert dt("calibrated", dt=1e-6) == 1e-6          # a step of one's own
    lmprun.run(lmprun.ROOT / "inputs" / "in.bag", tmp_path, variables=SMALL).check()
    lmprun.run(lmprun.ROOT / "inputs" / "in.fill", tmp_path,
               variables=dict(SMALL, tbags=tree, sand="calibrated", nsettle=10)).check()
    steps = [l.split() for l in (tmp_path / "log.lammps").read_text().splitlines() if l.startswith("timestep")]
    assert float(steps[-1][1]) == pytest.approx(1e-6, rel=1e-12)   # as LAMMPS ran it
    for name in ("in.shear", "in.cyclic", "in.press"):
        text = (lmprun.ROOT / "inputs" / name).read_text()
        assert re.search(r"^variable\s+dt0 index", text, re.M), name
        assert not re.search(r"^variable\s+dt index", text, re.M), name
        include = re.search(r"^include\s+\$\{tbags\}/inputs/sand.lmp", text, re.M).start()
        assert text.index("dt0 index") < include < text.index("v_dt"), name
