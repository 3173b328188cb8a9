"""The simple shear protocol (in.bag, in.fill, in.shear) end to end on a tiny bag: the plate
reaches F_v, shears at constant speed with F_v held, and writes the CSV and dumps; bad -var
values stop with a clear message."""
import re

import numpy as np
import pytest

import lmprun

INPUTS = lmprun.INPUTS
SIZE = lmprun.TINY_BAG


@pytest.fixture(scope="module")
def filled(tiny_filled):
    return tiny_filled


def test_protocol_on_a_tiny_bag(filled):
    res = lmprun.run(INPUTS / "in.shear", filled, variables=dict(SIZE, v=0.02, ufinal=0.0003, du_dump=0.0001)).check()
    out = res.output
    comp = [l for l in out.splitlines() if l.startswith("COMPRESSED")][0]
    fv, target = float(comp.split()[2]), float(comp.split()[5].rstrip("),"))
    print(comp)
    assert abs(fv - target) < 0.005 * target
    assert abs(target - 5500 * 7 * 7 / 79 ** 2) < 1e-9
    d = np.genfromtxt(filled / "shear.csv", delimiter=",", names=True)
    print("CSV rows: u = %s mm, S = %s N, F_v = %s N" % (d["u_mm"], d["S_N"], d["Fv_N"]))
    # rows: u = 0, then the means of each 0.1 mm (u at the interval's middle)
    assert len(d) == 4 and np.allclose(d["u_mm"], [0, 0.05, 0.15, 0.25], atol=1e-3)
    assert (d["S_N"][1:] > 0).all()
    # F_v held: each interval's mean within 1 % of the target
    assert np.abs(d["Fv_N"][1:] - target).max() < 0.01 * target
    assert list(filled.glob("dump.grains.*")) and list(filled.glob("dump.contacts.*"))


@pytest.mark.parametrize("var,message", [({"nx": 2}, "nx, ny, nz must be at least 3"),
                                         ({"Fv": -5}, "Fv must be > 0"),
                                         ({"ufinal": 0}, "v and ufinal must be > 0"),
                                         ({"du_dump": 5e-5}, "du_dump >= du_csv"),
                                         ({"damping": "sideways"}, "damping must be implicit or explicit"),
                                         ({"checkpoint_first": 3}, "checkpoint_first must be 1 or 2")])
def test_bad_variables(tmp_path, var, message):
    res = lmprun.run(INPUTS / "in.shear", tmp_path, variables=dict(SIZE, **var))
    assert res.returncode != 0 and message in res.output


