"""The batched SIMD kernel of pair gran/hertz/rolling: its AVX2 build (picked at run time) and its
baseline x86-64 build (SSE2, pair_style keyword 'kernel baseline') give the same bits, pressure
included; each run logs the build that ran, and the tests check that both really ran.
A dense two-material packing with random velocities: sliding, rolling caps, contacts opening.
(The kernel against stock pair granular: test_pair_stock.py.)"""
import pytest

import lmprun
import packing

DECK = lmprun.packing_head("${newton}") + """variable vx atom 0.05*normal(0,1,4929)
variable vy atom 0.05*normal(0,1,4930)
variable vz atom 0.05*normal(0,1,4931)
velocity all set v_vx v_vy v_vz
pair_style gran/hertz/rolling ${model} ${options}
pair_coeff 1 1 material 1.8e9 0.1 friction 0.31 rolling 0.05 restitution 0.2
pair_coeff 2 2 material 0.75e9 0.1 friction 0.26 rolling 0.03 restitution 0.3
pair_coeff 1 2 friction 0.2 rolling 0.04 restitution 0.25
timestep 1e-6
fix 1 all nve/sphere
thermo_style custom step ke press pxx pyz
thermo_modify format float %.17g
thermo 50
run 200
write_dump all custom final.dump id x y z vx vy vz omegax omegay omegaz fx fy fz tqx tqy tqz &
    modify sort id format float %.17g
"""


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    return packing.make(tmp_path_factory.mktemp("packing"))


def run(wd, data, model, newton="on", options=""):
    return lmprun.run(DECK, wd, variables={"data": data, "model": model, "newton": newton,
                                           "options": options}).check()


def kernel_of(res):
    """The batch kernel a run logged: 'avx2' or 'baseline'."""
    lines = [l for l in res.output.splitlines() if "batch kernel" in l]
    assert lines, "the pair style did not log its kernel"
    return lines[0].split("batch kernel ")[1].split(",")[0].split()[0]


def require_avx2(res):
    if kernel_of(res) != "avx2":
        pytest.skip("the AVX2 kernel did not run (%s): only the baseline was tested"
                    % [l for l in res.output.splitlines() if "batch kernel" in l][0])


@pytest.mark.parametrize("model", ["epsd", "cdt", "none"])
def test_avx2_and_baseline_builds_agree_bitwise(tmp_path, data, model):
    default = run(tmp_path / "default", data, model)
    require_avx2(default)
    base = run(tmp_path / "baseline", data, model, options="kernel baseline")
    assert kernel_of(base) == "baseline"
    for f in ("final.dump", "log.lammps"):
        a = (tmp_path / "default" / f).read_text()
        b = (tmp_path / "baseline" / f).read_text()
        if f == "log.lammps":    # thermo lines only (the log also has timings)
            a, b = ([l for l in x.splitlines() if len(l.split()) == 5 and l.split()[0].isdigit()]
                    for x in (a, b))
            assert len(a) == 5
        assert a == b, f


FREEZE = lmprun.packing_head() + """pair_style gran/hertz/rolling epsd
pair_coeff * * material 1.8e9 0.1 friction 0.31 rolling 0.05 restitution 0.2
group frz id <= 150
fix f frz freeze
timestep 1e-6
fix 1 all nve/sphere
run 50
""" + lmprun.CONTACT_DUMP


def test_frozen_atoms_use_the_other_mass(tmp_path, data):
    """fix freeze: m* of a contact with a frozen atom is the other atom's mass (the kernel packs
    frozen masses negative); per-atom forces of the free atoms equal the sums of single()'s
    contact forces (which take m* from the masses and the freeze group directly)."""
    import numpy as np
    lmprun.run(FREEZE, tmp_path, variables={"data": data}).check()
    c, ids, forces, sums = lmprun.contact_force_sums(tmp_path)
    free = ids > 150
    frozen_contacts = ((c[:, 0] <= 150) != (c[:, 1] <= 150)).sum()
    err = np.abs(sums[free] - forces[free]).max() / np.abs(c[:, 3:6]).max()
    print("%d contacts, %d between a frozen and a free atom; error %.2e" % (len(c), frozen_contacts, err))
    assert frozen_contacts > 20
    assert err < 1e-12


def dump_and_thermo(wd):
    log = [l for l in (wd / "log.lammps").read_text().splitlines()
           if len(l.split()) == 5 and l.split()[0].isdigit()]
    assert len(log) == 5
    return (wd / "final.dump").read_text(), log


