"""bond_style bpm/yarn in LIGGGHTS (src-liggghts/bond_bpm_yarn.cpp on law/yarn_law.h) against
exact answers, as the LAMMPS tests do: the table's force-strain curve when pulled, no force when
pushed, breaking at the break strain, a cantilever under a tip load against the discrete beam;
then a bent, spinning chain of four bonded spheres against LAMMPS's bpm/yarn (same law: to
round-off), on 1 and 2 LIGGGHTS ranks, and continued from a restart file."""
import math

import numpy as np
import pytest

import lmprun
from twoengines import columns, data_file, liggghts_head, rel, run, thermo_block

TABLE = lmprun.ROOT / "inputs" / "yarn_pp_tape.table"
A, D_YARN, NU_YARN = math.pi * 1e-3 ** 2 / 4, 1e-3, 0.3


def table():
    rows = [l.split() for l in TABLE.read_text().splitlines()
            if l.strip() and l.split()[0].isdigit() and len(l.split()) == 3]
    return np.array([float(r[1]) for r in rows]), np.array([float(r[2]) for r in rows])


def yarn_head(extra_coeff=""):
    """Spheres with bonds (type 1), our contact model but no contacts (all spheres are one
    molecule, excluded; LIGGGHTS keeps bonded pairs in its pair list whatever special_bonds
    says), the yarn bond. (LAMMPS's decks: newton on off; LIGGGHTS's granular pairs need off.)"""
    return liggghts_head("hybrid granular molecular", "0.002 bin\nneigh_modify delay 0 exclude molecule all",
                         (1e9,), (0.3,), (0.5,), (0.3,), (0.05,)) + f"""
pair_style gran model tbags
pair_coeff * *
bond_style bpm/yarn
bond_coeff 1 table {TABLE} YARN_PP_TAPE diameter {D_YARN} poisson {NU_YARN} {extra_coeff}
"""


def two_bonded(tmp_path, v):
    """Two 5 mm spheres 5 mm apart, bonded; sphere 2 moves away at v (m/s), sphere 1 held."""
    atoms = [(1, 1, 0.005, 450.0, (0.0, 0.0, 0.0), (0, 0, 0), (0, 0, 0)),
             (2, 1, 0.005, 450.0, (0.005, 0.0, 0.0), (v, 0, 0), (0, 0, 0))]
    data_file(tmp_path / "data.txt", atoms, 1, bonds=[(1, 2)], engine="liggghts",
              box=(-0.01, 0.03, -0.01, 0.01, -0.01, 0.01))


def pull(tmp_path, v, n, extra=""):
    """strain, axial force on sphere 1 (tension positive) every 100 steps of a constant-speed pull."""
    two_bonded(tmp_path, v)
    deck = yarn_head(extra) + f"""
group a id 1
group b id 2
fix m1a a move linear 0 0 0
fix m2b b move linear {v} 0 0
variable eps equal (x[2]-x[1]-0.005)/0.005
variable F equal fx[1]
thermo_style custom step v_eps v_F
thermo_modify format float %.15g
thermo 100
timestep 1e-6
run {n}
"""
    t = run(deck, tmp_path, "liggghts")
    return t["eps"], t["F"]


def test_pulled_bond_follows_the_table(tmp_path):
    eps, F = pull(tmp_path, 0.05, 15000)
    e_t, s_t = table()
    want = A * np.interp(eps, e_t, s_t)
    t = eps > 1e-4
    err = np.abs(F[t] - want[t]).max() / want[t].max()
    print("LIGGGHTS force-strain: max |F - A sigma(eps)| / F_max = %.2e up to eps %.3f" % (err, eps.max()))
    assert err < 1e-3 and eps.max() > 0.14


def test_pushed_bond_carries_no_force(tmp_path):
    eps, F = pull(tmp_path, -0.05, 5000)
    assert eps.min() < -0.049 and np.abs(F).max() == 0.0


@pytest.mark.parametrize("brk", [None, 0.1])
def test_bond_breaks_at_the_break_strain(tmp_path, brk):
    eps, F = pull(tmp_path, 0.05, 20000, "" if brk is None else "break %g" % brk)
    target = 0.16 if brk is None else brk
    stretched = eps > 1e-4
    first = np.argmax(stretched & (F == 0.0))    # the first printed step without force
    print("LIGGGHTS: broken between strains %.4f and %.4f (break strain %g)" % (eps[first - 1], eps[first], target))
    assert first > 0 and (F[first:] == 0.0).all() and F[first - 1] > 0.0
    assert eps[first - 1] <= target + 1e-9 and eps[first] >= target - 1e-9


