"""The same particles in LAMMPS (with the tbags plugin) and in LIGGGHTS (with our styles built
in), for the cross-checks test_liggghts_*.py and the engines' benchmark (bench/engines.py): data
files in each engine's atom style, a thermo table of per-atom values both engines print the same
way, its reader, the comparison, and the decks of a filled bag pressed between two plates.
"""
import re
import sys

import numpy as np

import lmprun

sys.path.insert(0, str(lmprun.ROOT / "postprocess"))
from tbagspost.datafile import DataFile  # noqa: E402

# per-atom values printed each thermo step (equal-style variables cannot read torques in
# LAMMPS, so both engines go through compute property/atom)
COLS = ("x", "y", "z", "fx", "fy", "fz", "tqx", "tqy", "tqz", "omegax", "omegay", "omegaz")


def data_file(path, atoms, ntypes, bonds=(), engine="lammps", box=(-0.01, 0.01, -0.01, 0.01, -0.005, 0.01)):
    """atoms: (id, type, diameter, density, (x, y, z), (vx, vy, vz), (wx, wy, wz)); bonds: (i, j)
    of bond type 1. Spheres alone: atom_style sphere (LAMMPS) or granular (LIGGGHTS); with bonds:
    bpm/sphere (LAMMPS: id mol type d rho x y z) or hybrid granular molecular (LIGGGHTS: id type
    x y z d rho mol)."""
    lines = ["tbags two-engine test", "", "%d atoms" % len(atoms), "%d atom types" % ntypes]
    if bonds:
        lines += ["%d bonds" % len(bonds), "1 bond types"]
    lines += ["", "%.17g %.17g xlo xhi" % box[:2], "%.17g %.17g ylo yhi" % box[2:4],
              "%.17g %.17g zlo zhi" % box[4:], "", "Atoms", ""]
    for a in atoms:
        i, t, d, rho, x = a[0], a[1], a[2], a[3], a[4]
        if not bonds:
            lines.append("%d %d %.17g %.17g %.17g %.17g %.17g" % ((i, t, d, rho) + tuple(x)))
        elif engine == "lammps":
            lines.append("%d 1 %d %.17g %.17g %.17g %.17g %.17g" % ((i, t, d, rho) + tuple(x)))
        else:
            lines.append("%d %d %.17g %.17g %.17g %.17g %.17g 1" % ((i, t) + tuple(x) + (d, rho)))
    lines += ["", "Velocities", ""]
    lines += ["%d %.17g %.17g %.17g %.17g %.17g %.17g" % ((a[0],) + tuple(a[5]) + tuple(a[6])) for a in atoms]
    if bonds:
        lines += ["", "Bonds", ""]
        lines += ["%d 1 %d %d" % (k + 1, i, j) for k, (i, j) in enumerate(bonds)]
    path.write_text("\n".join(lines) + "\n")


def liggghts_head(atom_style, neighbor, E, nu, rest, mu, mur):
    """A LIGGGHTS deck's start: spheres from data.txt (newton off: LIGGGHTS's granular pairs with
    history need it), and the materials (per type: E, nu; per type pair, row by row: rest, mu,
    mur) of contact model tbags."""
    n = len(E)
    words = lambda xs: " ".join("%r" % float(x) for x in xs)    # noqa: E731
    return f"""
atom_style {atom_style}
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
read_data data.txt
neighbor {neighbor}
hard_particles yes
fix m1 all property/global youngsModulus peratomtype {words(E)}
fix m2 all property/global poissonsRatio peratomtype {words(nu)}
fix m3 all property/global coefficientRestitution peratomtypepair {n} {words(rest)}
fix m4 all property/global coefficientFriction peratomtypepair {n} {words(mu)}
fix m5 all property/global coefficientRollingFriction peratomtypepair {n} {words(mur)}
"""


def thermo_block(engine, natoms, every=20, extra=()):
    """Commands printing COLS of atoms 1..natoms (and the extra thermo keywords) every `every`.
    An atom's value of a per-atom array is C_ID[i][j] in LAMMPS, c_ID[i][j] in LIGGGHTS (older)."""
    ref = "C_pa" if engine == "lammps" else "c_pa"
    out = ["compute pa all property/atom " + " ".join(COLS)]
    names = []
    for i in range(1, natoms + 1):
        for k, c in enumerate(COLS, 1):
            out.append("variable %s%d equal %s[%d][%d]" % (c, i, ref, i, k))
            names.append("v_%s%d" % (c, i))
    out += ["thermo_style custom step %s %s" % (" ".join(extra), " ".join(names)),
            "thermo_modify format float %.16g", "thermo %d" % every]
    return "\n".join(out)


