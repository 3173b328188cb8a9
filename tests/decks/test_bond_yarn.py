"""bond_style bpm/yarn against exact answers: the table's force-strain curve when pulled, no
force when pushed, breaking at the break strain, bending and twisting moments E I theta / r0 and
G J theta / r0, a cantilever under a tip load against beam theory; MPI ranks, newton_bond and
restart agreement in a run where bonds break; bad input."""
import math

import numpy as np
import pytest

import lmprun

TABLE = lmprun.ROOT / "inputs" / "yarn_pp_tape.table"


def table():
    rows = [l.split() for l in TABLE.read_text().splitlines()
            if l.strip() and l.split()[0].isdigit() and len(l.split()) == 3]
    return np.array([float(r[1]) for r in rows]), np.array([float(r[2]) for r in rows])


A = math.pi * 1e-3 ** 2 / 4
HEAD = lmprun.BPM_HEAD
PAIR_NONE = """special_bonds lj 0 1 1 coul 1 1 1
pair_style zero 0.006
pair_coeff * *
"""
BOND = "bond_style bpm/yarn\nbond_coeff 1 table %s YARN_PP_TAPE diameter 0.001 poisson 0.3 BONDEXTRA\n" % TABLE

# two 5 mm particles 5 mm apart, bonded (BONDEXTRA: more bond_coeff keywords), in groups a and b
TWO_BONDED = HEAD + """
create_atoms 1 single 0 0 0
create_atoms 1 single 0.005 0 0
set type 1 diameter 0.005
set type 1 density 450
""" + PAIR_NONE + BOND + """
create_bonds single/bond 1 1 2
group a id 1
group b id 2
"""

PULL = TWO_BONDED + """fix m1 a move linear 0 0 0
fix m2 b move linear ${v} 0 0
compute nb all nbond/atom
compute nbt all reduce sum c_nb
variable eps equal (x[2]-x[1]-0.005)/0.005
variable F equal -fx[2]
fix out all print 100 "$(v_eps:%.12g) $(v_F:%.12g) $(c_nbt)" file pull.txt screen no
timestep 1e-6
run ${n}
"""


def pull(tmp_path, v, n, extra=""):
    lmprun.run(PULL.replace("BONDEXTRA", extra), tmp_path, variables={"v": v, "n": n}).check()
    return np.loadtxt(tmp_path / "pull.txt")


def test_pulled_bond_follows_the_table(tmp_path):
    d = pull(tmp_path, 0.05, 15000)
    eps, F, nb = d[:, 0], d[:, 1], d[:, 2]
    e_t, s_t = table()
    want = A * np.interp(eps, e_t, s_t)
    t = eps > 1e-4
    err = np.abs(F[t] - want[t]).max() / want[t].max()
    print("force-strain: max |F - A sigma(eps)| / F_max = %.2e over eps up to %.3f" % (err, eps.max()))
    assert err < 1e-3 and eps.max() > 0.14 and (nb == 2).all()


def test_pushed_bond_carries_no_force(tmp_path):
    d = pull(tmp_path, -0.05, 5000)
    assert d[:, 0].min() < -0.049 and np.abs(d[:, 1]).max() == 0.0


@pytest.mark.parametrize("brk", [None, 0.1])
def test_bond_breaks_at_the_break_strain(tmp_path, brk):
    d = pull(tmp_path, 0.05, 20000, "" if brk is None else "break %g" % brk)
    eps, nb = d[:, 0], d[:, 2]
    first = np.argmax(nb == 0)
    target = 0.16 if brk is None else brk
    print("broken between strains %.4f and %.4f (break strain %g)" % (eps[first - 1], eps[first], target))
    assert nb[0] == 2 and nb[-1] == 0
    assert eps[first - 1] <= target + 1e-9 and eps[first] >= target - 1e-9 and eps[first] - eps[first - 1] < 0.011


def test_axial_damping_adds_g_n_times_the_stretch_rate(tmp_path):
    """damping g_n 0 0: pulled at v, F = A sigma(eps) + g_n v while stretched (the closed form of a
    viscous dashpot beside the yarn); pushed, still no force (the dashpot acts in tension only)."""
    g = 0.5
    d = pull(tmp_path / "pull", 0.05, 15000, "damping %g 0 0" % g)
    eps, F = d[:, 0], d[:, 1]
    e_t, s_t = table()
    t = eps > 1e-4
    extra = F[t] - A * np.interp(eps[t], e_t, s_t)
    print("damping force: %.6f to %.6f N (g_n v = %.6f N)" % (extra.min(), extra.max(), g * 0.05))
    assert np.allclose(extra, g * 0.05, rtol=1e-6, atol=1e-9)
    pushed = pull(tmp_path / "push", -0.05, 5000, "damping %g 0 0" % g)
    assert np.abs(pushed[:, 1]).max() == 0.0


