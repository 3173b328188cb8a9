"""inputs/in.fill on a small bag: the exact count at void ratio 0.68 +/- 0.01, equal number
fractions of the ten sizes, settled with small overlaps and every bag bond intact."""
import numpy as np

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
    # sizes in the data file: equal number fractions (within one grain)
    data = (tmp_path / "fill.data").read_text()
    atoms = data[data.index("Atoms"):data.index("Velocities")].splitlines()[2:]
    rows = np.array([[float(x) for x in l.split()[:7]] for l in atoms if l.strip()])
    sand = rows[rows[:, 2] == 2]    # bpm/sphere: id molecule type diameter density x y z
    counts = [np.sum(np.isclose(sand[:, 3], d, rtol=1e-6)) for d in SIZES]
    assert len(sand) == grains and max(counts) - min(counts) <= 1, counts
    e_exact = inner / np.sum(np.pi / 6 * sand[:, 3] ** 3) - 1
    assert abs(e - e_exact) < 1e-4, (e, e_exact)


def test_paper_bag_holds_the_papers_count(tmp_path):
    """81 x 81 x 17: 97,130 grains, 9,713 of each size (MODEL.md section 2), e = 0.68 +/- 0.01."""
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
