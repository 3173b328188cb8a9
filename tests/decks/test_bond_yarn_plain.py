"""bond_style yarn (axial yarn law for any atom style): energy conservation of a spinning
dumbbell that stays in tension, bond_write against the table, use inside bond_style hybrid,
breaking, write_data and restart round trips, bad input."""
import numpy as np
import pytest

import lmprun

TABLE = lmprun.ROOT / "inputs" / "yarn_pp_tape.table"
COEFF = "table %s YARN_PP_TAPE diameter 0.001 r0 0.005" % TABLE

# two particles of 30 mg in a 10 cm box
BOX = """
units si
atom_style bond
atom_modify map array
boundary f f f
region box block -0.05 0.05 -0.05 0.05 -0.05 0.05
"""

DUMBBELL = BOX + """create_box 1 box bond/types 2 extra/bond/per/atom 1
create_atoms 1 single -0.0026 0 0
create_atoms 1 single 0.0026 0 0
mass 1 3e-5
BONDSTYLE
create_bonds single/bond 1 1 2
# spinning about z (the bond stays in tension) with a radial push: the strain oscillates
velocity all set NULL NULL 0
set atom 1 vx -1.5 vy -80
set atom 2 vx 1.5 vy 80
variable eps equal (sqrt((x[2]-x[1])^2+(y[2]-y[1])^2)-0.005)/0.005
thermo_style custom step ke pe etotal v_eps
thermo_modify format float %.15g
thermo 1000
fix 1 all nve
timestep 5e-8
run 100000
"""


def thermo(output):
    rows = []
    for line in output.splitlines():
        w = line.split()
        if len(w) == 5 and w[0].isdigit():
            try:
                rows.append([float(x) for x in w])
            except ValueError:
                pass
    return np.array(rows)


@pytest.mark.parametrize("style", ["bond_style yarn\nbond_coeff * " + COEFF,
                                   "bond_style hybrid yarn harmonic\nbond_coeff 1 yarn " + COEFF +
                                   "\nbond_coeff 2 harmonic 100.0 0.005"])
def test_energy_conserved(tmp_path, style):
    res = lmprun.run(DUMBBELL.replace("BONDSTYLE", style), tmp_path).check()
    d = thermo(res.output)
    pe, et, eps = d[:, 2], d[:, 3], d[:, 4]
    drift = np.abs(et - et[0]).max() / et[0]
    print("strain %.4f..%.4f, bond energy up to %.4f J of %.4f J; max |E - E0|/E0 = %.2e over 1e5 steps"
          % (eps.min(), eps.max(), pe.max(), et[0], drift))
    assert eps.min() > 0.0 and eps.max() < 0.16 and pe.max() > 0.04 * et[0]
    assert drift < 1e-4


WRITE = """
units si
atom_style bond
region box block -0.05 0.05 -0.05 0.05 -0.05 0.05
create_box 1 box bond/types 1 extra/bond/per/atom 1
mass 1 3e-5
bond_style yarn
bond_coeff 1 %s
bond_write 1 101 0.004 0.0058 yarn.txt YARN
""" % COEFF


def test_bond_write_follows_table(tmp_path):
    lmprun.run(WRITE, tmp_path).check()
    rows = np.array([[float(x) for x in l.split()] for l in (tmp_path / "yarn.txt").read_text().splitlines()
                     if l.strip() and l.split()[0].isdigit() and len(l.split()) == 4])
    r, e, f = rows[:, 1], rows[:, 2], rows[:, 3]
    tab = np.array([[float(x) for x in l.split()[1:]] for l in TABLE.read_text().splitlines()
                    if l.strip() and l.split()[0].isdigit()])
    A = np.pi * 1e-6 / 4
    eps = (r - 0.005) / 0.005
    want = np.where(eps > 0, A * np.interp(eps, tab[:, 0], tab[:, 1]), 0.0)
    # bond_write's force column is -dE/dr: tension gives a negative (attractive) force
    err = np.abs(-f - want).max() / want.max()
    print("bond_write: max |F - A sigma| / F_max = %.2e; energy at 16 %% %.6f J" % (err, e[-1]))
    assert err < 1e-10 and np.all(e[eps <= 0] == 0.0)


