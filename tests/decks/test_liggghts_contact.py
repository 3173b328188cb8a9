"""The contact law in LIGGGHTS (pair_style gran model tbags, fix wall/gran model tbags) against
the same law in LAMMPS (pair_style gran/hertz/rolling, fix wall/gran/servo): the same code
(src-plugin/law/), so forces, torques and trajectories agree to round-off.

Two spheres of two materials, and a sphere on a fixed plate, start overlapping with normal,
tangential and spin velocities read from one data file by both engines; over 400 steps the
tangential and rolling springs load and the two spheres part, while the sphere pressed on the
plate sticks and slides in turn, so the histories' integration, rotation, cap and reset are
compared. The runs are also checked
against LIGGGHTS's native hertz + tangential history + rolling epsd2 (the closest stock
model): it differs by more than 1e-3, which shows the comparison can fail.
"""
import numpy as np
import pytest

from twoengines import columns, data_file, liggghts_head, rel, run, thermo_block

# materials: type 1 bag-like, type 2 sand-like; the plate's (type 2 in the plate run) is steel
E = {1: 0.75e9, 2: 1.8e9}
NU = {1: 0.1, 2: 0.1}
E_PLATE, NU_PLATE = 200e9, 0.3
# per type pair (1-1, 1-2, 2-2): restitution, friction, rolling friction
REST = {(1, 1): 0.3, (1, 2): 0.25, (2, 2): 0.2}
MU = {(1, 1): 0.26, (1, 2): 0.2, (2, 2): 0.31}
MU_PLATE = 0.05    # sphere-plate friction (the 1-2 pair of the plate runs): low, so that it slides
MUR = {(1, 1): 0.05, (1, 2): 0.08, (2, 2): 0.05}
STEPS, DT = 400, 2e-7

# two spheres overlapping 2 um along a skew normal, approaching, sliding and spinning
R1, R2, RHO1, RHO2 = 1.25e-3, 1.0e-3, 1100.0, 2650.0
N = np.array([0.48, -0.6, 0.64]) / np.linalg.norm([0.48, -0.6, 0.64])
PAIR_ATOMS = [  # id type diameter density x y z, vx vy vz, wx wy wz
    (1, 1, 2 * R1, RHO1, (0.0, 0.0, 0.0), (0.004, 0.0, -0.002), (30.0, -20.0, 10.0)),
    (2, 2, 2 * R2, RHO2, tuple((R1 + R2 - 2e-6) * N), (-0.01, 0.03, 0.0), (-40.0, 0.0, 60.0)),
]
# one sphere on a plate at z = 0, pressed 1.5 um and by a strong gravity (so that it stays on
# the plate), sliding in x and y, spinning
G_PLATE = 2000.0
PLATE_ATOMS = [(1, 1, 2 * R2, RHO2, (0.001, 0.002, R2 - 1.5e-6), (0.03, -0.01, -0.001),
                (20.0, 50.0, -30.0))]
def mu_table(plate):
    return {**MU, (1, 2): MU_PLATE} if plate else MU


def pair_list(table):
    return (table[(1, 1)], table[(1, 2)], table[(1, 2)], table[(2, 2)])


def liggghts_deck(plate, model="model tbags"):
    """plate: a sphere of type 1 on a primitive zplane wall of type 2 (the plate's material)."""
    e2, nu2 = (E_PLATE, NU_PLATE) if plate else (E[2], NU[2])
    wall = ("fix plate all wall/gran %s primitive type 2 zplane 0.0\n"
            "fix g all gravity %g vector 0 0 -1" % (model, G_PLATE)) if plate else ""
    head = liggghts_head("granular", "0.0005 bin\nneigh_modify delay 0", (E[1], e2), (NU[1], nu2),
                         pair_list(REST), pair_list(mu_table(plate)), pair_list(MUR))
    return head + f"""
fix m6 all property/global coefficientRollingViscousDamping peratomtypepair 2 0 0 0 0
pair_style gran {model}
pair_coeff * *
{wall}
fix integrate all nve/sphere
timestep {DT}
{thermo_block("liggghts", len(PLATE_ATOMS if plate else PAIR_ATOMS))}
run {STEPS}
"""