def test_resume_from_checkpoint(filled, tmp_path):
    """A checkpoint written while shearing resumes the shear stage on 2 ranks: the plate continues
    from its state and the CSV is appended up to u_final. The checkpoint is picked by name: the
    deck alternates shear.restart.1 and .2 every du_dump of u, so with checkpoints at 0.2, 0.4 and
    0.6 mm, .2 holds u = 0.4 mm. The resumed run starts with a fresh force evaluation (LAMMPS
    setup uses full-step velocities) on another decomposition, so it is close, not bit-identical:
    its first three rows (every 0.02 mm) are within 0.5 % of the straight run's S range and 1 um
    of w; further on, the round-off difference grows until a grain collapse happens some steps
    earlier or later (measured: w jumps 0.02 mm apart after 0.1 mm; S 3.0 N apart, 8 % of the S
    range, on the present tiny fill, 5 % on an earlier one), so all ten rows are held to 10 % of
    the S range and 0.05 mm of w, a bound on chaos, not on the restart (the spread between
    realizations is larger)."""
    import shutil
    shutil.copy(filled / "fill.data", tmp_path)
    v = dict(SIZE, v=0.02, ufinal=0.0006, du_dump=0.0002, du_csv=2e-5)
    lmprun.run(INPUTS / "in.shear", tmp_path, variables=v).check()
    straight = np.genfromtxt(tmp_path / "shear.csv", delimiter=",", names=True)
    # the checkpoint's row is not written again: the resumed rows continue after it; its first
    # checkpoint goes to the other file (-var checkpoint_first, as the launcher sets it), the
    # one resumed from is left as it was
    resumed_from = (tmp_path / "shear.restart.2").read_bytes()
    res = lmprun.run(INPUTS / "in.shear", tmp_path, np_ranks=2,
                     variables=dict(v, restart="shear.restart.2", checkpoint_first=1)).check()
    assert (tmp_path / "shear.restart.2").read_bytes() == resumed_from
    rows = np.genfromtxt(tmp_path / "shear.csv", delimiter=",", names=True)[len(straight):]
    same = straight[len(straight) - len(rows):]
    span = straight["S_N"].max() - straight["S_N"].min()
    print("resumed from u = 0.4 mm on 2 ranks, %d rows: |dS| %s N (S range %.1f N), max |dw| %.2e mm"
          % (len(rows), np.round(np.abs(rows["S_N"] - same["S_N"]), 3), span,
             np.abs(rows["w_mm"] - same["w_mm"]).max()))
    assert len(rows) == 10 and rows["u_mm"][0] == pytest.approx(0.41, abs=1e-3)
    assert np.allclose(rows["u_mm"], same["u_mm"], atol=1e-4)
    # the first rows close (round-off of another decomposition grows through the grains' slips:
    # measured 0.0, 0.0005, 0.36 N of a 38 N range on the third row), all within the spread
    assert np.abs(rows["S_N"][:2] - same["S_N"][:2]).max() < 0.005 * span
    assert np.abs(rows["w_mm"][:2] - same["w_mm"][:2]).max() < 1e-3
    assert np.abs(rows["S_N"] - same["S_N"]).max() < 0.10 * span
    assert np.abs(rows["w_mm"] - same["w_mm"]).max() < 0.05
    assert "SHEARED: u 0.600 mm" in res.output


def test_resumed_run_never_writes_over_its_checkpoint(filled, tmp_path):
    """Resumed from shear.restart.1 with -var checkpoint_first 2 (what ./tbags shear --resume
    passes), the run's first checkpoint goes to shear.restart.2: a stop while it writes leaves the
    checkpoint it came from (after ./tbags wip unpack, the only one). With the deck's former fixed
    order (.1 first) this fails: .1 is written over at u = 0.4 mm."""
    import shutil
    shutil.copy(filled / "fill.data", tmp_path)
    v = dict(SIZE, v=0.02, ufinal=0.0002, du_dump=0.0002)
    lmprun.run(INPUTS / "in.shear", tmp_path, variables=v).check()    # shear.restart.1 at 0.2 mm
    (tmp_path / "shear.restart.2").unlink(missing_ok=True)
    came_from = (tmp_path / "shear.restart.1").read_bytes()
    lmprun.run(INPUTS / "in.shear", tmp_path, variables=dict(v, ufinal=0.0004, restart="shear.restart.1",
                                                              checkpoint_first=2)).check()
    assert (tmp_path / "shear.restart.1").read_bytes() == came_from
    assert (tmp_path / "shear.restart.2").is_file()


