"""Plugin loading and bad input for pair gran/hertz/rolling: every mistake gives a LAMMPS
ERROR naming the style and what to write, never a crash."""
import pytest

import lmprun

BASE = """
units si
atom_style ATOMSTYLE
boundary p p p
COMM
region box block 0 0.01 0 0.01 0 0.01
create_box 2 box
create_atoms 1 single 0.004 0.005 0.005
create_atoms 2 single 0.0085 0.005 0.005
SETS
PAIR
run 0
"""

GOOD_PAIR = ("pair_style gran/hertz/rolling epsd\n"
             "pair_coeff * * material 1.8e9 0.1 friction 0.31 rolling 0.05 restitution 0.2")


def deck(pair=GOOD_PAIR, atom_style="sphere", comm="comm_modify vel yes"):
    sets = "set type * diameter 0.005\nset type * density 2650" if atom_style == "sphere" else "mass * 1.0"
    return (BASE.replace("ATOMSTYLE", atom_style).replace("COMM", comm)
            .replace("SETS", sets).replace("PAIR", pair))


def test_good_deck_runs(tmp_path):
    lmprun.run(deck(), tmp_path).check()


def test_plugin_list_and_explicit_load(tmp_path):
    text = "plugin load %s\nplugin list\n" % lmprun.PLUGIN + deck()
    res = lmprun.run(text, tmp_path, plugin_path=False).check()
    assert "gran/hertz/rolling" in res.output
    assert "tbags" in res.output


def test_plugin_path_autoload(tmp_path):
    res = lmprun.run("plugin list\n" + deck(), tmp_path).check()
    assert "pair style plugin gran/hertz/rolling" in res.output


def test_unknown_style_without_plugin(tmp_path):
    res = lmprun.run(deck(), tmp_path, plugin_path=False)
    assert res.returncode != 0 and "gran/hertz/rolling" in res.error_line()

# twisting sds without its coefficients
TWIST_PAIR = GOOD_PAIR.replace("epsd", "epsd twisting sds")

BAD = [
    ("pair_style gran/hertz/rolling", "missing rolling model"),
    ("pair_style gran/hertz/rolling epsd banana", "unknown keyword 'banana'"),
    ("pair_style gran/hertz/rolling sds", "unknown rolling model 'sds'"),
    ("pair_style gran/hertz/rolling epsd\npair_coeff * * material 1.8e9 0.1 friction 0.31 rolling 0.05 restitution 0.2 colour 3",
     "unknown pair_coeff keyword 'colour'"),
    ("pair_style gran/hertz/rolling epsd\npair_coeff * * material -1.8e9 0.1 friction 0.31 rolling 0.05 restitution 0.2",
     "Young's modulus must be > 0"),
    ("pair_style gran/hertz/rolling epsd\npair_coeff * * material 1.8e9 0.6 friction 0.31 rolling 0.05 restitution 0.2",
     "Poisson's ratio must be in (-1, 0.5)"),
    ("pair_style gran/hertz/rolling epsd\npair_coeff * * material 1.8e9 0.1 friction 0.31 rolling 0.05 restitution 0",
     "coefficient of restitution must be in (0, 1]"),
    ("pair_style gran/hertz/rolling epsd\npair_coeff * * material 1.8e9 0.1 friction 0.31 rolling 0.05 restitution 1.5",
     "coefficient of restitution must be in (0, 1]"),
    ("pair_style gran/hertz/rolling epsd\npair_coeff * * material 1.8e9 0.1 friction 0.31 rolling -0.05 restitution 0.2",
     "rolling friction mu_r must be >= 0"),
    ("pair_style gran/hertz/rolling epsd\npair_coeff * * material 1.8e9 0.1 friction 0.31 restitution 0.2",
     "needs friction, restitution and rolling"),
    ("pair_style gran/hertz/rolling epsd\npair_coeff 1 1 material 1.8e9 0.1 friction 0.31 rolling 0.05 restitution 0.2",
     "type 2 has no material"),
    ("pair_style gran/hertz/rolling epsd\npair_coeff 1 2 material 1.8e9 0.1 friction 0.31 rolling 0.05 restitution 0.2",
     "'material' sets a type's E and nu"),
    ("pair_style gran/hertz/rolling epsd\npair_coeff * * friction 0.31 material 1.8e9",
     "keyword 'material' needs 2 value(s)"),
    ("pair_style gran/hertz/rolling epsd twisting marshall", "twisting must be none or sds"),
    ("pair_style gran/hertz/rolling epsd twisting", "twisting must be none or sds"),
    (GOOD_PAIR + " twisting 1e-5 1e-10 1e-6", "needs 'twisting sds' in the pair_style command"),
    (TWIST_PAIR, "needs 'twisting k_tw c_tw mu_tw'"),
    (TWIST_PAIR + " twisting -1e-5 1e-10 1e-6", "stiffness k_tw > 0"),
    (TWIST_PAIR + " twisting 1e-5 -1e-10 1e-6", "damping c_tw >= 0"),
    (TWIST_PAIR + " twisting 1e-5 1e-10 -1e-6", "mu_tw >= 0"),
    (TWIST_PAIR + " twisting 1e-5 1e-10", "keyword 'twisting' needs 3 value(s)"),
]


@pytest.mark.parametrize("pair,message", BAD)
def test_bad_input(tmp_path, pair, message):
    res = lmprun.run(deck(pair=pair), tmp_path)
    err = res.error_line()
    assert res.returncode != 0, res.output[-2000:]
    assert "gran/hertz/rolling" in err and message in err, err


def test_wrong_atom_style(tmp_path):
    res = lmprun.run(deck(atom_style="atomic"), tmp_path)
    assert res.returncode != 0
    assert "atom_style sphere or bpm/sphere" in res.error_line()


def test_missing_comm_modify_vel(tmp_path):
    res = lmprun.run(deck(comm=""), tmp_path)
    assert res.returncode != 0
    assert "comm_modify vel yes" in res.error_line()


@pytest.mark.parametrize("twist", [False, True])
def test_write_data_round_trip(tmp_path, twist):
    pair = GOOD_PAIR
    if twist:
        # types 1 and 2 given, the 1-2 pair mixed
        pair = (GOOD_PAIR.replace("epsd", "epsd twisting sds").replace("* *", "1 1")
                + " twisting 1e-5 1e-10 1e-6\n"
                "pair_coeff 2 2 material 0.9e9 0.3 friction 0.5 rolling 0.1 restitution 0.5 "
                "twisting 4e-5 4e-10 4e-6")
    text = deck(pair=pair).replace("run 0", "run 0\nwrite_data rt.data pair ij")
    lmprun.run(text, tmp_path).check()
    again = """
units si
atom_style sphere
comm_modify vel yes
pair_style gran/hertz/rolling epsd%s
read_data rt.data
run 0
write_data rt2.data pair ij
""" % (" twisting sds" if twist else "")
    lmprun.run(again, tmp_path).check()
    def coeffs(p):
        t = (tmp_path / p).read_text()
        return t[t.index("PairIJ Coeffs"):t.index("Atoms")]
    assert "material 1800000000 0.10000000000000001 friction 0.31" in coeffs("rt.data")
    if twist:    # the 1-2 pair mixed geometrically: sqrt(1e-5 4e-5) = 2e-5
        assert "1 2 friction" in coeffs("rt.data") and " twisting 2.0000000000000002e-05" in coeffs("rt.data")
    assert coeffs("rt.data") == coeffs("rt2.data")
