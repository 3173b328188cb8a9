"""Run LAMMPS decks for the tests, through the launcher's runner (launcher/tbagsrun/lammps.py),
and read what they write.

Every deck test imports this module. The environment comes from ctest (TBAGS_LMP,
LAMMPS_PLUGIN_PATH); run through `./tbags test` or `ctest` rather than by hand.
"""
import os
import sys
import textwrap
from pathlib import Path

import numpy as np

ROOT = Path(os.environ.get("TBAGS_ROOT", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(ROOT / "launcher"))
from tbagsrun import lammps  # noqa: E402
from tbagsrun.presets import DEMO_BAG, PRESETS  # noqa: E402

LMP = os.environ.get("TBAGS_LMP", "")
PLUGIN = Path(os.environ.get("LAMMPS_PLUGIN_PATH", "")) / "tbagsplugin.so"


INPUTS = ROOT / "inputs"
# the sanitized build (ASan + UBSan) runs LAMMPS 5-10 times slower: every time limit a test sets
# is multiplied by this (measured: ./tbags fabric on the tiny bag took more than 1,200 s there)
SLOWDOWN = 8 if os.environ.get("TBAGS_SANITIZE") == "1" else 1
# the deck tests' bag: 258 particles, 153 grains; each stage takes seconds
TINY_BAG = {"nx": 9, "ny": 9, "nz": 5}


def bag_and_fill(workdir, size=TINY_BAG):
    """inputs/in.bag and in.fill in workdir: a filled bag for the shear, cyclic and stack tests."""
    for deck in ("in.bag", "in.fill"):
        run(INPUTS / deck, workdir, variables=size).check()
    Path(workdir, ".size").write_text(size_key(size))
    return Path(workdir)


def size_key(size):
    """A bag's size as bag_and_fill stamps it (.size), for filled_bag to match."""
    return repr(sorted(size.items()))


# the suite's shared products (ctest fixtures, tests/decks/make_fixture.py): made once per ctest
# run into TBAGS_FIXTURES/<name>, copied by the tests that need them; made here when absent (a
# test run by hand)
FIXTURES = os.environ.get("TBAGS_FIXTURES", "")


def shared(name):
    """The folder of the suite's fixture `name` if ctest made it, else None."""
    folder = Path(FIXTURES) / name if FIXTURES else None
    return folder if folder and (folder / ".done").is_file() else None


def filled_bag(workdir, size=TINY_BAG):
    """A filled bag in workdir: the suite's shared fill of this size copied (fixture "tiny"), or
    bag_and_fill() when there is none."""
    import shutil
    src = shared("tiny")
    if src and (src / ".size").read_text() == size_key(size):
        Path(workdir).mkdir(parents=True, exist_ok=True)
        for f in src.iterdir():
            if f.is_file() and f.name != ".done":
                shutil.copy2(f, Path(workdir) / f.name)
        return Path(workdir)
    return bag_and_fill(workdir, size)


# the demo preset's bag and shear, with the decks' step and plate damping said explicitly, to
# u = 2 mm of the preset's 5 (the suite's time: the shear is 85 % of the run; the committed
# realizations give the spread at every mm, results/demo-realizations-by-u.csv)
DEMO_U = 2.0
DEMO_SHEAR = dict(DEMO_BAG, **dict(PRESETS["demo"].runs[0].variables, ufinal=DEMO_U / 1000),
                  dt=1.5e-6, damping="explicit")


def demo_run(workdir):
    """The main job's bag, fill (seed 4821) and shear (the demo preset's protocol to DEMO_U, 1 rank) in
    workdir, with LAMMPS's output; returns (workdir, the shear's screen output)."""
    bag_and_fill(workdir, DEMO_BAG)
    res = run(INPUTS / "in.shear", workdir, variables=DEMO_SHEAR, timeout=3600).check()
    Path(workdir, "shear.output.txt").write_text(res.output)
    return Path(workdir), res.output


def demo(workdir):
    """demo_run()'s folder: the suite's shared one (fixture "demo"), else made in workdir."""
    src = shared("demo")
    if src:
        return src, (src / "shear.output.txt").read_text()
    return demo_run(workdir)


def run(deck, workdir, np_ranks=1, variables=None, args=(), plugin_path=True, timeout=1200,
        engine="lammps"):
    """Run `deck` (text, written to in.test, or a path) in workdir; returns the runner's Result
    (not checked: .check() raises with LAMMPS's first ERROR line). engine: "liggghts" runs the
    LIGGGHTS build with our styles (TBAGS_LIGGGHTS) instead."""
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    if isinstance(deck, Path):
        deck_file = deck
    else:
        deck_file = workdir / "in.test"
        deck_file.write_text(textwrap.dedent(deck))
    return lammps.run(deck_file, workdir, np_ranks, variables, args, timeout=timeout * SLOWDOWN,
                      plugin=plugin_path, engine=engine)


def read_dump(path, last=False):
    """A 'dump/write_dump ... custom' text file's first (or last) snapshot: (columns, array)."""
    lines = Path(path).read_text().splitlines()
    heads = [k for k, line in enumerate(lines) if line.startswith("ITEM: ATOMS")]
    if not heads:
        raise ValueError("no ITEM: ATOMS in %s" % path)
    k = heads[-1] if last else heads[0]
    rows = []
    for line in lines[k + 1:]:
        if line.startswith("ITEM:"):
            break
        if line.strip():
            rows.append([float(x) for x in line.split()])
    return lines[k].split()[2:], np.array(rows)


def column(path, name):
    cols, data = read_dump(path)
    return data[:, cols.index(name)]


def max_rel_diff(a, b):
    """Largest component difference relative to the largest magnitude in b."""
    a, b = np.asarray(a), np.asarray(b)
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


def packing_head(newton=None):
    """Deck head that reads a sphere packing (variable data) with an atom map, as the pair tests do."""
    return ("\nunits si\natom_style sphere\natom_modify map array\nboundary p p p\ncomm_modify vel yes\n"
            + ("newton %s\n" % newton if newton else "") + "read_data ${data}\n")


# deck head for a few bonded bpm/sphere particles placed by create_atoms (the bond tests, the
# pair's special-bond test): an atom map, newton_bond off, room for bonds and special partners
BPM_HEAD = """
units si
atom_style bpm/sphere
atom_modify map array
boundary f f f
comm_modify vel yes
newton on off
region box block -0.01 0.07 -0.02 0.02 -0.02 0.02
create_box 1 box bond/types 1 extra/bond/per/atom 2 extra/special/per/atom 4
"""


# deck tail that records every contact through compute pair/local (single()) and the per-atom
# forces of compute(): contact_force_sums() then compares the two
CONTACT_DUMP = """
compute pl all pair/local dist fx fy fz p1 p2 p3 cutoff radius
compute pid all property/local patom1 patom2 cutoff radius
dump c all local 1 contacts.dump c_pid[*] c_pl[*]
dump_modify c format float %.17g
run 0
write_dump all custom forces.dump id fx fy fz modify sort id format float %.17g
"""


def force_torque_diff(dump_a, dump_b):
    """Two write_dump files with fx fy fz tqx tqy tqz (sorted by id): the largest force and torque
    differences, each relative to the largest value of the second."""
    cols, a = read_dump(dump_a)
    _, b = read_dump(dump_b)
    f = [cols.index(c) for c in ("fx", "fy", "fz")]
    t = [cols.index(c) for c in ("tqx", "tqy", "tqz")]
    return max_rel_diff(a[:, f], b[:, f]), max_rel_diff(a[:, t], b[:, t])


def contact_force_sums(workdir):
    """After a deck ending in CONTACT_DUMP: (contacts, ids, per-atom forces of compute(), sums of
    the contact forces per atom). Contact columns: id1 id2 dist, normal force on id1 (3),
    tangential force on id1 (3)."""
    lines = (Path(workdir) / "contacts.dump").read_text().splitlines()
    k = max(i for i, l in enumerate(lines) if l.startswith("ITEM: ENTRIES"))
    c = np.array([[float(x) for x in l.split()] for l in lines[k + 1:] if l.strip()])
    _, rows = read_dump(Path(workdir) / "forces.dump")
    ids = rows[:, 0].astype(int)
    F = np.zeros((ids.max() + 1, 3))
    fij = c[:, 3:6] + c[:, 6:9]
    np.add.at(F, c[:, 0].astype(int), fij)
    np.add.at(F, c[:, 1].astype(int), -fij)
    return c, ids, rows[:, 1:4], F[ids]