def lammps_deck(plate):
    if plate:
        coeff = "coeff 1 friction %g rolling %g restitution %g" % (MU_PLATE, MUR[(1, 2)], REST[(1, 2)])
        wall = ("fix plate all wall/gran/servo zplane 0.0 +1 material %g %g %s\n"
                "fix g all gravity %g vector 0 0 -1" % (E_PLATE, NU_PLATE, coeff, G_PLATE))
    else:
        wall = ""
    return f"""
units si
atom_style sphere
atom_modify map array
boundary f f f
comm_modify vel yes
read_data data.txt
neighbor 0.0005 bin
neigh_modify delay 0
pair_style gran/hertz/rolling epsd
pair_coeff 1 1 material {E[1]} {NU[1]} friction {MU[(1, 1)]} rolling {MUR[(1, 1)]} restitution {REST[(1, 1)]}
pair_coeff 2 2 material {E[2]} {NU[2]} friction {MU[(2, 2)]} rolling {MUR[(2, 2)]} restitution {REST[(2, 2)]}
pair_coeff 1 2 friction {MU[(1, 2)]} rolling {MUR[(1, 2)]} restitution {REST[(1, 2)]}
{wall}
fix integrate all nve/sphere
timestep {DT}
{thermo_block("lammps", len(PLATE_ATOMS if plate else PAIR_ATOMS))}
run {STEPS}
"""


def run_both(tmp_path, plate, liggghts_model="model tbags"):
    atoms = PLATE_ATOMS if plate else PAIR_ATOMS
    out = {}
    for engine, deck in (("lammps", lammps_deck(plate)), ("liggghts", liggghts_deck(plate, liggghts_model))):
        wd = tmp_path / engine
        wd.mkdir()
        data_file(wd / "data.txt", atoms, 2)
        out[engine] = run(deck, wd, engine)
    return out


@pytest.mark.parametrize("plate", [False, True], ids=["pair", "plate"])
def test_same_law_same_numbers(tmp_path, plate):
    natoms = 1 if plate else 2
    r = run_both(tmp_path, plate)
    lmp, lig = r["lammps"], r["liggghts"]
    assert len(lmp["Step"]) == len(lig["Step"]) == STEPS // 20 + 1
    # the contact changes the spins; the pair parts within the run, the sphere on the plate
    # stays and slides (|F_t| = mu F_n at some printed steps, with a loaded spring)
    touching = np.abs(lmp["fz1"]) > 0
    assert touching[:5].all()
    assert touching[-1] if plate else not touching[-1]
    assert np.max(np.abs(lmp["omegax1"] - lmp["omegax1"][0])) > 1.0
    if plate:
        weight = 4.0 / 3.0 * np.pi * R2 ** 3 * RHO2 * G_PLATE    # in fz1 with the contact's
        ratio = np.hypot(lmp["fx1"], lmp["fy1"])[1:] / (MU_PLATE * (lmp["fz1"][1:] + weight))
        assert np.sum(np.abs(ratio - 1.0) < 1e-9) >= 3 and np.min(ratio) < 0.9, ratio
    for kind in ("f", "tq", "omega", "x", "y", "z"):
        d = rel(lig, lmp, columns(kind, natoms))
        print("%s %s: LIGGGHTS vs LAMMPS %.2e" % ("plate" if plate else "pair", kind, d))
        assert d < 1e-10, kind


def test_native_model_differs(tmp_path):
    """LIGGGHTS's own Hertz + tangential history + rolling epsd2 is not our law (history
    integrated then projected, damping only while sticking, the capped spring without the
    damping, a rolling spring of its own stiffness): the comparison above would see it."""
    r = run_both(tmp_path, False, "model hertz tangential history rolling_friction epsd2")
    d = rel(r["liggghts"], r["lammps"], columns("tq", 2))
    print("native LIGGGHTS vs our law: torques differ by %.2e" % d)
    assert d > 1e-3
