"""Bad input for bond_style bpm/yarn: missing or broken tables and coefficients, wrong atom
style, missing integrator: each a LAMMPS ERROR (or WARNING) naming the style and the fix."""
import pytest

import lmprun

TABLE = lmprun.ROOT / "inputs" / "yarn_pp_tape.table"

DECK = """
units si
atom_style ATOMSTYLE
boundary f f f
comm_modify vel yes
newton on off
region box block -0.01 0.02 -0.01 0.01 -0.01 0.01
create_box 1 box bond/types 1 extra/bond/per/atom 2 extra/special/per/atom 2
create_atoms 1 single 0 0 0
create_atoms 1 single 0.005 0 0
SETS
special_bonds lj 0 1 1 coul 1 1 1
pair_style zero 0.006
pair_coeff * *
bond_style bpm/yarn
bond_coeff 1 COEFF
create_bonds single/bond 1 1 2
FIX
run 0
"""
GOOD = "table %s YARN_PP_TAPE diameter 0.001 poisson 0.3" % TABLE


def deck(coeff=GOOD, atom_style="bpm/sphere", fix="fix 1 all nve/bpm/sphere"):
    sets = ("set type 1 diameter 0.005\nset type 1 density 450" if atom_style == "bpm/sphere"
            else "mass 1 1e-5")
    return (DECK.replace("ATOMSTYLE", atom_style).replace("SETS", sets)
            .replace("COEFF", coeff).replace("FIX", fix))


def write_table(path, rows, header="N %d"):
    lines = ["# test table", "", "T", header % len(rows), ""]
    lines += ["%d %s %s" % (k + 1, e, s) for k, (e, s) in enumerate(rows)]
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.mark.parametrize("fix", ["fix 1 all nve/bpm/sphere", "fix 1 all nve/sphere"])
def test_good_deck_runs(tmp_path, fix):
    # the law reads no orientations: either integrator of rotations, no warning
    res = lmprun.run(deck(fix=fix), tmp_path).check()
    assert "rotations integrated" not in res.output


def test_missing_integrator_warns(tmp_path):
    res = lmprun.run(deck(fix=""), tmp_path).check()
    assert "need their rotations integrated: fix nve/sphere" in res.output


@pytest.mark.parametrize("rows,message", [
    ([(0, 0), (0.1, 1e8), (0.1, 2e8)], "strains must increase strictly"),
    ([(0, 0), (0.1, 1e8), (0.2, -1e8)], "stresses must not be negative"),
    ([(0, 0)], "needs 'N n' with n >= 2"),
    ([(0.01, 0), (0.1, 1e8)], "must start at strain 0 with stress 0"),
])
def test_bad_tables(tmp_path, rows, message):
    t = write_table(tmp_path / "bad.table", rows)
    res = lmprun.run(deck("table %s T diameter 0.001 poisson 0.3" % t), tmp_path)
    assert res.returncode != 0 and "bpm/yarn" in res.error_line() and message in res.error_line(), res.error_line()


BAD = [
    ("table /nonexistent/file.table YARN diameter 0.001 poisson 0.3", "cannot read yarn table"),
    ("table %s NO_SUCH_SECTION diameter 0.001 poisson 0.3" % TABLE, "no section 'NO_SUCH_SECTION'"),
    ("table %s YARN_PP_TAPE poisson 0.3" % TABLE, "needs 'diameter D' with D > 0"),
    ("table %s YARN_PP_TAPE diameter -0.001 poisson 0.3" % TABLE, "needs 'diameter D' with D > 0"),
    ("table %s YARN_PP_TAPE diameter 0.001" % TABLE, "needs 'poisson NU'"),
    ("table %s YARN_PP_TAPE diameter 0.001 poisson 0.3 break 0.5" % TABLE, "must be in (0, 0.16]"),
    ("table %s YARN_PP_TAPE diameter 0.001 poisson 0.3 shear -0.5" % TABLE, "shear coefficient must be >= 0"),
    ("table %s YARN_PP_TAPE diameter 0.001 poisson 0.3 colour red" % TABLE, "unknown bond_coeff keyword 'colour'"),
    ("%s YARN_PP_TAPE diameter 0.001 poisson 0.3" % TABLE, "write 'bond_coeff T table FILE KEYWORD"),
    ("table %s YARN_PP_TAPE diameter 0.001 poisson 0.3 unload sometimes" % TABLE, "unload must be elastic or plastic"),
]


@pytest.mark.parametrize("coeff,message", BAD)
def test_bad_coeff(tmp_path, coeff, message):
    res = lmprun.run(deck(coeff), tmp_path)
    assert res.returncode != 0 and "bpm/yarn" in res.error_line() and message in res.error_line(), res.error_line()


def test_wrong_atom_style(tmp_path):
    res = lmprun.run(deck(atom_style="bond", fix=""), tmp_path)
    assert res.returncode != 0 and "requires atom_style bpm/sphere" in res.error_line(), res.error_line()


@pytest.mark.parametrize("settings,message", [
    ("kernel", "kernel needs a value: auto or baseline"),
    ("kernel fast", "kernel fast is not known; use auto or baseline"),
    ("stiff yes", "unknown keyword 'stiff'; use overlay/pair, break, store/local or kernel"),
])
def test_bad_settings(tmp_path, settings, message):
    res = lmprun.run(deck().replace("bond_style bpm/yarn", "bond_style bpm/yarn " + settings), tmp_path)
    assert res.returncode != 0 and "Bond style bpm/yarn: " + message in res.error_line()


def test_kernel_keyword_picks_the_build(tmp_path):
    res = lmprun.run(deck().replace("bond_style bpm/yarn", "bond_style bpm/yarn kernel baseline"), tmp_path).check()
    assert "Bond style bpm/yarn: batch kernel baseline" in res.output