def test_box_widened_for_the_walls(filled, tmp_path):
    """-var room (and, by default, ufinal + 0.3 of the bag's height on big bags: the paper bag lost
    a wall particle past in.bag's 20 mm margin) widens the box in x and y, also when resumed from a
    checkpoint, whose contact histories LAMMPS must reassign first (a 'run 0' after the fixes). A
    checkpoint resumed with and without the widening continues the same: the first rows within
    0.5 % of the S range (the other box's neighbour order is round-off; the sandpaper plates' and
    the grains' tangential histories, if lost, drop S by tens of %). Resumed again from the widened
    run's checkpoint, the box is not widened twice; a room <= 0 is refused."""
    import shutil
    shutil.copy(filled / "fill.data", tmp_path)
    v = dict(SIZE, v=0.02, ufinal=0.0002, du_dump=0.0002, du_csv=2e-5)
    res = lmprun.run(INPUTS / "in.shear", tmp_path, variables=v).check()    # shear.restart.1 at 0.2 mm
    assert "BOX:" not in res.output    # a small bag keeps in.bag's box
    start = len(np.genfromtxt(tmp_path / "shear.csv", delimiter=",", names=True))
    shutil.copy(tmp_path / "shear.restart.1", tmp_path / "at0.2.restart")
    rows = {}
    for name, extra in (("kept", {}), ("widened", {"room": 0.03})):
        shutil.copy(tmp_path / "at0.2.restart", tmp_path / "shear.restart.1")
        shutil.copy(tmp_path / "shear.csv", tmp_path / ("csv." + name))
        res = lmprun.run(INPUTS / "in.shear", tmp_path, variables=dict(v, ufinal=0.0004, restart="shear.restart.1",
                                                                      checkpoint_first=2, **extra)).check()
        rows[name] = np.genfromtxt(tmp_path / "shear.csv", delimiter=",", names=True)[start:]
        assert ("BOX: widened for the walls (room 30.0 mm): x -0.0300 0.0700, y -0.0300 0.0700 m" in res.output) \
            == (name == "widened")
        shutil.copy(tmp_path / ("csv." + name), tmp_path / "shear.csv")
    kept, wide = rows["kept"], rows["widened"]
    span = kept["S_N"].max() - kept["S_N"].min()
    print("resumed at u = 0.2 mm with and without the widened box: |dS| %s N (S range %.1f N)"
          % (np.round(np.abs(wide["S_N"] - kept["S_N"]), 4), span))
    assert len(wide) == len(kept) == 10
    assert np.abs(wide["S_N"][:2] - kept["S_N"][:2]).max() < 0.005 * span
    # the widened run's checkpoint (shear.restart.2, at 0.4 mm) holds the wide box: not widened again
    res = lmprun.run(INPUTS / "in.shear", tmp_path, variables=dict(v, ufinal=0.0006, restart="shear.restart.2",
                                                                  checkpoint_first=1, room=0.03)).check()
    assert "BOX:" not in res.output and "SHEARED: u 0.600 mm" in res.output
    res = lmprun.run(INPUTS / "in.shear", tmp_path / "bad", variables=dict(SIZE, room=-2))
    assert res.returncode != 0 and "room must be > 0 m" in res.output


