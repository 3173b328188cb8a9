"""Bad input for fix wall/gran/servo: each mistake is a LAMMPS ERROR (or, for an unreachable
target, a WARNING) naming the fix and what to do."""
import pytest

import lmprun

BASE = """
units si
atom_style sphere
boundary p p f
comm_modify vel yes
region box block 0 0.02 0 0.02 0 0.03
create_box 2 box
create_atoms 1 single 0.01 0.01 0.01
set type * diameter 0.005
set type * density 2650
PAIR
FIX
fix 1 all nve/sphere
run RUN
"""
PAIR = ("pair_style gran/hertz/rolling epsd\n"
        "pair_coeff * * material 1.8e9 0.1 friction 0.31 rolling 0.05 restitution 0.2")
PLATE = "fix p all wall/gran/servo zplane 0.0 +1 material 200e9 0.1 coeff * friction 1e10 rolling 0.05 restitution 0.2"
FILM = ("fix p all wall/gran/servo zplane 0.005 both material 3e9 0.4 film 0.001 950 bounds 0 0.02 0 0.02 "
        "free x z coeff * friction 0.1 rolling 0 restitution 0.2 face +1 "
        "coeff * friction 1e10 rolling 0 restitution 0.2 face -1")


def deck(fix, pair=PAIR, nrun=0):
    return BASE.replace("PAIR", pair).replace("FIX", fix).replace("RUN", str(nrun))


def test_good_plate_runs(tmp_path):
    lmprun.run(deck(PLATE), tmp_path).check()


def test_good_film_runs(tmp_path):
    res = lmprun.run(deck(FILM, nrun=10), tmp_path).check()
    assert "film of mass 0.00038 kg, no gravity" in res.output


BAD = [
    (PLATE.replace("zplane", "wplane"), "unknown plane 'wplane'"),
    (PLATE.replace("+1", "up"), "side must be +1"),
    (PLATE + " colour red", "unknown keyword 'colour'"),
    (PLATE.replace("material 200e9 0.1 ", ""), "missing 'material E nu' of the plate"),
    (PLATE.replace("200e9", "-200e9"), "plate Young's modulus must be > 0"),
    (PLATE.replace("coeff *", "coeff 2"), "particles of type 1 are in the group but have no plate coefficients"),
    (PLATE.replace("restitution 0.2", "restitution 0"), "restitution must be in (0, 1]"),
    (PLATE + " servo 10 gains 0 0 vmax 0.01", "servo gains must be KP > 0"),
    (PLATE + " servo 10 gains 1e-3 0 vmax -1", "servo vmax must be > 0"),
    (PLATE + " servo 10", "servo needs 'gains KP KI' and 'vmax V'"),
    (PLATE + " servo 10 gains 1e-3 0 vmax 0.01 filter -1e-4", "servo filter time constant must be >= 0"),
    (PLATE + " servo 10 gains 1e-3 0 vmax 0.01 filter", "filter needs a time constant"),
    (PLATE + " velocity q 0.1", "velocity dimension must be x, y or z"),
    (PLATE.replace("zplane 0.0", "zplane 0.0095"), "the plate starts 0.8 radii inside a particle"),
    (PLATE + " velocity x v_nothing", "velocity variable nothing does not exist"),
    (PLATE + " damping later", "damping must be explicit (as stock) or implicit, not 'later'"),
    (PLATE + " damping", "keyword 'damping' needs 1 value(s)"),
    # films: a sheet with particles on both sides (FILM: the sphere at 10 mm, on its + side)
    (FILM.replace(" coeff * friction 1e10 rolling 0 restitution 0.2 face -1", ""),
     "no film (- face) coefficients; add 'coeff 1 friction mu rolling mu_r restitution e face -1'"),
    (FILM.replace("coeff * friction 0.1", "coeff 2 friction 0.1"), "no film (+ face) coefficients"),
    (FILM.replace("friction 0.1", "friction -0.1"), "friction must be given and >= 0"),
    (FILM.replace("zplane 0.005", "zplane 0.04"), "the film (0.0395 to 0.0405 m) is outside the box"),
    (FILM.replace("film 0.001 950 ", ""), "give its 'film THICKNESS DENSITY'"),
    (FILM.replace("film 0.001 950", "film 0.001 -950"), "film needs a thickness > 0 m and a density > 0"),
    (FILM.replace("bounds 0 0.02 0 0.02 ", ""), "a film needs 'bounds"),
    (FILM + " servo 10 gains 1e-3 0 vmax 0.01", "a film has no servo"),
    (FILM.replace("face -1", "face 2"), "face must be +1 or -1"),
    (PLATE + " free x", "free motion needs a mass"),
    (PLATE + " coeff 1 friction 0.1 rolling 0 restitution 0.2 face +1", "face is for a film"),
    (PLATE + " film 0.001 950", "'film' is for a sheet with particles on both sides"),
    (FILM.replace("free x z", "free"), "free needs one or more of x, y, z"),
]