UNLOAD = TWO_BONDED.replace("BONDEXTRA", "unload plastic") + """variable eps equal (x[2]-x[1]-0.005)/0.005
variable F equal -fx[2]
fix out all print 100 "$(v_eps:%.12g) $(v_F:%.12g)" file unload1.txt screen no
timestep 1e-6
fix m1 a move linear 0 0 0
# pull to 8 %, unload to 5 % (the checkpoint), then (unload2.txt) to 1 % and reload to 10 %
fix m2 b move linear 0.05 0 0
run 8000
unfix m2
fix m2 b move linear -0.05 0 0
run 3000
write_restart unload.restart
"""

RELOAD = """
units si
read_restart unload.restart
comm_modify vel yes
pair_style zero 0.006
pair_coeff * *
group a id 1
group b id 2
variable eps equal (x[2]-x[1]-0.005)/0.005
variable F equal -fx[2]
fix out all print 100 "$(v_eps:%.12g) $(v_F:%.12g)" file unload2.txt screen no
timestep 1e-6
fix m1 a move linear 0 0 0
fix m2 b move linear -0.05 0 0
run 4000
unfix m2
fix m2 b move linear 0.05 0 0
run 9000
"""


@pytest.mark.parametrize("ranks", [1, 2])
def test_plastic_unloading_across_restart(tmp_path, ranks):
    """unload plastic: pulled to 8 %, back to 1 % through a restart (read on 1 or 2 ranks), then
    to 10 %: the force follows the table while loading, the line of the initial modulus E_0 from
    (8 %, sigma(8 %)) down to zero while unloading and reloading (slack below the permanent
    strain, 1.2 %), and the table again past 8 %: the largest strain survives the restart file."""
    lmprun.run(UNLOAD, tmp_path).check()
    lmprun.run(RELOAD, tmp_path, np_ranks=ranks).check()
    d = np.vstack([np.loadtxt(tmp_path / "unload1.txt"), np.loadtxt(tmp_path / "unload2.txt")])
    eps, F = d[:, 0], d[:, 1]
    e_t, s_t = table()
    E0 = s_t[1] / e_t[1]
    emax = np.maximum.accumulate(eps)
    want = A * np.maximum(0.0, np.interp(emax, e_t, s_t) - E0 * (emax - eps))
    err = np.abs(F - want).max() / A / s_t.max()
    unloaded = eps < emax - 1e-3
    slack = want == 0
    print("%d ranks: max |F - closed form| / F_max %.2e over %d rows (%d unloading, %d slack); "
          "strain %.3f..%.3f" % (ranks, err, len(F), unloaded.sum(), slack.sum(), eps.min(), eps.max()))
    assert eps.max() > 0.099 and eps[unloaded].min() < 0.011
    assert unloaded.sum() > 50 and slack.sum() >= 4 and (F[slack] == 0).all()
    assert err < 1e-6


ROTATE = HEAD + """
create_atoms 1 single 0 0 0
create_atoms 1 single 0.005 0 0
set type 1 diameter 0.005
set type 1 density 450
""" + PAIR_NONE + BOND + """
create_bonds single/bond 1 1 2
set atom 1 omega $(-v_wx/2) $(-v_wy/2) 0
set atom 2 omega $(v_wx/2) $(v_wy/2) 0
timestep 1e-6
run 1000
write_dump all custom torque.dump id tqx tqy tqz modify sort id format float %.17g
"""