def test_cantilever_tip_deflection(tmp_path):
    """As the LAMMPS test: 10 bonds of 5 mm, 1 mm yarn, tip load 1 mN, against the discrete
    chain's deflection (bending + shear springs; Euler-Bernoulli within 2 %)."""
    P, r0, N = -1e-3, 0.005, 10
    atoms = [(k + 1, 1, 0.005, 450.0, (k * r0, 0.0, 0.0), (0, 0, 0), (0, 0, 0)) for k in range(N + 1)]
    data_file(tmp_path / "data.txt", atoms, 1, bonds=[(k, k + 1) for k in range(1, N + 1)],
              engine="liggghts", box=(-0.01, 0.06, -0.01, 0.01, -0.02, 0.01))
    deck = yarn_head() + f"""
group clamp id 1
group free subtract all clamp
group tip id {N + 1}
fix load tip addforce 0 0 {P}
fix integrate free nve/sphere
fix calm free viscous 2e-3
timestep 2e-6
variable tipz equal z[{N + 1}]
thermo_style custom step v_tipz
thermo_modify format float %.15g
thermo 10000
run 300000
"""
    z = run(deck, tmp_path, "liggghts")["tipz"][-1]
    e_t, s_t = table()
    E = s_t[1] / e_t[1]
    G = E / (2 * (1 + NU_YARN))
    I = math.pi * D_YARN ** 4 / 64
    kappa = 6 * (1 + NU_YARN) / (7 + 6 * NU_YARN)
    beam = P * (N * r0) ** 3 / (3 * E * I)
    discrete = P * r0 ** 3 * (N ** 3 / 3 - N / 12) / (E * I) + N * P * r0 / (kappa * G * A)
    print("LIGGGHTS tip deflection %.6e m: Euler-Bernoulli %.6e (%.2f %%), discrete %.6e (%.3f %%)"
          % (z, beam, 100 * (z / beam - 1), discrete, 100 * (z / discrete - 1)))
    assert abs(z / beam - 1) < 0.02 and abs(z / discrete - 1) < 0.002


# a zigzag of four 4 mm spheres, bonds of 5 mm, thrown apart and spun: tension, slack, bending,
# twisting and shear of the bonds, no contacts
CHAIN = [(1, 1, 0.004, 900.0, (0.0, 0.0, 0.0), (-0.05, 0.02, 0.0), (0.0, 30.0, -10.0)),
         (2, 1, 0.004, 900.0, (0.004, 0.003, 0.0), (0.01, -0.03, 0.02), (20.0, 0.0, 0.0)),
         (3, 1, 0.004, 900.0, (0.008, 0.0, 0.0), (0.0, 0.04, -0.03), (-10.0, 10.0, 40.0)),
         (4, 1, 0.004, 900.0, (0.012, 0.003, 0.001), (0.06, 0.0, 0.01), (0.0, -30.0, 0.0))]
CHAIN_BONDS = [(1, 2), (2, 3), (3, 4)]
CHAIN_BOX = (-0.01, 0.022, -0.01, 0.013, -0.01, 0.01)
CHAIN_STEPS = 3000


def chain_lammps():
    return f"""
units si
atom_style bpm/sphere
atom_modify map array
boundary f f f
newton on off
comm_modify vel yes cutoff 0.012
read_data data.txt
neighbor 0.002 bin
neigh_modify delay 0
special_bonds lj 0 1 1 coul 1 1 1
pair_style zero 0.006
pair_coeff * *
bond_style bpm/yarn
bond_coeff 1 table {TABLE} YARN_PP_TAPE diameter {D_YARN} poisson {NU_YARN} damping 0.01 0.01 1e-8
fix integrate all nve/sphere
timestep 1e-6
{thermo_block("lammps", 4, every=100)}
run {CHAIN_STEPS}
"""


