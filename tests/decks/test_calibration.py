"""Triaxial calibration (calibration/): the cell reaches and holds the confining stress on every
wall, the misfit is zero on the data itself, fit.py runs end to end on a tiny sample with a
2-evaluation budget, and bad input gives a clear message naming the option with no report left.

Tiny sample: a 25 x 25 x 50 mm cell (260 grains of the ten sand sizes); its walls loosen the
packing, so it is prepared at void ratio 0.80 +/- 0.03 rather than the 0.68 of the real cell."""
import csv
import importlib.util
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import lmprun

CAL = lmprun.ROOT / "calibration"
SIGMA3 = 2e5
TINY = {"W": 0.025, "H": 0.05}
TINY_ARGS = ["--width", "0.025", "--height", "0.05", "--void-ratio", "0.8", "--e-tol", "0.03",
             "--strain", "0.02", "--jobs", "1"]


def load_fit():
    spec = importlib.util.spec_from_file_location("fit", CAL / "fit.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.fixture(scope="module")
def cell(tmp_path_factory):
    """A tiny sample consolidated at 0.2 MPa and sheared to 3 % axial strain."""
    d = tmp_path_factory.mktemp("cell")
    common = dict(TINY, tbags=lmprun.ROOT, sigma3=SIGMA3)
    prep = lmprun.run(CAL / "in.triax_prep", d, variables=dict(common, mu_prep=0.15, out="p.restart")).check()
    (d / "prep.out").write_text(prep.output)
    res = lmprun.run(CAL / "in.triax", d, variables=dict(common, prep="p.restart", strain=0.03)).check()
    return d, res.output


def test_cell_reaches_the_confining_stress_on_every_wall(cell):
    d, out = cell
    # the deck's summaries for the tools (fit.py reads them) agree with its printed lines
    cons = json.loads((d / "consolidated.json").read_text())
    walls = cons["walls_Pa"]
    printed = [float(x) for x in [l for l in out.splitlines() if l.startswith("WALLS:")][0].split()[1:]]
    assert walls == pytest.approx(printed, abs=0.006)
    prep = json.loads((d / "prep.json").read_text())
    assert prep["sigma3_Pa"] == SIGMA3 and 0.3 < prep["void_ratio"] < 1.5
    assert json.loads((d / "shear.json").read_text())["inertial_number"] > 0
    print("wall stresses after consolidation (Pa):", walls)
    assert len(walls) == 6
    for s in walls:
        assert abs(s / SIGMA3 - 1) < 0.01


def test_lateral_walls_hold_the_confining_stress_while_the_axial_walls_move(cell):
    d, out = cell
    a = np.loadtxt(d / "triax.csv", delimiter=",", comments="#", skiprows=1)
    lateral = a[1:, 10:14] / SIGMA3 - 1          # sxlo sxhi sylo syhi, every 0.1 % of axial strain
    print("lateral wall stress error: max %.3f %%, mean %.3f %%; axial strain %.2f %%, ratio %.3f"
          % (100 * np.abs(lateral).max(), 100 * np.abs(lateral).mean(), a[-1, 0], a[:, 3].max()))
    assert a[-1, 0] > 2.9                          # the axial walls moved (3 % strain)
    assert a[:, 3].max() > 1.3                     # and loaded the sample
    assert np.abs(lateral).mean() < 0.01           # the servo holds sigma3 within 1 % on average
    assert np.abs(lateral).max() < 0.02            # and within 2 % at every output
    assert "inertial number 1.000e-03" not in out  # deck default is I = 5e-4
    assert "inertial number 5.000e-04" in out


def test_stiff_grains_keep_the_servos_steady(tmp_path):
    """E 7.2 GPa (dt 1e-6 s): the lateral gains fall as (1.8 GPa / E)^(1/3) (gains.inc), and the
    tiny cell consolidates to sigma3 within 1 % on every wall and holds it while shearing (mean
    under 1 %, every output under 2 %). With the 1.8 GPa gains the walls missed sigma3 by 20 % after
    re-consolidation and by 38 % while shearing (the servos oscillate on the stiffer packing)."""
    common = dict(TINY, tbags=lmprun.ROOT, sigma3=SIGMA3, E=7.2e9, dt=1e-6)
    lmprun.run(CAL / "in.triax_prep", tmp_path, variables=dict(common, mu_prep=0.15, out="p.restart")).check()
    res = lmprun.run(CAL / "in.triax", tmp_path, variables=dict(common, prep="p.restart", strain=0.03)).check()
    assert "(x 0.630 for E " in res.output
    walls = json.loads((tmp_path / "consolidated.json").read_text())["walls_Pa"]
    a = np.loadtxt(tmp_path / "triax.csv", delimiter=",", comments="#", skiprows=1)
    lateral = a[1:, 10:14] / SIGMA3 - 1
    print("E 7.2 GPa: walls after consolidation %s Pa; lateral error while shearing mean %.3f %%, max %.3f %%"
          % (walls, 100 * np.abs(lateral).mean(), 100 * np.abs(lateral).max()))
    assert all(abs(w / SIGMA3 - 1) < 0.01 for w in walls)
    assert np.abs(lateral).mean() < 0.01 and np.abs(lateral).max() < 0.02


@pytest.fixture(scope="module")
def pcell(tmp_path_factory):
    """The tiny sample in the periodic cell, consolidated at 0.2 MPa and sheared to 3 %."""
    d = tmp_path_factory.mktemp("pcell")
    common = dict(TINY, tbags=lmprun.ROOT, sigma3=SIGMA3)
    prep = lmprun.run(CAL / "in.triax_prep_periodic", d, variables=dict(common, mu_prep=0.15, out="p.restart")).check()
    res = lmprun.run(CAL / "in.triax_periodic", d, variables=dict(common, prep="p.restart", strain=0.03)).check()
    return d, prep.output + res.output


def test_periodic_cell_holds_the_confining_stress_while_it_shortens(pcell):
    """in.triax_prep_periodic consolidates to sigma3 in x, y, z (0.5 %); while in.triax_periodic
    shortens the box, its lateral servo holds sigma3 within 1 % on average and 2 % at every
    output, as the walled cell's plates (a press/berendsen barostat lagged by 110 % here, the
    servo without its integral term by 1.3 % on average)."""
    d, out = pcell
    prep = json.loads((d / "prep.json").read_text())
    assert all(abs(s / SIGMA3 - 1) < 0.01 for s in prep["stresses_Pa"]), prep
    assert "converged 1" in [l for l in out.splitlines() if l.startswith("PREP:")][0]
    a = np.loadtxt(d / "triax.csv", delimiter=",", comments="#", skiprows=1)
    lateral = a[1:, 6:8] / SIGMA3 - 1              # sx sy, every 0.1 % of axial strain
    print("periodic cell: lateral stress error max %.3f %%, mean %.3f %%; axial strain %.2f %%, ratio %.3f, "
          "void ratio %.4f" % (100 * np.abs(lateral).max(), 100 * np.abs(lateral).mean(), a[-1, 0],
                               a[:, 3].max(), prep["void_ratio"]))
    assert a[-1, 0] > 2.9 and a[:, 3].max() > 1.3
    assert np.abs(lateral).mean() < 0.01
    assert np.abs(lateral).max() < 0.02
    assert "periodic cell" in out and "inertial number 5.000e-04" in out


def test_misfit_is_zero_on_the_data_itself():
    fit = load_fit()
    data = fit.load_data(CAL / "data", [0.5])[0.5][1]
    curve = {"eps_a_pct": data[:, 0], "ratio": data[:, 1], "eps_v_pct": data[:, 2]}
    assert fit.misfit_one(curve, data)[0] == pytest.approx(0.0, abs=1e-12)
    curve["ratio"] = data[:, 1] * 1.1
    assert fit.misfit_one(curve, data)[0] > 0.01


def run_fit(args, tmp_path, env=None):
    e = dict(os.environ)
    e.update(env or {})
    cmd = [sys.executable, str(CAL / "fit.py"), "--workdir", str(tmp_path / "work"),
           "--out", str(tmp_path / "report")] + args
    return subprocess.run(cmd, capture_output=True, text=True, env=e, cwd=tmp_path)


def test_fit_runs_end_to_end_on_a_tiny_sample(tmp_path):
    # 0.3 MPa is not in the data: the fit runs and says which curve it compares with
    res = run_fit(TINY_ARGS + ["--pressures", "0.3", "--budget", "2", "--grid-mu", "0.5",
                               "--grid-mur", "0.1"], tmp_path)
    print(res.stdout[-3000:], res.stderr[-3000:])
    assert res.returncode == 0
    assert "no data at sigma3 = 0.3 MPa: compared with the nearest curve, Test_0.2.data" in res.stdout
    rep = tmp_path / "report"
    text = (rep / "report.md").read_text()
    assert "Test_0.2.data" in text and "| best |" in text
    rows = (rep / "runs.csv").read_text().splitlines()
    assert len(rows) == 3                          # header + 2 evaluations
    assert (rep / "triaxial.png").stat().st_size > 10000
    # resumable: a second call finds both evaluations in the cache and runs no deck
    again = run_fit(TINY_ARGS + ["--pressures", "0.3", "--budget", "2", "--grid-mu", "0.5",
                                 "--grid-mur", "0.1"], tmp_path)
    assert again.returncode == 0 and "run mu" not in again.stdout and "sample" not in again.stdout


def test_conventions_reach_the_deck_and_the_report(tmp_path):
    """--rolling-radius mean (and --twisting sds): in.triax runs pair_style ... rolling_radius mean
    (twisting sds; its log says so), the report states the convention, and the run is not the
    cache's effective-radius run."""
    args = TINY_ARGS + ["--pressures", "0.2", "--budget", "1", "--mu", "0.5", "--mur", "0.1", "--no-figure"]
    eff = run_fit(args, tmp_path)
    assert eff.returncode == 0, eff.stdout[-2000:] + eff.stderr[-2000:]
    mean = run_fit(args + ["--rolling-radius", "mean", "--replace"], tmp_path)    # (another search: same --out)
    assert mean.returncode == 0, mean.stdout[-2000:] + mean.stderr[-2000:]
    assert "run mu 0.5 mur 0.1" in mean.stdout    # not taken from the cache
    runs = json.loads((tmp_path / "work" / "evaluations.json").read_text())
    logs = {k: (Path(r["csv"]).parent / "in.triax.out").read_text() for k, r in runs.items()}
    assert sorted("rolling radius mean (Ri+Rj)/2" in t for t in logs.values()) == [False, True]
    assert "with the mean rolling radius" in (tmp_path / "report" / "report.md").read_text()
    bad = run_fit(args + ["--rolling-radius", "twice"], tmp_path)
    assert bad.returncode != 0 and "--rolling-radius" in bad.stderr
    # --twisting sds: the deck's pair style twists (its log), with the coefficients the report gives
    tw = run_fit(args + ["--twisting", "sds", "--replace"], tmp_path)
    assert tw.returncode == 0, tw.stdout[-2000:] + tw.stderr[-2000:]
    assert "run mu 0.5 mur 0.1" in tw.stdout
    runs = json.loads((tmp_path / "work" / "evaluations.json").read_text())
    logs = [(Path(r["csv"]).parent / "in.triax.out").read_text() for r in runs.values()]
    assert sorted("; twisting sds" in t for t in logs) == [False, False, True]
    report = (tmp_path / "report" / "report.md").read_text()
    assert "Twisting resistance: sds" in report and "0.2 MPa: k_tw" in report


def test_periodic_cell_reaches_the_fit_and_the_report(tmp_path):
    """--cell periodic: fit.py prepares and shears with the periodic decks (their logs say so),
    the report names the cell, and the walled runs' cache is not served for it."""
    args = ["--width", "0.025", "--height", "0.05", "--void-ratio", "0.6", "--e-tol", "0.05",
            "--strain", "0.02", "--jobs", "1", "--pressures", "0.2", "--budget", "1", "--no-figure"]
    res = run_fit(args + ["--cell", "periodic"], tmp_path)
    assert res.returncode == 0, res.stdout[-2000:] + res.stderr[-2000:]
    runs = json.loads((tmp_path / "work" / "evaluations.json").read_text())
    assert len(runs) == 1 and all("_periodic_" in k for k in runs)
    log = (Path(list(runs.values())[0]["csv"]).parent / "in.triax_periodic.out").read_text()
    assert "periodic cell" in log
    assert "Cell: periodic, stress-controlled" in (tmp_path / "report" / "report.md").read_text()
    bad = run_fit(args + ["--cell", "cylinder"], tmp_path)
    assert bad.returncode != 0 and "--cell" in bad.stderr


def test_bracket_tabulates_the_readings(tmp_path):
    """--bracket R1,R2: one row per reading (named from each report's options.json) with the
    numbers of its runs.csv; a directory without a report is refused by name, and nothing runs."""
    args = TINY_ARGS + ["--pressures", "0.2", "--budget", "1", "--no-figure"]
    for out, extra in (("r1", []), ("r2", ["--rolling-radius", "mean"])):
        res = run_fit(args + extra + ["--out", str(tmp_path / out)], tmp_path)
        assert res.returncode == 0, res.stdout[-2000:] + res.stderr[-2000:]
    res = run_fit(["--pressures", "0.2", "--bracket", "%s,%s" % (tmp_path / "r1", tmp_path / "r2"),
                   "--out", str(tmp_path / "b")], tmp_path, env={"TBAGS_LMP": ""})
    assert res.returncode == 0, res.stdout[-2000:] + res.stderr[-2000:]
    table = (tmp_path / "b" / "bracket.md").read_text()
    rows = [l for l in table.splitlines() if l.startswith("| effective") or l.startswith("| mean")]
    assert [r.split(" |")[0] for r in rows] == ["| effective radius, twisting none, walled cell",
                                                "| mean radius, twisting none, walled cell"]
    for out, row in zip(("r1", "r2"), rows):
        with open(tmp_path / out / "runs.csv", newline="") as fh:
            first = next(csv.DictReader(fh))
        assert "%.2f" % float(first["peak_sim_0.2"]) == row.split(" | ")[3]
        assert "%.2f" % float(first["contraction_0.2"]) == row.split(" | ")[5]
    bad = run_fit(["--pressures", "0.2", "--bracket", str(tmp_path / "nowhere")], tmp_path)
    assert bad.returncode != 0 and "nowhere" in bad.stderr and "--budget 1" in bad.stderr


def test_mean_curve_of_samples():
    import importlib
    sys.path.insert(0, str(CAL))
    misfit = importlib.import_module("tbagscal.misfit")
    a = {"eps_a_pct": np.array([0.0, 1.0, 2.0, 3.0]), "ratio": np.array([1.0, 2.0, 3.0, 4.0])}
    b = {"eps_a_pct": np.array([0.0, 0.5, 1.0, 1.5, 2.0]), "ratio": np.array([1.0, 1.0, 1.0, 1.0, 5.0])}
    m = misfit.mean_curve([a, b])
    assert list(m["eps_a_pct"]) == [0.0, 0.5, 1.0, 1.5, 2.0]     # the shortest curve's strains
    assert list(m["ratio"]) == [1.0, 1.25, 1.5, 1.75, 4.0]
    assert misfit.mean_curve([a]) is a


def test_time_step_follows_the_grain_stiffness(tmp_path):
    """Stiffer grains than the paper's get dt sqrt(1.8 GPa / E) (the same fraction of the Rayleigh
    step), softer ones --dt; the samples' cache key carries the step used."""
    fit = load_fit()
    a = fit.parse_args(["--dt", "2e-6", "--workdir", str(tmp_path)])
    cal = fit.Calibration(a)
    assert cal.dt(1.8e9) == pytest.approx(2e-6)
    assert cal.dt(7.2e9) == pytest.approx(1e-6)
    assert cal.dt(0.9e9) == pytest.approx(2e-6)
    assert cal.cell_vars(18e9)["dt"] == "%.6g" % (2e-6 / 10 ** 0.5)
    assert "_dt1e-06_" in cal.prep_key(0.2, 7.2e9)


def test_fit_with_several_samples_per_pressure(tmp_path):
    """--seeds 2: two packings per pressure (different peaks), the misfit and the report's curve
    are those of their mean curve, and the peak's spread is reported (into a report directory
    whose parent does not exist yet)."""
    rep = tmp_path / "new" / "report"
    res = run_fit(TINY_ARGS + ["--pressures", "0.2", "--budget", "1", "--mu", "0.5", "--mur", "0.1",
                               "--seeds", "2", "--no-figure", "--out", str(rep)], tmp_path)
    assert res.returncode == 0, res.stdout[-2000:] + res.stderr[-2000:]
    assert "(seed 7331)" in res.stdout and "(seed 7332)" in res.stdout
    runs = json.loads((tmp_path / "work" / "evaluations.json").read_text())
    assert len(runs) == 2
    fit = load_fit()
    import importlib
    misfit = importlib.import_module("tbagscal.misfit")
    each = [misfit.read_curve(r["csv"]) for r in runs.values()]
    assert not np.allclose(each[0]["ratio"][:5], each[1]["ratio"][:5])   # two packings
    grid = min(each, key=lambda c: c["eps_a_pct"][-1])["eps_a_pct"]    # the mean, by hand
    mean = {n: grid if n == "eps_a_pct" else 0.5 * (np.interp(grid, each[0]["eps_a_pct"], each[0][n])
                                                    + np.interp(grid, each[1]["eps_a_pct"], each[1][n]))
            for n in each[0]}
    data = fit.load_data(CAL / "data", [0.2])[0.2][1]
    import csv as csvmod
    row = next(csvmod.DictReader(open(rep / "runs.csv")))
    assert float(row["J"]) == pytest.approx(misfit.misfit_one(mean, data)[0], rel=1e-5)
    peaks = [c["ratio"].max() for c in each]
    assert float(row["peak_sim_0.2"]) == pytest.approx(np.mean(peaks), rel=1e-5)
    assert float(row["peak_sd_0.2"]) == pytest.approx(np.std(peaks, ddof=1), rel=1e-4)
    assert float(row["peak_sd_0.2"]) > 0
    written = misfit.read_curve(rep / "curve_best_0.2MPa.csv")
    assert np.allclose(written["ratio"], mean["ratio"], rtol=1e-5)
    assert "Samples per pressure: 2 (seeds 7331, 7332)" in (rep / "report.md").read_text()


def test_contraction_study_on_a_tiny_sample(tmp_path):
    """--study with one seed and no other variant: the packing's limits bracket the sample's void
    ratio, the seed's row and the spread table are written; without the fit's runs.csv it stops
    with a message naming the file."""
    rep = tmp_path / "report"
    res = run_fit(TINY_ARGS + ["--pressures", "0.2", "--study"], tmp_path)
    assert res.returncode == 2 and "--study needs" in res.stderr and "runs.csv" in res.stderr
    rep.mkdir()
    (rep / "runs.csv").write_text("n,mu,mur,E,J\n1,0.5,0.1,1.8e9,0.3\n2,0.6,0.1,1.8e9,0.2\n")
    fit = load_fit()
    import importlib
    study = importlib.import_module("tbagscal.study")
    study.SEEDS, study.E_FACTORS, study.VOID_RATIOS, study.FRICTIONS = (7331,), (), (), ()
    a = fit.parse_args(TINY_ARGS + ["--pressures", "0.2", "--study", "--no-figure",
                                    "--workdir", str(tmp_path / "work"), "--out", str(rep)])
    cal = fit.Calibration(a)
    study.run_study(cal, fit.load_data(a.data, a.pressures), rep)
    text = (rep / "contraction-study.md").read_text()
    print(text)
    import csv as csvmod
    rows = list(csvmod.DictReader(open(rep / "contraction-study.csv")))
    assert len(rows) == 1 and rows[0]["case"] == "seed 7331" and float(rows[0]["mu"]) == 0.6
    lim = [l for l in text.splitlines() if l.startswith("| 0.2 |")][0].split("|")
    emin, emax, e0 = float(lim[2]), float(lim[3]), float(rows[0]["e0"])
    assert emin < e0 < emax and 0 < float(rows[0]["Dr"]) < 1
    assert float(rows[0]["contraction"]) > 0 and "| seed | seed 7331 | 0.2 |" in text


def test_fit_recovers_a_known_friction(tmp_path):
    """A synthetic target made by the deck itself (the tiny sample at 0.2 MPa with mu = 0.6,
    written as a data set with its manifest), then a fit of mu from 0.3 with 8 evaluations (grid
    0.45, 0.75, then Nelder-Mead): the search converges, the best mu is within 0.05 of 0.6 and
    its misfit under a tenth of the start's."""
    import csv
    import hashlib
    common = TINY_ARGS + ["--pressures", "0.2", "--fit", "mu", "--mur", "0.05", "--grid-mur", "0.05"]
    made = run_fit(common + ["--mu", "0.6", "--budget", "1", "--grid-mu", "0.6", "--no-figure"], tmp_path)
    assert made.returncode == 0, made.stdout[-2000:] + made.stderr[-2000:]
    runs = json.loads((tmp_path / "work" / "evaluations.json").read_text())
    assert len(runs) == 1
    curve = np.genfromtxt(next(iter(runs.values()))["csv"], delimiter=",", names=True, comments="#")
    data = tmp_path / "synthetic"
    data.mkdir()
    rows = np.column_stack([curve["eps_v_pct"], 0 * curve["ratio"], 0 * curve["ratio"],
                            curve["eps_a_pct"], curve["ratio"]])[1:]
    np.savetxt(data / "Synthetic_0.2.data", rows, header="e_v e_x e_y e_z s33/s11 (%): in.triax at mu 0.6")
    digest = hashlib.sha256((data / "Synthetic_0.2.data").read_bytes()).hexdigest()
    with open(data / "manifest.csv", "w", newline="") as fh:
        csv.writer(fh).writerows([["sigma3_MPa", "file", "sha256"], ["0.2", "Synthetic_0.2.data", digest]])
    res = run_fit(common + ["--mu", "0.3", "--budget", "8", "--grid-mu", "0.45,0.75", "--data", str(data),
                            "--no-figure", "--replace"], tmp_path)
    print(res.stdout[-3000:])
    assert res.returncode == 0, res.stderr[-2000:]
    found = [l for l in res.stdout.splitlines() if l.startswith("fit.py: evaluation ")]
    J = {float(l.split(" mu ")[1].split()[0]): float(l.split("misfit")[1]) for l in found}
    best = min(J, key=J.get)
    print("evaluations (mu: misfit): %s; best mu %.4f" % (sorted(J.items()), best))
    assert len(J) >= 6 and abs(best - 0.6) < 0.05 and J[best] < 0.1 * J[0.3]


def no_report(tmp_path):
    return not (tmp_path / "report").exists() or not any((tmp_path / "report").iterdir())


@pytest.mark.parametrize("args,message", [
    (["--mu", "-0.1"], "--mu -0.1: sliding friction must be in [0, 1.5]"),
    (["--mur", "0.9"], "--mur 0.9: rolling friction (dimensionless) must be in [0, 0.5]"),
    (["--E", "0"], "--E 0: grain Young's modulus (Pa) must be in"),
    (["--pressures", "0.2,-1"], "--pressures 0.2,-1.0: each confining stress must be in (0, 50] MPa"),
    (["--void-ratio", "2"], "--void-ratio 2: void ratio must be in"),
    (["--fit", "mu,k"], "--fit mu,k: choose among mu, mur, E"),
    (["--seeds", "0"], "--seeds 0: between 1 and 20 samples per pressure"),
])
def test_parameter_outside_its_range(tmp_path, args, message):
    res = run_fit(TINY_ARGS + args, tmp_path)
    assert res.returncode == 2
    assert message in res.stderr, res.stderr
    assert no_report(tmp_path)


def test_missing_data_file(tmp_path):
    data = tmp_path / "data"
    shutil.copytree(CAL / "data", data)
    (data / "Test_0.5.data").unlink()
    res = run_fit(TINY_ARGS + ["--data", str(data)], tmp_path)
    assert res.returncode == 2
    assert "--data %s: data file Test_0.5.data (sigma3 0.5 MPa, listed in manifest.csv) is missing" % data \
        in res.stderr, res.stderr
    assert no_report(tmp_path)


def test_sample_that_cannot_reach_the_void_ratio(tmp_path):
    args = [a for a in TINY_ARGS]
    args[args.index("--void-ratio") + 1] = "0.5"
    res = run_fit(args + ["--pressures", "0.2", "--budget", "1"], tmp_path)
    print(res.stdout, res.stderr)
    assert res.returncode == 2
    assert "--void-ratio 0.5: the sample cannot reach this void ratio at 0.2 MPa" in res.stderr
    assert no_report(tmp_path)


def test_lammps_not_found(tmp_path):
    res = run_fit(TINY_ARGS, tmp_path, env={"TBAGS_LMP": ""})
    assert res.returncode == 2
    assert "TBAGS_LMP is not set" in res.stderr
    assert no_report(tmp_path)