def test_twisting_and_bending_moments(tmp_path):
    """The two particles spin in opposite senses at prescribed rates (nothing integrated, no
    shear at the bond centre): after 1000 steps the moments on particle 1 are G J theta / r0
    (twist, about x) and E I theta / r0 (bending, about y)."""
    wx, wy, r0, d, nu = 2.0, 3.0, 0.005, 1e-3, 0.3
    lmprun.run(ROTATE.replace("BONDEXTRA", ""), tmp_path, variables={"wx": wx, "wy": wy}).check()
    t = [lmprun.column(tmp_path / "torque.dump", c)[0] for c in ("tqx", "tqy", "tqz")]
    e_t, s_t = table()
    E = s_t[1] / e_t[1]
    G = E / (2 * (1 + nu))
    I, J = math.pi * d ** 4 / 64, math.pi * d ** 4 / 32
    theta_x, theta_y = wx * 1000 * 1e-6, wy * 1000 * 1e-6
    print("twist %.6e (G J theta/r0 = %.6e), bend %.6e (E I theta/r0 = %.6e)"
          % (t[0], G * J * theta_x / r0, t[1], E * I * theta_y / r0))
    assert abs(t[0] - G * J * theta_x / r0) < 1e-9 * G * J * theta_x / r0
    assert abs(t[1] - E * I * theta_y / r0) < 1e-9 * E * I * theta_y / r0


CANTILEVER = HEAD + """
lattice sc 0.005
region line block -0.1 10.1 -0.1 0.1 -0.1 0.1
create_atoms 1 region line
set type 1 diameter 0.005
set type 1 density 450
""" + PAIR_NONE + """
special_bonds lj 0 1 1 coul 0 1 1
bond_style zero
bond_coeff *
create_bonds many all all 1 0.0049 0.0051
special_bonds lj 0 1 1 coul 1 1 1
""" + BOND + """
group clamp id 1
group free subtract all clamp
variable tipid equal count(all)
group tip id ${tipid}
fix load tip addforce 0 0 ${P}
fix integrate free nve/bpm/sphere
fix calm free viscous 2e-3
timestep 2e-6
run 300000
print "TIP $(z[v_tipid]:%.17g) $(count(all))"
"""


def test_cantilever_tip_deflection(tmp_path):
    """Euler-Bernoulli: delta = P L^3 / (3 E I); 10 bonds of 5 mm, 1 mm yarn, P = 1 mN."""
    P, r0, d, nu = -1e-3, 0.005, 1e-3, 0.3
    res = lmprun.run(CANTILEVER.replace("BONDEXTRA", ""), tmp_path, variables={"P": P}).check()
    z, n = [float(x) for x in [l for l in res.output.splitlines() if l.startswith("TIP")][0].split()[1:]]
    N = int(n) - 1
    e_t, s_t = table()
    E = s_t[1] / e_t[1]
    G = E / (2 * (1 + nu))
    I, Ar = math.pi * d ** 4 / 64, math.pi * d ** 2 / 4
    kappa = 6 * (1 + nu) / (7 + 6 * nu)
    L = N * r0
    beam = P * L ** 3 / (3 * E * I)
    discrete = P * r0 ** 3 * (N ** 3 / 3 - N / 12) / (E * I) + N * P * r0 / (kappa * G * Ar)
    print("tip deflection %.6e m: Euler-Bernoulli %.6e (%.2f %%), discrete chain %.6e (%.3f %%)"
          % (z, beam, 100 * (z / beam - 1), discrete, 100 * (z / discrete - 1)))
    assert abs(z / beam - 1) < 0.02
    assert abs(z / discrete - 1) < 0.002


def test_orientations_not_used(tmp_path):
    """The law is incremental: integrating the rotations with nve/sphere (no quaternions) moves
    the cantilever as nve/bpm/sphere does, to round-off (their inertia factors round apart)."""
    assert "fix integrate free nve/bpm/sphere" in CANTILEVER and "run 300000" in CANTILEVER
    tips = []
    for fix in ("nve/bpm/sphere", "nve/sphere"):
        deck = (CANTILEVER.replace("BONDEXTRA", "").replace("free nve/bpm/sphere", "free " + fix)
                .replace("run 300000", "run 20000"))
        res = lmprun.run(deck, tmp_path / fix.replace("/", "_"), variables={"P": -1e-3}).check()
        tips.append(float([l for l in res.output.splitlines() if l.startswith("TIP")][0].split()[1]))
    print("tip z after 20000 steps: nve/bpm/sphere %.17g, nve/sphere %.17g" % tuple(tips))
    assert tips[0] < -1e-5    # it moved
    assert abs(tips[1] - tips[0]) < 1e-8 * abs(tips[0])