def test_kernel_keyword(tmp_path, data):
    """kernel avx2 runs the AVX2 build or stops with the reason; auto logs what it picked."""
    auto = run(tmp_path / "auto", data, "epsd")
    if kernel_of(auto) == "avx2":
        assert kernel_of(run(tmp_path / "avx2", data, "epsd", options="kernel avx2")) == "avx2"
    else:
        r = lmprun.run(DECK, tmp_path / "avx2", variables={"data": data, "model": "epsd", "newton": "on",
                                                             "options": "kernel avx2"})
        assert r.returncode != 0 and "kernel avx2 is not available" in r.output


@pytest.mark.parametrize("model", ["epsd", "none"])
def test_candidate_list_gives_the_whole_list_bits(tmp_path, data, model):
    """Each step visits only the candidate pairs (closer than r_i + r_j + a fraction of the
    neighbor skin), rebuilt when an atom has moved half that. With a candidate skin of 0.2 %
    of the neighbor skin (2 um) the list is rebuilt every 20-40 steps between neighbor list
    builds, while pairs close by up to 10 um in the run (new contacts form): a missed rebuild
    would miss contacts. Both equal the whole-list walk (fraction 0) bit for bit."""
    runs = {}
    for frac in ("0", "0.002", None):
        wd = tmp_path / ("default" if frac is None else "f" + frac)
        run(wd, data, model, options="" if frac is None else "contact_skin " + frac)
        runs[frac] = dump_and_thermo(wd)
    assert runs["0.002"] == runs["0"]
    assert runs[None] == runs["0"]


@pytest.mark.parametrize("options,message", [
    ("contact_skin -0.1", "contact_skin must be a fraction >= 0 of the neighbor skin"),
    ("contact_skin", "contact_skin needs a fraction"),
    ("kernel sse9", "kernel must be auto, avx2 or baseline, not 'sse9'"),
    ("kernel", "kernel needs auto, avx2 or baseline"),
    ("rolling_radius", "rolling_radius must be effective (R* = RiRj/(Ri+Rj)) or mean"),
    ("rolling_radius big", "rolling_radius must be effective (R* = RiRj/(Ri+Rj)) or mean ((Ri+Rj)/2), not 'big'"),
])
def test_bad_pair_style_keywords(tmp_path, data, options, message):
    r = lmprun.run(DECK, tmp_path, variables={"data": data, "model": "epsd", "newton": "on",
                                              "options": options})
    assert r.returncode != 0 and message in r.error_line(), r.error_line()


RESTARTED = """
units si
read_restart kernel.restart
comm_modify vel yes
timestep 1e-6
fix 1 all nve/sphere
run 10
"""


def test_kernel_keywords_survive_a_restart(tmp_path, data):
    """kernel and contact_skin are stored in the restart file with the rolling model: the run
    that reads it logs the same kernel choice."""
    deck = DECK.replace("write_dump all custom final.dump", "write_restart kernel.restart\nwrite_dump all custom final.dump")
    lmprun.run(deck, tmp_path, variables={"data": data, "model": "cdt", "newton": "on",
                                          "options": "kernel baseline contact_skin 0.1"}).check()
    res = lmprun.run(RESTARTED, tmp_path).check()
    line = [l for l in res.output.splitlines() if "batch kernel" in l][0]
    print(line)
    assert "batch kernel baseline" in line and "(kernel baseline)" in line
    assert "rolling radius effective R*" in line


def test_rolling_radius_survives_a_restart(tmp_path, data):
    """rolling_radius mean is stored in the restart file (and logged): the run that reads it
    continues with the mean radius, where the default (effective) gives other torques."""
    deck = DECK.replace("write_dump all custom final.dump", "write_restart kernel.restart\nwrite_dump all custom final.dump")
    first = lmprun.run(deck, tmp_path, variables={"data": data, "model": "epsd", "newton": "on",
                                                  "options": "rolling_radius mean"}).check()
    assert "rolling radius mean (Ri+Rj)/2" in first.output
    res = lmprun.run(RESTARTED, tmp_path).check()
    line = [l for l in res.output.splitlines() if "batch kernel" in l][0]
    print(line)
    assert "rolling radius mean (Ri+Rj)/2" in line
    effective = run(tmp_path / "effective", data, "epsd")
    assert (tmp_path / "effective" / "final.dump").read_text() != (tmp_path / "final.dump").read_text()
    assert "rolling radius effective R*" in effective.output