@pytest.mark.parametrize("fix,message", BAD)
def test_bad_input(tmp_path, fix, message):
    res = lmprun.run(deck(fix), tmp_path)
    assert res.returncode != 0, res.output[-1500:]
    assert "wall/gran/servo" in res.error_line() and message in res.error_line(), res.error_line()


def test_needs_our_pair_style(tmp_path):
    stock = ("pair_style granular\npair_coeff * * hertz/material 1.8e9 0.2 0.1 tangential mindlin "
             "NULL 1.0 0.31 damping coeff_restitution")
    res = lmprun.run(deck(PLATE, pair=stock), tmp_path)
    assert res.returncode != 0 and "pair_style gran/hertz/rolling" in res.error_line()


def test_unreachable_target_warns(tmp_path):
    # a plate far below a lone sphere that cannot supply 1e6 N: at vmax for too long -> warning
    far = PLATE.replace("zplane 0.0", "zplane -0.5") + " servo 1e6 gains 1e-6 0 vmax 0.01 warn 2000"
    res = lmprun.run(deck(far, nrun=3000), tmp_path).check()
    warn = [l for l in res.output.splitlines() if "WARNING" in l and "wall/gran/servo" in l]
    assert warn and "raise vmax, start the plate closer, or check the target" in warn[0]


# ---- the start-position check belongs to the plate's first run only ----------------------------
GROW = BASE.replace("PAIR", PAIR).replace("FIX", PLATE.replace("zplane 0.0", "zplane 0.0075")).replace(
    "run RUN", """run 0
# radii grown against a plate that is already in place (sample preparation by radius growth)
set type * diameter 0.0055
run 10
print "GROWN $(f_p[3]:%.6g)"
NEWPLATE
run 10
""")


def test_radius_growth_against_a_placed_plate_runs(tmp_path):
    res = lmprun.run(GROW.replace("NEWPLATE", ""), tmp_path).check()
    fz = float([l for l in res.output.splitlines() if l.startswith("GROWN")][0].split()[1])
    assert fz < 0.0    # the grown grain pushes on the plate


def test_a_new_plate_inside_a_grain_is_still_refused(tmp_path):
    res = lmprun.run(GROW.replace("NEWPLATE", PLATE.replace("fix p", "fix q").replace("zplane 0.0", "zplane 0.0075")),
                     tmp_path)
    assert res.returncode != 0, res.output[-1500:]
    assert "wall/gran/servo q: the plate starts 0.0909 radii inside a particle" in res.error_line(), res.error_line()


def test_a_plate_from_a_restart_file_is_not_checked_again(tmp_path):
    # a checkpoint of a plate pressed into a grain (here by growth; in a shear run by the load)
    # resumes: the plate's state comes from the restart file, so the start check does not apply
    first = GROW.replace("NEWPLATE", "write_restart pressed.restart")
    lmprun.run(first, tmp_path).check()
    resume = """
units si
atom_style sphere
boundary p p f
comm_modify vel yes
read_restart pressed.restart
comm_modify vel yes
PLATE
fix 1 all nve/sphere
run 10
print "RESUMED $(f_p[3]:%.6g)"
""".replace("PLATE", PLATE.replace("zplane 0.0", "zplane 0.0075"))
    res = lmprun.run(resume, tmp_path).check()
    fz = float([l for l in res.output.splitlines() if l.startswith("RESUMED")][0].split()[1])
    assert fz < 0.0
    # the same deck with a new fix ID (no restart state) is refused
    bad = lmprun.run(resume.replace("fix p all", "fix q all").replace("f_p[3]", "f_q[3]"), tmp_path)
    assert bad.returncode != 0 and "wall/gran/servo q: the plate starts" in bad.error_line(), bad.output[-800:]