SHEET_MAKE = """
units si
atom_style bpm/sphere
boundary f f f
region box block -0.01 0.08 -0.01 0.04 -0.01 0.01
create_box 1 box bond/types 1 extra/bond/per/atom 4 extra/special/per/atom 20
lattice sc 0.005
region sheet block 0 12 0 5 -0.1 0.1
create_atoms 1 region sheet
set type 1 diameter 0.005
set type 1 density 450
special_bonds lj 0 1 1 coul 0 1 1
pair_style zero 0.006
pair_coeff * *
bond_style zero
bond_coeff *
create_bonds many all all 1 0.0049 0.0051
write_data sheet.data nocoeff
"""

# both ends pulled apart fast enough to tear the sheet; the middle integrated
PULL_ENDS = """region left block -0.0005 0.0005 INF INF INF INF units box
region right block 0.0595 0.0605 INF INF INF INF units box
group left region left
group right region right
group middle subtract all left right
fix pullL left move linear -3 0 0 units box
fix pullR right move linear 3 0 0 units box
fix integrate middle nve/bpm/sphere
compute nb all nbond/atom
compute nbt all reduce sum c_nb
"""

# the yarn bond overlays the contact law (special weights 1: bonded neighbours still touch in
# compression); both ends pulled apart fast enough to tear the sheet
SHEET = """
units si
atom_style bpm/sphere
atom_modify map array
boundary f f f
comm_modify vel yes cutoff 0.012
newton on ${newton_bond}
read_data ${data}
special_bonds lj 1 1 1 coul 1 1 1
pair_style gran/hertz/rolling epsd
pair_coeff 1 1 material 0.75e9 0.1 friction 0.26 rolling 0.05 restitution 0.2
bond_style bpm/yarn overlay/pair yes
bond_coeff 1 table %s YARN_PP_TAPE diameter 0.001 poisson 0.3 damping 1e-3 1e-3 1e-8
PULL_ENDS
thermo_style custom step c_nbt
thermo 500
timestep 1e-6
${neigh}
${midrun}
run ${n1}
${checkpoint}
run ${n2}
print "BONDS $(c_nbt)"
write_dump all custom sheet.dump id x y z vx vy vz modify sort id format float %%.17g
""".replace("PULL_ENDS\n", PULL_ENDS) % TABLE

SHEET_RESTART = """
units si
read_restart sheet.restart
comm_modify vel yes cutoff 0.012
PULL_ENDS
timestep 1e-6
run ${n2}
print "BONDS $(c_nbt)"
write_dump all custom sheet_restart.dump id x y z vx vy vz modify sort id format float %.17g
""".replace("PULL_ENDS\n", PULL_ENDS)


def sheet(wd, data, ranks=1, newton_bond="off", checkpoint=False, neigh="", midrun="", deck=SHEET):
    res = lmprun.run(deck, wd, np_ranks=ranks, variables={
        "data": data, "newton_bond": newton_bond, "n1": 1000, "n2": 1500, "neigh": neigh,
        "midrun": midrun, "checkpoint": "write_restart sheet.restart" if checkpoint else ""}).check()
    bonds = float([l for l in res.output.splitlines() if l.startswith("BONDS")][-1].split()[1])
    return res, bonds


@pytest.fixture(scope="module")
def sheet_data(tmp_path_factory):
    wd = tmp_path_factory.mktemp("sheetdata")
    lmprun.run(SHEET_MAKE, wd).check()
    return wd / "sheet.data"


@pytest.fixture(scope="module")
def sheet_ref(tmp_path_factory, sheet_data):
    wd = tmp_path_factory.mktemp("sheet1")
    res, bonds = sheet(wd, sheet_data, checkpoint=True)
    return wd, bonds


def test_sheet_tears(sheet_ref):
    wd, bonds = sheet_ref
    lattice_bonds = 2 * (12 * 6 + 13 * 5)    # counted from both ends
    print("sheet: %d of %d bond ends left" % (bonds, lattice_bonds))
    assert 0 < bonds < lattice_bonds


@pytest.mark.parametrize("ranks,newton_bond", [(2, "off"), (4, "off"), (1, "on"), (2, "on")])
def test_sheet_same_on_ranks_and_newton(tmp_path, sheet_data, sheet_ref, ranks, newton_bond):
    wd, bonds = sheet_ref
    res, b = sheet(tmp_path, sheet_data, ranks, newton_bond)
    cols, a = lmprun.read_dump(tmp_path / "sheet.dump")
    _, r = lmprun.read_dump(wd / "sheet.dump")
    x = [cols.index(c) for c in ("x", "y", "z")]
    dx = np.abs(a[:, x] - r[:, x]).max()
    print("ranks=%d newton_bond=%s: bonds %d vs %d, max |dx| = %.3e m" % (ranks, newton_bond, b, bonds, dx))
    assert b == bonds and dx < 1e-12


