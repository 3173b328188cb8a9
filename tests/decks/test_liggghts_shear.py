"""The shear test in both engines on the tiny bag: inputs/in.shear (LAMMPS) and
inputs/liggghts/in.shear (LIGGGHTS, from the same fill converted) compress the bag to F_v and shear
it 1 mm at the demo's speed. The compression stops at the same step in both (the same servo and
convergence rule, checked every 1000 steps); then the means per 0.1 mm of u agree: the first row
to 1 %, S over the run to a few % (the engines' round-off differences grow in the packing as two
realizations' would, but from far closer states), w to 0.05 mm; F_v is held in both."""
import os
import subprocess

import numpy as np
import pytest

import lmprun
from twoengines import convert
from tbagspost.run import read_csv  # (postprocess/ is on the path through twoengines)
from tbagsrun.liggghts_stage import means_to_csv

RUN = {"nx": 9, "ny": 9, "nz": 5, "v": 0.015, "ufinal": 0.001}
# LIGGGHTS's servo plates damp explicitly (as stock) at 1.5e-6 s: LAMMPS runs the same scheme
EXPLICIT = {"dt": 1.5e-6, "damping": "explicit"}


@pytest.fixture(scope="module")
def runs(tiny_filled, tmp_path_factory):
    fill = tiny_filled / "fill.data"
    wd = tmp_path_factory.mktemp("lammps")
    (wd / "fill.data").write_bytes(fill.read_bytes())
    lmprun.run(lmprun.INPUTS / "in.shear", wd, variables=dict(RUN, **EXPLICIT)).check()
    csv = np.genfromtxt(wd / "shear.csv", delimiter=",", names=True, comments="#")
    lmp = {"t": csv["time_s"], "u": csv["u_mm"], "w": csv["w_mm"], "S": csv["S_N"], "F": csv["Fv_N"]}
    lmp_log = (wd / "log.lammps").read_text()
    wd = tmp_path_factory.mktemp("liggghts")
    convert(fill, wd / "fill.liggghts.data")
    res = lmprun.run(lmprun.INPUTS / "liggghts" / "in.shear", wd, engine="liggghts",
                     variables=dict(RUN, fill="fill.liggghts.data")).check("liggghts")
    m = np.loadtxt(wd / "shear.means.txt")
    lig = {"u": m[:, 2] * 1e3, "w": m[:, 3] * 1e3, "S": m[:, 4], "F": m[:, 5]}
    return lmp, lig, lmp_log, res.output, wd


def test_compressed_at_the_same_step(runs):
    lmp_log, lig_out = runs[2], runs[3]
    lmp_steps = int(lmp_log.split("COMPRESSED")[0].split("Loop time of")[-1].split("for")[1].split()[0])
    lig_steps = lig_out.split("COMPRESSED")[0].count("Loop time of") * 1000
    print("compression: LAMMPS %d steps, LIGGGHTS %d" % (lmp_steps, lig_steps))
    assert lmp_steps == lig_steps


def test_same_shear_curve(runs):
    lmp, lig = runs[0], runs[1]
    # LAMMPS's CSV starts with the set-up row (u = 0); then the rows match one for one
    a = {k: v[1:] for k, v in lmp.items()}
    assert len(a["S"]) == len(lig["S"]) == 10 and np.allclose(a["u"], lig["u"], atol=1e-3)
    dS = np.abs(lig["S"] - a["S"])
    dw = np.abs(lig["w"] - a["w"])
    print("tiny bag, 1 mm: S LIGGGHTS vs LAMMPS: first row %.2f %%, mean %.2f %%, max %.2f %% of S at 1 mm "
          "(%.1f N); w: max %.4f mm; F_v means %.2f-%.2f N (LIGGGHTS), %.2f-%.2f N (LAMMPS)"
          % (100 * dS[0] / a["S"][0], 100 * dS.mean() / a["S"][-1], 100 * dS.max() / a["S"][-1],
             a["S"][-1], dw.max(), lig["F"].min(), lig["F"].max(), a["F"].min(), a["F"].max()))
    assert dS[0] < 0.01 * a["S"][0]
    assert dS.mean() < 0.05 * a["S"][-1] and dS.max() < 0.1 * a["S"][-1]
    assert dw.max() < 0.05
    target = 5500 * 7 * 7 / 79 ** 2
    for F in (lig["F"], a["F"]):
        assert np.all(np.abs(F / target - 1) < 0.01)