def test_loads_share_the_start_of_their_compression(filled, tmp_path):
    """-var compress_to 0.9 at the smallest load compresses to 0.9 F_v and checkpoints; a run at a
    larger load continues from it (-var compress_from) as if it had compressed from the start:
    the plate runs at its speed limit until the force nears the target, so the same steps for
    every load. Against the straight run at that load: the same total of compression steps (to
    the 1,000 of the convergence check), the plate at the same depth, the target reached (not the
    checkpoint's), then the first rows of shear within 0.5 % of the S range (the restart's fresh
    force evaluation, then chaos: 10 % for all rows, as in test_resume_from_checkpoint)."""
    import re
    import shutil
    import sys
    sys.path.insert(0, str(lmprun.ROOT / "postprocess"))
    from tbagspost.run import loops

    v = dict(SIZE, v=0.02, ufinal=0.0002, du_dump=0.001, du_csv=2e-5)
    out = {}
    for name, extra in (("straight", dict(Fpaper=5500)), ("part", dict(Fpaper=1960, compress_to=0.9)),
                        ("rest", dict(Fpaper=5500, compress_from="../part/compress.restart"))):
        wd = tmp_path / name
        wd.mkdir()
        shutil.copy(filled / "fill.data", wd)
        out[name] = lmprun.run(INPUTS / "in.shear", wd, variables=dict(v, **extra)).check()
    part = re.search(r"COMPRESSION PART: F_v (\S+) N \(0.9 of (\S+) N\)", out["part"].output)
    assert part and float(part.group(1)) >= 0.9 * float(part.group(2))
    assert (tmp_path / "part" / "compress.restart").is_file() and not (tmp_path / "part" / "shear.csv").exists()
    comp = {}
    for name in ("straight", "rest"):
        line = re.search(r"COMPRESSED: F_v (\S+) N \(target (\S+)\), w (\S+) mm", out[name].output)
        comp[name] = [float(x) for x in line.groups()]
        assert abs(comp[name][0] - comp[name][1]) < 0.005 * comp[name][1]
    n_straight, n_part, n_rest = (loops((tmp_path / n / "log.lammps").read_text())[0]["steps"]
                                  for n in ("straight", "part", "rest"))
    print("compression steps: straight %d, shared part %d + rest %d; COMPRESSED %s" % (
        n_straight, n_part, n_rest, comp))
    assert comp["rest"][1] == comp["straight"][1] and abs(comp["rest"][2] - comp["straight"][2]) < 1e-3
    assert abs(n_part + n_rest - n_straight) <= 1000 and n_part > 0.5 * n_straight
    a, b = (np.genfromtxt(tmp_path / n / "shear.csv", delimiter=",", names=True) for n in ("straight", "rest"))
    span = a["S_N"].max() - a["S_N"].min()
    print("|dS| %s N (S range %.1f N)" % (np.round(np.abs(a["S_N"] - b["S_N"]), 3), span))
    assert len(a) == len(b) == 11 and np.allclose(a["u_mm"], b["u_mm"], atol=1e-4)
    assert np.abs(a["S_N"][:3] - b["S_N"][:3]).max() < 0.005 * span
    assert np.abs(a["S_N"] - b["S_N"]).max() < 0.10 * span


@pytest.mark.parametrize("var,message", [
    ({"compress_from": "nothere.restart"}, "no compression checkpoint nothere.restart"),
    ({"compress_to": 0.99}, "compress_to must be below 0.98"),
    ({"compress_to": 0.5, "compress_from": "x"}, "no compression checkpoint x"),
    ({"compress_to": 0.5, "compress_every": 0}, "compress_every must be a whole number of steps >= 1"),
    ({"compress_to": 0.5, "compress_every": 2.5}, "compress_every must be a whole number of steps >= 1")])
def test_bad_shared_compression(filled, tmp_path, var, message):
    res = lmprun.run(INPUTS / "in.shear", tmp_path, variables=dict(SIZE, fill=filled / "fill.data", **var))
    assert res.returncode != 0 and message in res.output


def test_shared_part_past_a_smaller_load_is_refused(filled, tmp_path):
    """A checkpoint made past the force where a smaller load's servo slows down would give that
    load another compression than its own: refused."""
    import shutil
    shutil.copy(filled / "fill.data", tmp_path)
    lmprun.run(INPUTS / "in.shear", tmp_path, variables=dict(SIZE, Fpaper=5500, compress_to=0.5)).check()
    res = lmprun.run(INPUTS / "in.shear", tmp_path, variables=dict(SIZE, Fpaper=1960, compress_from="compress.restart"))
    assert res.returncode != 0 and "where this run (F_v" in res.output and "slows down" in res.output
    # a finished part given as a stopped one (compress_to with compress_from): refused too
    res = lmprun.run(INPUTS / "in.shear", tmp_path, variables=dict(SIZE, Fpaper=5500, compress_to=0.5,
                                                                   compress_from="compress.restart"))
    assert res.returncode != 0 and "it is a finished part" in res.output


