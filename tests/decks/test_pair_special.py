"""pair gran/hertz/rolling between bonded particles: the special_bonds lj 1-2 weight w scales the
whole contact (force and torques; the history evolves unscaled, as in stock pair granular),
w = 0 removes the pair, w = 1 is the plain contact (what the bag decks use: bonded neighbours
still touch in compression). Fractional weights take the kernel's per-contact factor path; its
AVX2 and baseline builds agree bit for bit there too."""
import pytest

import lmprun
import packing

DECK = lmprun.BPM_HEAD + """
create_atoms 1 single 0 0 0
create_atoms 1 single 0.0049 0.0003 0.0001
create_atoms 1 single -0.0049 0.0002 -0.0001
set type 1 diameter 0.005
set type 1 density 2650
velocity all set 0 0 0
set atom 1 vx 0.01 omega 0 0 3
set atom 3 vy 0.02 omega 1 0 0
special_bonds lj 0 1 1 coul 1 1 1
pair_style gran/hertz/rolling epsd ${options}
pair_coeff * * material 1.8e9 0.1 friction 0.31 rolling 0.05 restitution 0.2
bond_style zero
bond_coeff *
create_bonds single/bond 1 1 2
special_bonds lj ${w} 1 1 coul 1 1 1
fix 1 all nve/sphere
timestep 1e-7
compute t all property/atom tqx tqy tqz
group one id 1
group two id 2
compute t1 one reduce sum c_t[1] c_t[2] c_t[3]
compute t2 two reduce sum c_t[1] c_t[2] c_t[3]
thermo_style custom step c_t1[1]
run ${nsteps}
print "F1 $(fx[1]:%.17g) $(fy[1]:%.17g) $(fz[1]:%.17g) $(c_t1[1]:%.17g) $(c_t1[2]:%.17g) $(c_t1[3]:%.17g)"
print "F2 $(fx[2]:%.17g) $(fy[2]:%.17g) $(fz[2]:%.17g) $(c_t2[1]:%.17g) $(c_t2[2]:%.17g) $(c_t2[3]:%.17g)"
"""


def forces(tmp_path, w, nsteps=0, tag="", options=""):
    res = lmprun.run(DECK, tmp_path / ("w%s-%d%s" % (w, nsteps, tag)),
                     variables={"w": w, "nsteps": nsteps, "options": options}).check()
    if tag == "":
        forces.kernel = [l for l in res.output.splitlines() if "batch kernel" in l][0]
    rows = {l.split()[0]: [float(x) for x in l.split()[1:]] for l in res.output.splitlines()
            if l.startswith(("F1 ", "F2 "))}
    return rows["F1"], rows["F2"]


def test_weight_scales_the_bonded_contact(tmp_path):
    """Atom 1 touches 2 (bonded) and 3 (not bonded); atom 2 touches only 1."""
    one = forces(tmp_path, 1)
    half = forces(tmp_path, 0.5)
    zero = forces(tmp_path, 0)
    print("w = 1: %s\nw = 0.5: %s\nw = 0: %s" % (one, half, zero))
    # atom 2: only the bonded contact, scaled exactly (a product by 0.5 rounds exactly)
    assert all(abs(v) > 0 for v in one[1][:3])
    assert half[1] == [0.5 * v for v in one[1]]
    assert zero[1] == [0.0] * 6
    # atom 1: the unbonded contact with 3 stays whole; the bonded part scales
    for k in range(6):
        bonded = one[0][k] - zero[0][k]
        assert abs(half[0][k] - (zero[0][k] + 0.5 * bonded)) <= 1e-12 * max(abs(v) for v in one[0])


def test_factor_path_builds_agree(tmp_path):
    """w = 0.5 for 200 steps: the AVX2 build and the baseline build give the same bits."""
    avx2 = forces(tmp_path, 0.5, 200)
    if "batch kernel avx2" not in forces.kernel:
        pytest.skip("the AVX2 kernel did not run (%s): only the baseline was tested" % forces.kernel)
    base = forces(tmp_path, 0.5, 200, "-base", options="kernel baseline")
    print(avx2, base)
    assert avx2 == base
    assert avx2[1] != forces(tmp_path, 1, 200, "-base", options="kernel baseline")[1]    # the weight acted


REISSUE_A = lmprun.packing_head() + """pair_style gran/hertz/rolling none
pair_coeff * * material 1.8e9 0.1 friction 0.31 restitution 0.2
timestep 1e-6
fix 1 all nve/sphere
run 200
write_data mid.data nocoeff
# the same style again with another rolling model: LAMMPS only calls settings() on the pair
pair_style gran/hertz/rolling epsd
pair_coeff * * material 1.8e9 0.1 friction 0.31 rolling 0.05 restitution 0.2
run 200
write_dump all custom final.dump id x y z vx vy vz omegax omegay omegaz modify sort id format float %.17g
"""
REISSUE_B = """
units si
atom_style sphere
atom_modify map array
boundary p p p
comm_modify vel yes
read_data mid.data
pair_style gran/hertz/rolling epsd
pair_coeff * * material 1.8e9 0.1 friction 0.31 rolling 0.05 restitution 0.2
timestep 1e-6
fix 1 all nve/sphere
run 200
write_dump all custom fresh.dump id x y z vx vy vz omegax omegay omegaz modify sort id format float %.17g
"""


def test_reissued_pair_style_with_another_rolling_model(tmp_path):
    """pair_style gran/hertz/rolling none, a run, then pair_style ... epsd: the history store is
    made anew for the new model (another record size: reading the old store would run past its
    records), with a warning; the second run equals a fresh EPSD run from the same state (zero
    history), to round-off."""
    import numpy as np
    data = packing.make(tmp_path / "packing")
    res = lmprun.run(REISSUE_A, tmp_path, variables={"data": data}).check()
    assert "the rolling or twisting model changed since the last run" in res.output
    lmprun.run(REISSUE_B, tmp_path).check()
    cols, a = lmprun.read_dump(tmp_path / "final.dump")
    _, b = lmprun.read_dump(tmp_path / "fresh.dump")
    dx = np.abs(a[:, 1:4] - b[:, 1:4]).max()
    dv = lmprun.max_rel_diff(a[:, 4:10], b[:, 4:10])
    print("re-issued against fresh: max |dx| %.2e m, max |dv|/max|v| %.2e" % (dx, dv))
    assert dx < 1e-12 and dv < 1e-9


def test_reissued_pair_style_with_twisting_switched_on(tmp_path):
    """The same rolling model, twisting switched on by a re-issued pair_style: the record grows
    by the twist angle, so the store is made anew with the warning (reading the old, shorter
    records would run past them) and the run goes on."""
    data = packing.make(tmp_path / "packing")
    first, second = REISSUE_A.split("write_data mid.data nocoeff\n")
    first = first.replace("rolling none\n", "rolling epsd\n").replace(
        "restitution 0.2\n", "rolling 0.05 restitution 0.2\n")
    second = second.replace("rolling epsd\n", "rolling epsd twisting sds\n").replace(
        "restitution 0.2\n", "restitution 0.2 twisting 1e-5 1e-10 1e-6\n")
    deck = first + second
    assert deck.count("twisting sds") == 1 and deck.count("rolling epsd") == 2
    res = lmprun.run(deck, tmp_path, variables={"data": data}).check()
    assert res.output.count("the rolling or twisting model changed since the last run") == 1