def test_csv_from_the_means_and_the_trace(runs):
    """The LIGGGHTS run's per-step trace has every shearing step once; averaged over a row's steps
    it gives fix ave/time's mean of the row (to its 6 printed digits); the CSV made from both has
    in.shear's columns with min <= mean <= max and no broken bond."""
    wd = runs[4]
    m = np.loadtxt(wd / "shear.means.txt")
    tr = np.loadtxt(wd / "shear.steps.txt")
    assert np.array_equal(tr[:, 0], np.arange(1, m[-1, 0] + 1))
    last = 0
    for row in m:
        chunk = tr[(tr[:, 0] > last) & (tr[:, 0] <= row[0])]
        for mc, tc in ((3, 1), (4, 2), (5, 3), (6, 4)):    # w S F_v z_plate
            assert chunk[:, tc].mean() == pytest.approx(row[mc], rel=2e-5), (row[0], mc)
        last = row[0]
    means_to_csv(wd / "shear.means.txt", wd / "shear.csv", wd / "shear.start.txt", wd / "shear.steps.txt")
    d = read_csv(wd / "shear.csv")
    for q, unit in (("w", "mm"), ("S", "N"), ("Fv", "N"), ("zplate", "mm")):
        mean, lo, hi = d["%s_%s" % (q, unit)], d["%s_min_%s" % (q, unit)], d["%s_max_%s" % (q, unit)]
        assert np.all(lo <= mean + 1e-4) and np.all(mean <= hi + 1e-4)
    assert np.all(d["S_max_N"][1:] > d["S_min_N"][1:])    # S varies within a row while shearing
    assert np.all(d["broken_bonds"] == 0)
    print("LIGGGHTS tiny bag: S spread within a row (max - min) %.2f-%.2f N, F_v %.3f-%.3f N"
          % ((d["S_max_N"] - d["S_min_N"])[1:].min(), (d["S_max_N"] - d["S_min_N"])[1:].max(),
             (d["Fv_max_N"] - d["Fv_min_N"])[1:].min(), (d["Fv_max_N"] - d["Fv_min_N"])[1:].max()))


def test_launcher_engine_liggghts(tmp_path):
    """./tbags shear --engine liggghts end to end on the tiny bag: LAMMPS's bag and fill, the
    shear in LIGGGHTS, shear.csv in the launcher's columns, the S-u figure."""
    out = tmp_path / "out"
    tiny = ["-np", "1", "-var", "nx", "9", "-var", "ny", "9", "-var", "nz", "5", "-var", "v", "0.02",
            "-var", "ufinal", "0.0003"]
    env = dict(os.environ, TBAGS_BUILD_DIR=os.environ.get("TBAGS_BUILD", str(lmprun.ROOT / "build")))
    r = subprocess.run([str(lmprun.ROOT / "tbags"), "shear", "--engine", "liggghts", "--out", str(out)] + tiny,
                       env=env, capture_output=True, text=True, timeout=900 * lmprun.SLOWDOWN)
    print(r.stdout[-2000:], r.stderr[-2000:])
    assert r.returncode == 0 and "shear (LIGGGHTS)" in r.stdout and "SHEARED: u 0.299" in r.stdout
    d = read_csv(out / "shear.csv")
    assert len(d) == 4 and d["u_mm"][0] == 0 and abs(d["u_mm"][-1] - 0.25) < 1e-3
    assert "S_max_N" in d.dtype.names and not (out / "shear.steps.txt").exists()
    assert (out / "figures" / "shear.png").is_file()
