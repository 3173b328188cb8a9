"""Isolator models (postprocess/tbagspost/isolator.py) and the designer's properties (design.py)
on loops whose answers are known: each model recovers its own parameters from its own loops, the
extended Masing rules close inner loops, Phillips and Hashash's loop dissipates F times Masing's
energy, the properties of a bilinear loop are its own, and the modification factors are ratios."""
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "postprocess"))
from tbagspost import design, isolator as iso  # noqa: E402

AMPS = (0.25, 0.5, 1, 2, 3, 5)


def lanes_of(model, amps=AMPS, n=200):
    """Two sine cycles per amplitude from rest; the second is compared."""
    th = 2 * np.pi * np.arange(2 * n) / n
    u = [a * np.sin(th) for a in amps]
    return iso.Lanes(u=u, S=[model.simulate(x) for x in u], start=[n] * len(amps))


def close(fitted, true, rel):
    for k, v in true.params().items():
        assert fitted.params()[k] == pytest.approx(v, rel=rel), k


@pytest.mark.parametrize("true,fit", [
    (iso.Bilinear(K_u=500.0, Q_d=100.0, K_d=20.0), iso.fit_bilinear),
    (iso.BoucWen(K=500.0, a=0.05, D_y=0.3, n=1.5, b=0.6), iso.fit_bouc_wen),
    (iso.MasingRO(K0=520.0, S_y=300.0, r=4.0), iso.fit_masing),
])
def test_a_model_recovers_its_own_parameters(true, fit):
    f = fit(lanes_of(true))
    print(true.name, {k: "%.6g" % v for k, v in f.model.params().items()}, "rms %.1e" % f.rms_S)
    close(f.model, true, 0.01)
    assert f.rms_S < 1e-3 and f.worst_K < 1e-3 and f.worst_h < 1e-3


def test_reduced_masing_recovers_backbone_and_reduction():
    true = iso.MasingROF(K0=520.0, S_y=300.0, r=4.0, p1=1.0, p2=0.6, p3=1.5)
    lanes = lanes_of(true)
    f = iso.fit_reduced(lanes, iso.fit_masing(lanes).model)
    print({k: "%.6g" % v for k, v in f.model.params().items()})
    close(f.model, true, 0.01)


def test_reduced_loop_dissipates_F_times_masing():
    """Phillips and Hashash: the steady loop of amplitude u_m has h = F(u_m) h_Masing, and closes at
    its tips (K_eq the same as Masing's)."""
    rof = iso.MasingROF(K0=520.0, S_y=300.0, r=4.0, p1=0.9, p2=0.6, p3=1.5)
    masing = iso.MasingRO(K0=520.0, S_y=300.0, r=4.0)
    for a, d, m in zip(AMPS, lanes_of(rof).measures(), lanes_of(masing).measures()):
        F = float(rof.F(a)[0])
        assert d.h_eq == pytest.approx(F * m.h_eq, rel=2e-3, abs=1e-5)
        assert d.K_eq == pytest.approx(m.K_eq, rel=1e-3)


def test_masing_steady_loop_matches_closed_form_damping():
    ro = iso.MasingRO(K0=520.0, S_y=300.0, r=4.0)
    for a, d in zip(AMPS, lanes_of(ro).measures()):
        assert d.h_eq == pytest.approx(float(ro.ro.damping(ro.ro.S(a))[0]), rel=5e-3, abs=1e-5)


def test_extended_masing_closes_inner_loops():
    """Load to 3, unload to 1 (an inner reversal), reload to 2, back to 1.5, then on to 3 and 4: after
    the inner loop closes the path follows the branch it interrupted, and past 3 the backbone."""
    ro = iso.MasingRO(K0=520.0, S_y=300.0, r=4.0)
    seg = lambda a, b: np.linspace(a, b, 301)[1:]  # noqa: E731
    reload = np.linspace(1.0, 4.0, 601)[1:]          # u = 2.5 is on it (k = 300)
    u = np.concatenate([[0.0], seg(0, 3), seg(3, 1), seg(1, 2), seg(2, 1.5), reload[reload > 1.5]])
    plain = np.concatenate([[0.0], seg(0, 3), seg(3, 1), reload])
    S, P = ro.simulate(u), ro.simulate(plain)
    assert u.max() == plain.max()                      # the same backbone table
    i, j = np.flatnonzero(np.isclose(u, 2.5))[-1], np.flatnonzero(np.isclose(plain, 2.5))[-1]
    assert S[i] == pytest.approx(P[j], rel=1e-12)
    assert S[-1] == pytest.approx(ro.backbone_fn(1.01 * 4.0)(4.0), rel=1e-12)
    # and the inner loop really left the branch (S differs there)
    k = np.flatnonzero(np.isclose(u, 1.75))
    assert abs(S[k[-1]] - P[np.flatnonzero(np.isclose(plain, 1.75))[-1]]) > 1.0


