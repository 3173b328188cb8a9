"""The top plate's force servo in LIGGGHTS (fix servo/plate on law/servo.h driving a mesh plate
through fix move/mesh linear/variable; the plate's force from fix mesh/surface/stress) against
LAMMPS's fix wall/gran/servo on the tiny bag: the plate approaches at vmax, touches, and the
proportional servo brings F_v to its target, as inputs/between_plates.lmp compresses the bag;
the plate's force and speed agree step for step (to round-off at first, within a fraction of a
percent of the target once the packing has rearranged). Also: bad input to fix servo/plate."""
import numpy as np
import pytest

import lmprun
from twoengines import PLATE, DataFile, bag_model_lammps, convert, run

STEPS, EVERY = 40000, 200
FV, KP, VMAX, TAU = 43.0, 1.0, 0.02, 1e-4    # the tiny bag's F_v (between_plates.lmp's servo)


def geometry(fill):
    """Top plate start (0.1 mm above the top particles: the approach is short) and the bag's centre."""
    d = DataFile(fill)
    return float(d.x[:, 2].max()) + 0.0025 + 1e-4, d.x[:, 0].mean(), d.x[:, 1].mean()


def lammps_deck(ztop):
    servo = f"servo {FV} gains {KP / FV!r} 0 vmax {VMAX} filter {TAU}"
    return bag_model_lammps(f"{ztop!r} -1 {PLATE} {servo}") + f"""
variable F equal f_top[3]
variable speed equal -f_top[22]
thermo_style custom step v_F v_speed
thermo_modify format float %.16g
thermo {EVERY}
run {STEPS}
"""


def liggghts_deck(ztop, cx, cy, servo_args=None):
    servo = servo_args or f"target {FV} gains {KP / FV!r} 0 vmax {VMAX} filter {TAU}"
    return f"""
variable fill string fill.liggghts.data
include ${{tbags}}/inputs/liggghts/model.lig
fix top all mesh/surface/stress file ${{tbags}}/inputs/liggghts/plate.stl type 3 scale 0.2 &
    move {cx!r} {cy!r} {ztop!r} stress on
fix topwall all wall/gran model tbags mesh n_meshes 1 meshes top
variable F equal f_top[3]
fix servo all servo/plate v_F {servo}
variable vz equal -f_servo
variable zero equal 0
fix press all move/mesh mesh top linear/variable v_zero v_zero v_vz
variable speed equal f_servo
thermo_style custom step v_F v_speed
thermo_modify format float %.16g
thermo {EVERY}
run {STEPS}
"""


@pytest.fixture(scope="module")
def runs(tiny_filled, tmp_path_factory):
    fill = tiny_filled / "fill.data"
    ztop, cx, cy = geometry(fill)
    wd = tmp_path_factory.mktemp("lammps")
    (wd / "fill.data").write_bytes(fill.read_bytes())
    out = {"lammps": run(lammps_deck(ztop), wd, "lammps")}
    wd = tmp_path_factory.mktemp("liggghts")
    convert(fill, wd / "fill.liggghts.data")
    out["liggghts"] = run(liggghts_deck(ztop, cx, cy), wd, "liggghts")
    return out


def test_servo_plate_as_lammps(runs):
    lmp, lig = runs["lammps"], runs["liggghts"]
    assert len(lmp["Step"]) == len(lig["Step"]) == STEPS // EVERY + 1
    touched = np.argmax(lmp["F"] > 0)
    assert touched > 0 and np.argmax(lig["F"] > 0) == touched
    # before the touch: both approach at vmax; then the same force, to round-off at first
    assert np.allclose(lig["speed"][1:touched], VMAX, rtol=1e-12)
    assert np.allclose(lmp["speed"][1:touched], VMAX, rtol=1e-12)
    early = slice(touched, touched + 5)
    d_early = np.max(np.abs(lig["F"][early] - lmp["F"][early])) / FV
    late = slice(-20, None)
    d_late = np.max(np.abs(lig["F"][late] - lmp["F"][late])) / FV
    print("servo: touch at step %d; F LIGGGHTS vs LAMMPS / F_v: first 5 prints %.2e, last 20 %.2e; "
          "final F %.3f / %.3f N (target %g)" % (lmp["Step"][touched], d_early, d_late, lig["F"][-1],
                                                  lmp["F"][-1], FV))
    assert d_early < 1e-6
    # reached the target and held it in both
    for r in (lmp, lig):
        assert abs(np.mean(r["F"][late]) / FV - 1) < 0.02


@pytest.mark.parametrize("args,message", [
    ("target 43 gains 0.02 0", "needs 'target F0', 'gains KP KI' and 'vmax V'"),
    ("target -5 gains 0.02 0 vmax 0.01", "target force must be > 0"),
    ("target 43 gains 0.02 0 vmax 0.01 colour red", "unknown keyword 'colour'"),
    ("target 43 gains 0.02 vmax 0.01", "gains needs a number, got 'vmax'"),
])
def test_bad_input(tmp_path, tiny_filled, args, message):
    fill = tiny_filled / "fill.data"
    ztop, cx, cy = geometry(fill)
    convert(fill, tmp_path / "fill.liggghts.data")
    res = lmprun.run(liggghts_deck(ztop, cx, cy, args), tmp_path, engine="liggghts")
    assert res.returncode != 0 and message in res.output, res.output[-600:]