def chain_liggghts(steps=CHAIN_STEPS, restart="", damping=True):
    """restart: 'write' (stop halfway with a restart file) or 'read' (go on from it)."""
    head = yarn_head("damping 0.01 0.01 1e-8" if damping else "")
    if restart == "read":
        head = head.replace("read_data data.txt", "read_restart half.restart")
        # the bond style and its coefficients come from the restart file
        head = "\n".join(l for l in head.splitlines() if not l.startswith("bond_"))
    tail = "write_restart half.restart\n" if restart == "write" else ""
    return head + f"""
fix integrate all nve/sphere
timestep 1e-6
{thermo_block("liggghts", 4, every=100)}
run {steps}
{tail}"""


@pytest.fixture(scope="module")
def chain_lammps_run(tmp_path_factory):
    wd = tmp_path_factory.mktemp("chain_lammps")
    data_file(wd / "data.txt", CHAIN, 1, bonds=CHAIN_BONDS, engine="lammps", box=CHAIN_BOX)
    return run(chain_lammps(), wd, "lammps")


def chain_liggghts_run(wd, ranks=1, steps=CHAIN_STEPS, restart="", damping=True):
    wd.mkdir(parents=True, exist_ok=True)
    data_file(wd / "data.txt", CHAIN, 1, bonds=CHAIN_BONDS, engine="liggghts", box=CHAIN_BOX)
    return run(chain_liggghts(steps, restart, damping), wd, "liggghts", ranks)


def test_chain_same_as_lammps(tmp_path, chain_lammps_run):
    lmp = chain_lammps_run
    lig = chain_liggghts_run(tmp_path)
    assert len(lig["Step"]) == len(lmp["Step"]) == CHAIN_STEPS // 100 + 1
    # the bonds work: forces and torques on every sphere at the end, spins changed
    assert all(abs(lmp["tqx%d" % i][-1]) + abs(lmp["tqy%d" % i][-1]) > 0 for i in range(1, 5))
    assert np.max(np.abs(lmp["omegaz3"] - lmp["omegaz3"][0])) > 1.0
    for kind in ("f", "tq", "omega", "x", "y", "z"):
        d = rel(lig, lmp, columns(kind, 4))
        print("chain %s: LIGGGHTS vs LAMMPS %.2e" % (kind, d))
        assert d < 1e-10, kind


def test_chain_two_ranks(tmp_path):
    """The box split in x: bonds across the ranks' boundary, their history on both ends."""
    one = chain_liggghts_run(tmp_path / "np1")
    two = chain_liggghts_run(tmp_path / "np2", ranks=2)
    d = max(rel(two, one, columns(k, 4)) for k in ("f", "tq", "x", "y", "z", "omega"))
    print("chain: LIGGGHTS 2 ranks vs 1 rank %.2e" % d)
    assert d < 1e-10


def test_chain_restart(tmp_path):
    """Half the run, write_restart, read_restart and the other half: the bonds' history (fix
    bond/history/yarn) and coefficients come back, so the end is the uninterrupted run's. The
    bonds without damping here: a restarted run's first forces use the full-step velocities,
    the uninterrupted run's the half-step ones (velocity Verlet), so dampers would differ."""
    whole = chain_liggghts_run(tmp_path / "whole", damping=False)
    chain_liggghts_run(tmp_path / "cont", steps=CHAIN_STEPS // 2, restart="write", damping=False)
    second = run(chain_liggghts(CHAIN_STEPS // 2, "read", False), tmp_path / "cont", "liggghts")
    d = max(abs(second[c][-1] - whole[c][-1]) / max(abs(whole[c]).max(), 1e-300)
            for c in columns("f", 4) + columns("x", 4) + columns("tq", 4))
    print("chain: restarted vs uninterrupted %.2e" % d)
    assert d < 1e-10


def test_example_runs(tmp_path):
    """examples/liggghts/in.bonded_chain: the grain comes to rest on the yarn."""
    deck = lmprun.ROOT / "examples" / "liggghts" / "in.bonded_chain"
    res = lmprun.run(deck, tmp_path, variables={"tbags": lmprun.ROOT}, engine="liggghts").check("liggghts")
    line = next(l for l in res.output.splitlines() if l.startswith("CHAIN EXAMPLE"))
    gap = float(line.split("rests ")[1].split()[0])
    print(line)
    assert 1.0 < gap < 3.5 + 1e-3