def test_slider_in_series_is_rigid_plastic_with_the_bags_in_front():
    """A slider of strength 20 N behind two linear bags of 400 N/mm each (a bilinear without
    yield): the loop is a parallelogram with Q_d = 20 N, elastic stiffness 200 N/mm, K_d = 0."""
    bag = iso.Bilinear(K_u=400.0, Q_d=1e9, K_d=0.0)
    lanes = lanes_of(iso.Slider(bag=bag, mu_N=20.0, bags=2), amps=(2.0,), n=400)
    u, S = lanes.last(0, lanes.u[0]), lanes.last(0, lanes.S[0])
    p = design.properties(u, S)
    assert p.Q_d == pytest.approx(20.0, rel=1e-6)
    assert abs(p.K_d) < 0.05 and p.D_y == pytest.approx(0.1, rel=0.02)
    assert np.abs(S).max() == pytest.approx(20.0, rel=1e-9)


@pytest.mark.parametrize("amp", [0.25, 1.0, 3.0])
def test_an_elastic_slider_behind_bags_is_their_series_spring(amp):
    """k_slip 1000 N/mm in series with two bags of 400 N/mm: an elastic stiffness of
    1 / (2/400 + 1/1000) = 166.7 N/mm up to 20 N (D_y 0.12 mm), then slip: the loop's D_y and
    damping are the elastic-perfectly-plastic ones, h = (2/pi)(1 - D_y/D)."""
    bag = iso.Bilinear(K_u=400.0, Q_d=1e9, K_d=0.0)
    lanes = lanes_of(iso.Slider(bag=bag, mu_N=20.0, bags=2, k_slip=1000.0), amps=(amp,), n=800)
    u, S = lanes.last(0, lanes.u[0]), lanes.last(0, lanes.S[0])
    p = design.properties(u, S)
    d_y = 20.0 / (1.0 / (2 / 400.0 + 1 / 1000.0))
    assert p.D_y == pytest.approx(d_y, rel=0.02)
    assert p.beta_eff == pytest.approx(2 / np.pi * (1 - d_y / amp), rel=0.02, abs=2e-3)
    assert np.abs(S).max() == pytest.approx(20.0, rel=1e-9)


def test_bilinear_loop_properties_are_its_own():
    """ASCE/AASHTO properties of a bilinear loop (vertices exact: sampled finely): k_eff = K_eq,
    beta_eff = h_eq (to 1e-6), and Q_d, K_d, D_y those of the model."""
    m = iso.Bilinear(K_u=500.0, Q_d=100.0, K_d=20.0)
    lanes = lanes_of(m, amps=(2.0,), n=20000)
    u, S = lanes.last(0, lanes.u[0]), lanes.last(0, lanes.S[0])
    p = design.properties(u, S)
    print(p)
    assert p.k_eff == pytest.approx(p.K_eq, rel=1e-6) and p.beta_eff == pytest.approx(p.h_eq, rel=1e-6)
    assert p.Q_d == pytest.approx(100.0, rel=1e-6)
    assert p.K_d == pytest.approx(20.0, rel=1e-3) and p.D_y == pytest.approx(m.D_y, rel=1e-3)
    assert p.k_eff == pytest.approx(m.Q_d / 2.0 + m.K_d, rel=1e-6)


def test_recommend_prefers_the_model_within_tolerances():
    lanes = lanes_of(iso.MasingRO(K0=520.0, S_y=300.0, r=4.0))
    fits = iso.fit_all(lanes)
    best, why = iso.recommend(fits)
    print(why)
    assert best.model.name.startswith("R-O") and "within" in why