@pytest.mark.parametrize("damping", ["explicit", "implicit"])
def test_same_on_one_and_two_ranks(filled, tmp_path, damping):
    """The whole shear stage (compression and the first 0.2 mm of shear) on 1 and 2 ranks gives
    the same CSV, digit for digit (forces agree to round-off, which the CSV's 4 decimals hide), with
    the plates' explicit (default) and implicit damping (-var damping: fix wall/gran/servo's keyword
    on both plates only when implicit)."""
    import shutil
    v = dict(SIZE, v=0.02, ufinal=0.0002, du_dump=0.001, damping=damping)
    csv = {}
    for ranks in (1, 2):
        wd = tmp_path / str(ranks)
        wd.mkdir()
        shutil.copy(filled / "fill.data", wd)
        lmprun.run(INPUTS / "in.shear", wd, np_ranks=ranks, variables=v).check()
        csv[ranks] = (wd / "shear.csv").read_text()
        fixes = [line for line in (wd / "log.lammps").read_text().splitlines()
                 if line.startswith("fix") and "wall/gran/servo" in line and "$" not in line]
        assert len(fixes) == 2 and all(("damping implicit" in f) == (damping == "implicit") for f in fixes)
    print(csv[2])
    assert csv[1] == csv[2] and len(csv[1].splitlines()) >= 4


def test_csv_rows_are_interval_means(filled, tmp_path):
    """Each CSV row holds the mean, min and max over every step of its interval: the same run's
    per-step trace (trace 1) averaged over the row's steps gives the row, column by column."""
    import shutil
    shutil.copy(filled / "fill.data", tmp_path)
    lmprun.run(INPUTS / "in.shear", tmp_path, variables=dict(SIZE, v=0.02, ufinal=0.0003, trace=1)).check()
    rows = np.genfromtxt(tmp_path / "shear.csv", delimiter=",", names=True)
    tr = np.genfromtxt(tmp_path / "shear.steps.csv", delimiter=",", names=True)
    n = int(rows["steps"][1])
    assert rows["steps"][0] == 1 and (rows["steps"][1:] == n).all() and n == round(1e-4 / (0.02 * 1.5e-6))
    # the trace starts at the u = 0 step (the CSV's first row) and has every step once
    s0 = tr["step"][0]
    assert np.all(np.diff(tr["step"]) == 1) and len(tr) > n * (len(rows) - 1)
    for k in range(1, len(rows)):
        chunk = tr[(tr["step"] > s0 + (k - 1) * n) & (tr["step"] <= s0 + k * n)]
        assert len(chunk) == n
        for col, scale in (("time_s", 1e-7), ("u_mm", 1e-4), ("w_mm", 1e-4), ("S_N", 1e-4),
                           ("Fv_N", 1e-4), ("zplate_mm", 1e-4)):
            assert rows[col][k] == pytest.approx(chunk[col].mean(), abs=scale), (k, col)
        for col in ("w", "S", "Fv", "zplate"):
            unit = "_N" if col in ("S", "Fv") else "_mm"
            assert rows[col + "_min" + unit][k] == pytest.approx(chunk[col + unit].min(), abs=1e-4)
            assert rows[col + "_max" + unit][k] == pytest.approx(chunk[col + unit].max(), abs=1e-4)
    # the first row is the one step before shearing
    assert rows["S_N"][0] == pytest.approx(tr["S_N"][0], abs=1e-4)
    # the means differ from the interval's last step, as they should for a varying force
    last = np.array([tr["S_N"][tr["step"] == s0 + k * n][0] for k in range(1, len(rows))])
    assert np.abs(rows["S_N"][1:] - last).max() > 1e-3


def test_yarn_shear_spring_is_a_choice(filled, tmp_path):
    """-var yarn_shear 0 drops the yarn bonds' shear spring (bonds then resist tension, bending and
    twisting only): on this bag the walls' shear springs carry most of S, so S falls sharply."""
    import shutil
    S = {}
    for k in (-1, 0):
        wd = tmp_path / str(k)
        wd.mkdir()
        shutil.copy(filled / "fill.data", wd)
        lmprun.run(INPUTS / "in.shear", wd, variables=dict(SIZE, v=0.02, ufinal=0.0006, yarn_shear=k)).check()
        log = (wd / "log.lammps").read_text()
        coeff = [l for l in log.splitlines() if re.match(r"\s*bond_coeff\s+1\s+table", l)][-1]
        assert (" shear 0" in coeff) == (k == 0), coeff
        S[k] = np.genfromtxt(wd / "shear.csv", delimiter=",", names=True)["S_N"][-1]
    print("S at 0.55 mm: %.2f N with the shear spring, %.2f N without" % (S[-1], S[0]))
    assert S[0] < 0.5 * S[-1]