def test_sheet_same_with_the_baseline_kernel(tmp_path, sheet_data, sheet_ref):
    """The bond law's batch built for the baseline and (where the CPU has it) for AVX2: the same
    bits, so the same sheet, torn the same way."""
    wd, bonds = sheet_ref
    deck = SHEET.replace("bond_style bpm/yarn overlay/pair yes", "bond_style bpm/yarn overlay/pair yes kernel baseline")
    res, _ = sheet(tmp_path, sheet_data, deck=deck)
    assert "batch kernel baseline" in res.output
    assert (tmp_path / "sheet.dump").read_bytes() == (wd / "sheet.dump").read_bytes()


def test_sheet_write_restart_on_ranks(tmp_path, sheet_data):
    # a write_restart between runs migrates atoms between ranks (as LAMMPS's neighbor history did
    # for the pair, see test_pair_mpi) while the bond history fix still holds the run's bond
    # list: the run after it must be the run without it
    out = {}
    for chk in (False, True):
        wd = tmp_path / ("chk" if chk else "plain")
        res, b = sheet(wd, sheet_data, 2, "off", checkpoint=chk)
        out[chk] = (lmprun.read_dump(wd / "sheet.dump"), b)
    (cols, a), b0 = out[False]
    (_, r), b1 = out[True]
    x = [cols.index(c) for c in ("x", "y", "z")]
    dx = np.abs(a[:, x] - r[:, x]).max()
    print("2 ranks, write_restart between runs: bonds %d vs %d, max |dx| = %.3e m" % (b1, b0, dx))
    assert b0 == b1 and dx < 1e-12


@pytest.mark.parametrize("ranks,newton_bond", [(1, "off"), (2, "on"), (4, "off")])
def test_sheet_checkpoints_during_the_run_change_nothing(tmp_path, sheet_data, ranks, newton_bond):
    """A checkpoint every 100 steps during both runs (the restart command): the same torn sheet,
    bit for bit, as without. LAMMPS's bond history store lost the history (shear springs,
    moments, largest strain) of the steps between each checkpoint and the next reneighboring;
    ours keeps it (fix_bond_history_tbags.h). Both runs reneighbor every 10 steps: LAMMPS also
    reneighbors where it writes a checkpoint, which alone reorders the sums (round-off)."""
    neigh = "neigh_modify every 10 delay 0 check no"
    plain, chk = tmp_path / "plain", tmp_path / "restart"
    _, b0 = sheet(plain, sheet_data, ranks, newton_bond, neigh=neigh)
    _, b1 = sheet(chk, sheet_data, ranks, newton_bond, neigh=neigh,
                  midrun="restart 100 sheet.a.restart sheet.b.restart")
    assert (chk / "sheet.b.restart").exists()
    cols, a = lmprun.read_dump(plain / "sheet.dump")
    _, r = lmprun.read_dump(chk / "sheet.dump")
    x = [cols.index(c) for c in ("x", "y", "z")]
    print("ranks=%d newton_bond=%s, checkpoints every 100 steps: bonds %d vs %d, max |dx| = %.3e m"
          % (ranks, newton_bond, b1, b0, np.abs(a[:, x] - r[:, x]).max()))
    assert b0 == b1 and (chk / "sheet.dump").read_bytes() == (plain / "sheet.dump").read_bytes()


def test_sheet_restart_continues(sheet_ref):
    wd, bonds = sheet_ref
    res = lmprun.run(SHEET_RESTART, wd, variables={"n2": 1500}).check()
    b = float([l for l in res.output.splitlines() if l.startswith("BONDS")][-1].split()[1])
    cols, a = lmprun.read_dump(wd / "sheet_restart.dump")
    _, r = lmprun.read_dump(wd / "sheet.dump")
    x = [cols.index(c) for c in ("x", "y", "z")]
    dx = np.abs(a[:, x] - r[:, x]).max()
    print("restart: bonds %d vs %d, max |dx| = %.3e m" % (b, bonds, dx))
    assert b == bonds and dx < 1e-12