def test_lambdas_are_ratios_to_the_mean_of_the_cycles():
    def props(k):
        return design.Properties(D=1, k_eff=k, beta_eff=0.2, E_loop=1, Q_d=10, K_d=5, D_y=0.1, K_u=50,
                                 K_eq=k, h_eq=0.2)
    table = {(1, 1): props(110.0), (1, 2): props(100.0), (1, 3): props(90.0)}
    slow = {(1, 3): props(81.0)}
    lam = design.lambdas(table, slow, [{(1, 3): props(100.0)}])
    assert lam[1]["k_eff"]["cycles"] == pytest.approx((0.9, 1.1))
    assert lam[1]["k_eff"]["rate"] == pytest.approx((0.9, 1.0))
    assert lam[1]["k_eff"]["fills"] == pytest.approx((90 / 95, 100 / 95))
    assert lam[1]["k_eff"]["combined"] == pytest.approx((0.9 * 0.9 * 90 / 95, 1.1 * 1.0 * 100 / 95))
    assert lam[1]["beta_eff"]["cycles"] == pytest.approx((1.0, 1.0))


def test_properties_refuse_a_non_finite_loop():
    with pytest.raises(ValueError, match="non-finite"):
        design.properties([0, 1, 0, -1], [0, 1, np.nan, -1])