def thermo(log_text):
    """The thermo table after the first 'Step' header: {column: array over the printed steps};
    a variable's column is named without 'v_' (LIGGGHTS's header has none, LAMMPS's has)."""
    lines = log_text.splitlines()
    k = next(i for i, l in enumerate(lines) if re.match(r"\s*Step\s", l))
    cols = [c[2:] if c.startswith("v_") else c for c in lines[k].split()]
    rows = []
    for line in lines[k + 1:]:
        parts = line.split()
        if len(parts) != len(cols) or not re.match(r"^-?\d", parts[0]):
            break
        rows.append([float(v) for v in parts])
    data = np.array(rows)
    return {c: data[:, j] for j, c in enumerate(cols)}


def run(deck, workdir, engine, ranks=1):
    """Run deck (text) in workdir with the engine; returns its thermo table."""
    lmprun.run(deck, workdir, np_ranks=ranks, engine=engine).check(engine)
    return thermo((workdir / "log.lammps").read_text())


def columns(kind, natoms):
    """Thermo columns of one kind of value (COLS prefix: f, tq, omega, x ...) for all atoms."""
    return ["%s%d" % (c, i) for i in range(1, natoms + 1) for c in COLS if c.startswith(kind)]


def rel(a, b, names):
    """Largest difference over the named columns, relative to the largest magnitude of each."""
    return max(float(np.max(np.abs(a[n] - b[n])) / max(np.max(np.abs(b[n])), 1e-300)) for n in names)


def top_plate(fill):
    """A top plate 20 um into the highest particle, so that both plates press."""
    d = DataFile(fill)
    return float(np.max(d.x[:, 2] + 0.5 * d.diameter)) - 2e-5


# the plates' steel with sandpaper, as inputs/between_plates.lmp
PLATE = ("material 200e9 0.1 coeff 1 friction 1e10 rolling ${fabric_mur} restitution 0.2 "
         "coeff 2 friction 1e10 rolling 0.05 restitution 0.2")


def bag_model_lammps(top):
    """A filled bag (fill.data) with the model of inputs/between_plates.lmp, sand.lmp, fabric.lmp
    and yarn.lmp, the fixed bottom plate and gravity; top: the top plate's arguments after 'zplane'."""
    return f"""
units si
atom_style bpm/sphere
boundary f f f
comm_modify vel yes cutoff 0.010
newton on off
read_data fill.data
variable s equal 0.005
include ${{tbags}}/inputs/sand.lmp
include ${{tbags}}/inputs/fabric.lmp
pair_style gran/hertz/rolling epsd
pair_coeff 1 1 material ${{fabric_E}} ${{fabric_nu}} friction ${{fabric_mu}} rolling ${{fabric_mur}} restitution 0.2
pair_coeff 2 2 material ${{sand_E}} ${{sand_nu}} friction ${{sand_mu}} rolling ${{sand_mur}} restitution 0.2
pair_coeff 1 2 friction ${{fabric_mu}} rolling ${{fabric_mur}} restitution 0.2
include ${{tbags}}/inputs/yarn.lmp
timestep 1.5e-6
fix bottom all wall/gran/servo zplane -0.0025 +1 {PLATE}
fix top all wall/gran/servo zplane {top}
fix integrate all nve/sphere
fix gravity all gravity 9.81 vector 0 0 -1
"""


def bag_deck_lammps(ztop, steps, fields):
    """The bag pressed between the bottom plate and a fixed top plate at ztop for `steps`; writes
    end.dump (id and the fields, sorted, every digit) at the end."""
    return bag_model_lammps("%r -1 %s" % (ztop, PLATE)) + f"""
run {steps}
write_dump all custom end.dump {fields} modify sort id format float %.17g
"""


def bag_deck_liggghts(ztop, steps, fields):
    """The same in LIGGGHTS (inputs/liggghts/model.lig, fill.liggghts.data): end.dump holds the
    first and the last step."""
    return f"""
variable fill string fill.liggghts.data
include ${{tbags}}/inputs/liggghts/model.lig
fix top all wall/gran model tbags primitive type 3 zplane {ztop!r}
dump end all custom {steps} end.dump {fields}
dump_modify end sort id format "%d{' %.17g' * 9}"
run {steps}
"""


def convert(fill, out):
    """tbagspost/liggghts_fill.py: a LAMMPS fill as a LIGGGHTS data file."""
    import os
    import subprocess
    env = dict(os.environ, PYTHONPATH=str(lmprun.ROOT / "postprocess"))
    subprocess.run([sys.executable, "-m", "tbagspost.liggghts_fill", str(fill), str(out)], check=True,
                   capture_output=True, env=env)