BREAK = BOX + """create_box 1 box bond/types 1 extra/bond/per/atom 1
create_atoms 1 single 0 0 0
create_atoms 1 single 0.005 0 0
mass 1 3e-5
bond_style yarn
bond_coeff 1 %s break 0.1
create_bonds single/bond 1 1 2
group b id 2
fix m b move linear 0.05 0 0
compute bl all bond/local dist b1 b2
compute n all reduce sum c_bl[3] inputs local
variable eps equal (x[2]-x[1]-0.005)/0.005
thermo_style custom step v_eps c_n
thermo 100
timestep 1e-6
run 12000
write_data broken.data
""" % COEFF


def test_breaks_and_writes_data(tmp_path):
    res = lmprun.run(BREAK, tmp_path).check()
    rows = [l.split() for l in res.output.splitlines() if len(l.split()) == 3 and l.split()[0].isdigit()]
    eps = np.array([float(r[1]) for r in rows])
    alive = np.array([float(r[2]) > 0 for r in rows])    # axial force (b2) of active bonds
    eps, alive = eps[eps > 0], alive[eps > 0]
    first = np.argmax(~alive)
    print("bond turned off between strains %.4f and %.4f" % (eps[first - 1], eps[first]))
    assert alive[0] and not alive[-1] and eps[first - 1] <= 0.1 + 1e-9 and eps[first] >= 0.1 - 1e-9
    coeffs = (tmp_path / "broken.data").read_text()
    assert "Bond Coeffs # yarn" in coeffs and "r0 0.005" in coeffs and "break 0.10000000000000001" in coeffs


@pytest.mark.parametrize("coeff,message", [
    ("table %s YARN_PP_TAPE diameter 0.001" % TABLE, "needs 'r0 R0'"),
    ("table %s YARN_PP_TAPE diameter 0.001 r0 0.005 poisson 0.3" % TABLE, "unknown bond_coeff keyword 'poisson'"),
    ("table %s YARN_PP_TAPE diameter 0.001 r0 0.005 unload plastic" % TABLE, "unknown bond_coeff keyword 'unload'"),
])
def test_bad_input(tmp_path, coeff, message):
    res = lmprun.run(WRITE.replace(COEFF, coeff), tmp_path)
    assert res.returncode != 0 and "Bond style yarn" in res.error_line() and message in res.error_line(), res.error_line()


def test_restart_round_trip(tmp_path):
    """write_restart half way, read_restart and run the second half: the same final state as the
    run without a break (the bond's table, diameter and r0 come back from the restart file)."""
    deck = DUMBBELL.replace("BONDSTYLE", "bond_style yarn\nbond_coeff * " + COEFF)
    whole = thermo(lmprun.run(deck, tmp_path / "whole").check().output)
    first = deck.replace("run 100000", "run 50000\nwrite_restart half.restart")
    lmprun.run(first, tmp_path / "half").check()
    second = """read_restart half.restart
variable eps equal (sqrt((x[2]-x[1])^2+(y[2]-y[1])^2)-0.005)/0.005
thermo_style custom step ke pe etotal v_eps
thermo_modify format float %.15g
thermo 1000
fix 1 all nve
timestep 5e-8
run 50000
"""
    resumed = thermo(lmprun.run(second, tmp_path / "half").check().output)
    err = np.abs(resumed[-1, 1:] - whole[-1, 1:]) / np.abs(whole[-1, 1:])
    print("after the restart at 50000 steps, the final ke, pe, etotal, strain differ by %s (relative)" % err)
    assert resumed[-1, 0] == whole[-1, 0] == 100000 and err.max() < 1e-9