# ---- a history the fit never saw (tbagspost/history.py) ---------------------------------------
def irregular_history():
    """inputs/histories/make_irregular.py's history at 2 ms rows (u mm, t s)."""
    import importlib.util
    spec = importlib.util.spec_from_file_location(
        "make_irregular", Path(__file__).resolve().parents[2] / "inputs" / "histories" / "make_irregular.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    t, u = mod.history()
    return t[1::2], u[1::2]


def write_history(path, model, fv=318.0):
    """history.csv of `model` driven along the irregular history (from rest at u = 0)."""
    t, u = irregular_history()
    S = model.simulate(np.r_[0.0, u])[1:]
    path.mkdir(parents=True, exist_ok=True)
    with open(path / "history.csv", "w") as fh:
        fh.write("time_s,th_s,chunk,u_mm,w_mm,S_N,Fv_N\n# rows\n")
        for k in range(len(t)):
            fh.write("%.7f,%.7f,1,%.9f,0,%.9f,%g\n" % (10 + t[k], t[k], u[k], S[k], fv))
    return path


def test_work_of_a_coulomb_loop_is_four_F_times_the_amplitude():
    from tbagspost import history
    u = np.r_[np.linspace(0, 2, 50), np.linspace(2, -2, 100)[1:], np.linspace(-2, 0, 50)[1:]]
    S = np.where(np.gradient(u) >= 0, 30.0, -30.0)
    S[0] = 0.0                              # at rest before the first row
    assert history.work(u[1:], S[1:]) == pytest.approx(4 * 30.0 * 2, rel=0.02)


def test_history_check_is_exact_for_the_model_that_made_it(tmp_path):
    from tbagspost import history
    true = iso.MasingRO(K0=520.0, S_y=300.0, r=4.0)
    run = history.HistoryRun(write_history(tmp_path / "h", true))
    rows = history.compare(run, [("same", true), ("bilinear", iso.Bilinear(K_u=500.0, Q_d=150.0, K_d=40.0))])
    dem, same, bil = rows
    print([(r["model"], r["rms_of_peak"], r["W_ratio"]) for r in rows])
    assert dem["W_mJ"] > 0 and same["rms_of_peak"] < 1e-9 and same["W_ratio"] == pytest.approx(1, abs=1e-9)
    assert bil["rms_of_peak"] > 0.05 and abs(bil["W_ratio"] - 1) > 0.05
    # the figure and the section
    assert "| same | 0.0 % |" in "\n".join(history.section(run, rows, "one bag"))
    history.figure(run, rows)


def test_history_reader_drops_a_cut_last_row_and_names_a_bad_one(tmp_path):
    """The history's rows are read as cyclic.csv's (tbagspost.finite_rows): a last row an
    interrupted run left non-finite is dropped, a non-finite row inside stops with its number."""
    from tbagspost import history
    h = write_history(tmp_path / "h", iso.MasingRO(K0=520.0, S_y=300.0, r=4.0))
    f = h / "history.csv"
    lines = f.read_text().splitlines()
    n = len(lines) - 2
    f.write_text("\n".join(lines + ["4.1,4.1,1,nan,0,nan,318"]) + "\n")
    assert len(history.HistoryRun(h).csv) == n
    lines[100] = lines[100].split(",", 5)[0] + ",0.1,1,0.5,0,nan,318"
    f.write_text("\n".join(lines) + "\n")
    with pytest.raises(SystemExit, match=r"data row 99 \(history time 0.1 s\) has no finite S_N"):
        history.HistoryRun(h)


def test_history_on_the_command_line(tmp_path, capsys):
    """Cyclic runs of known Masing loops (test_cyclic_post) and a history of the same model: the
    R-O/Masing fit predicts the history within 2 % of its peak; history_check.csv is written."""
    from test_cyclic_post import TRUE, write_run
    from tbagspost import cli, history
    run = write_run(tmp_path / "F5500")
    h = write_history(tmp_path / "H5500", iso.MasingRO(K0=TRUE.K0, S_y=TRUE.S_y, r=TRUE.r))
    assert cli.main([str(run), "--history", str(h), "-o", str(tmp_path / "out")]) == 0
    rows = list(csv_rows(tmp_path / "out" / "history_check.csv"))
    by = {r["model"]: r for r in rows}
    assert float(by["R-O, Masing"]["rms_of_peak"]) < 0.02
    assert (tmp_path / "out" / "history-H5500.png").is_file()
    assert "### History H5500: one bag" in (tmp_path / "out" / "isolator.md").read_text()
    # a history of a load with no cyclic run says so
    h2 = write_history(tmp_path / "H1960", iso.MasingRO(K0=TRUE.K0, S_y=TRUE.S_y, r=TRUE.r), fv=113.0)
    assert cli.main([str(run), "--history", str(h2), "-o", str(tmp_path / "out2")]) == 0
    assert "No single-bag cyclic run of this fabric at this load" in (tmp_path / "out2" / "isolator.md").read_text()
    # two histories of one name in sibling folders: a figure each, named by the folders (the
    # figure of the first was overwritten when the name came from the folder two levels up)
    same = iso.MasingRO(K0=TRUE.K0, S_y=TRUE.S_y, r=TRUE.r)
    ha = write_history(tmp_path / "runs-history" / "H5500", same)
    hb = write_history(tmp_path / "runs-history-woven" / "H5500", same)
    assert cli.main([str(run), "--history", str(ha), "--history", str(hb), "-o", str(tmp_path / "out3")]) == 0
    figs = sorted(f.name for f in (tmp_path / "out3").glob("history-*.png"))
    assert figs == ["history-runs-history-H5500.png", "history-runs-history-woven-H5500.png"], figs
    assert all(r["fabric"] == "solid" for r in csv_rows(tmp_path / "out3" / "history_check.csv"))
    assert history.figure_names(["/a/x/H1", "/b/x/H1", "/c/H2"]) == ["a-x-H1", "b-x-H1", "H2"]


def csv_rows(path):
    import csv
    with open(path) as fh:
        yield from csv.DictReader(fh)


def test_a_second_fabric_is_its_own_load_and_its_effect_is_reported(tmp_path):
    """Two runs of one load, the second on the woven fabric with S halved: not fills of one load
    but two fabrics; the report gives woven / solid = 0.5 for k_eff and Q_d, 1 for beta_eff."""
    from test_cyclic_post import write_run
    from tbagspost import cli
    a = write_run(tmp_path / "solid" / "F5500")
    b = write_run(tmp_path / "woven" / "F5500")
    with open(b / "log.cyclic", "a") as fh:
        fh.write("FABRIC: woven: a woven fabric\n")
    lines = (b / "cyclic.csv").read_text().splitlines()
    for i, line in enumerate(lines):
        if i and not line.startswith("#"):
            f = line.split(",")
            f[6] = "%.6f" % (0.5 * float(f[6]))
            lines[i] = ",".join(f)
    (b / "cyclic.csv").write_text("\n".join(lines) + "\n")
    assert cli.main([str(a), str(b), "-o", str(tmp_path / "out")]) == 0
    md = (tmp_path / "out" / "isolator.md").read_text()
    assert "F_v = 318 N, fabric woven (F5500)" in md and "F_v = 318 N, fabric solid (F5500)" in md
    assert "Not measured for this load: rate, fills" in md          # not each other's fills
    sec = md.split("The fabric's effect at F_v = 318 N: woven over solid")[1]
    assert "| k_eff | 0.50 - 0.50 |" in sec and "| beta_eff | 1.00 - 1.00 |" in sec
    assert "| Q_d | 0.50 - 0.50 |" in sec