def test_overloaded_bag_tears(filled, tmp_path):
    """The tiny bag compressed to 10 kN (8 MPa on its 35 x 35 mm sand plan, 80 times the paper's
    highest stress): yarns stretch past 16 % and break. The CSV's broken_bonds (from compute
    nbond/atom: bond ends lost, halved) equals the count from the bond dumps (compute bond/local
    lists the bonds still there: the intact bag's 512 less them), at every dump."""
    import shutil
    shutil.copy(filled / "fill.data", tmp_path)
    res = lmprun.run(INPUTS / "in.shear", tmp_path, variables=dict(
        SIZE, Fv=10000, v=0.02, ufinal=0.0002, du_dump=0.0001, vmax_compress=0.1)).check()
    rows = np.genfromtxt(tmp_path / "shear.csv", delimiter=",", names=True)
    broken = int(res.output.split("broken bonds")[-1].split()[0])
    dumps = sorted(tmp_path.glob("dump.bonds.*"), key=lambda p: int(p.suffix[1:]))
    listed = [int(p.read_text().splitlines()[3]) for p in dumps]
    print("broken bonds: CSV %s, last line %d; bonds listed in the dumps %s of 512" % (rows["broken_bonds"], broken, listed))
    assert broken > 0 and len(dumps) == 3
    assert rows["broken_bonds"][-1] == broken
    assert all(512 - n == broken for n in listed)


def test_load_path_sums_to_the_plate_forces(filled, tmp_path):
    """What crosses the bag's mid-height (tbagspost.loadpath: contacts of each class and the yarn
    bonds' whole forces, from the dumps) is, at each dump step, the top plate's F_v plus the weight
    above the plane and its S, within 1 % averaged over the shear's dumps and 3 % at each (sheared at
    5 mm/s; a single step holds some inertia of the part above: measured up to 2 %); the plate's
    forces at exactly that step come from the trace. The same sums without the bonds miss S by most of it (solid fabric)."""
    import sys
    sys.path.insert(0, str(lmprun.ROOT / "postprocess"))
    from tbagspost import loadpath, run as tbrun
    lmprun.run(INPUTS / "in.shear", tmp_path, variables=dict(SIZE, fill=filled / "fill.data", v=0.005, ufinal=0.0003,
                                                             du_dump=0.00005, du_csv=0.00005, trace=1)).check()
    steps = np.genfromtxt(tmp_path / "shear.steps.csv", delimiter=",", names=True)
    r = tbrun.Run(tmp_path)
    ratios = []
    for step in r.steps("contacts")[1:]:    # (the first dump: the plate starting to move)
        g = r.grains(step)
        x = loadpath.through_plane(g, r.contacts(step), b=r.bonds(step))
        k = int(np.nonzero(steps["step"] == step)[0][0])
        mass = np.where(g.types == 1, 450.0, 2650.0) * 4 / 3 * np.pi * g.radius ** 3
        weight = 9.81 * mass[g.pos[:, 2] > x["z"]].sum()
        vz, hx = x["Fz"] / (steps["Fv_N"][k] + weight), x["Fx"] / steps["S_N"][k]
        no_bonds = (x["Fx"] - x["bonds"][1]) / steps["S_N"][k]
        print("step %d: vertical %.4f of F_v + W, horizontal %.4f of S (%.3f without the bonds)"
              % (step, vz, hx, no_bonds))
        assert abs(vz - 1) < 0.03 and abs(hx - 1) < 0.03
        ratios.append((vz, hx))
    vz, hx = np.mean(ratios, axis=0)
    assert len(ratios) >= 3 and abs(vz - 1) < 0.01 and abs(hx - 1) < 0.01
