"""tbagspost pieces on hand-made inputs (no LAMMPS): u at a dump step from the CSV and the log's
time step, dump readers against known values (box origin, id order, empty dumps), clear one-line
errors for truncated, cut, foreign and missing files, the progress bar, command-line checks."""
import io
import os
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(os.environ.get("TBAGS_ROOT", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(ROOT / "postprocess"))
from tbagspost import cli, dumps  # noqa: E402
from tbagspost.progress import Progress  # noqa: E402
from tbagspost.run import Run, loops  # noqa: E402

BOX = "ITEM: BOX BOUNDS ff ff ff\n-0.02 0.06\n-0.03 0.06\n-0.01 0.065\n"
# id type radius x y z vx vy vz dx dy dz, not in id order (LAMMPS writes in rank order)
ATOMS = np.array([[3, 2, 0.003, 0.011, 0.012, 0.013, 0.1, 0.2, 0.3, 1e-3, 2e-3, 3e-3],
                  [1, 1, 0.0025, 0.0, -0.001, 0.0001, -0.1, 0.0, 0.05, 4e-4, -5e-4, 6e-4],
                  [2, 1, 0.0025, 0.005, 0.0, 0.0, 0.0, 0.01, 0.0, 0.0, 0.0, -1e-4]])


def grains_text(rows=ATOMS, count=None):
    head = "ITEM: TIMESTEP\n1500\nITEM: NUMBER OF ATOMS\n%d\n" % (len(rows) if count is None else count)
    body = "".join(" ".join("%.10g" % v for v in r) + "\n" for r in rows)
    return head + BOX + "ITEM: ATOMS " + " ".join(dumps.GRAIN_COLUMNS) + "\n" + body


def local_text(rows, columns, step=1500):
    head = "ITEM: TIMESTEP\n%d\nITEM: NUMBER OF ENTRIES\n%d\n" % (step, len(rows))
    body = "".join(" ".join("%.10g" % v for v in r) + " \n" for r in rows)
    return head + BOX + "ITEM: ENTRIES " + " ".join(columns) + "\n" + body


@pytest.fixture
def rundir(tmp_path):
    rows = ["time_s,u_mm,w_mm,S_N,Fv_N,broken_bonds,zplate_mm", "# comment"]
    rows += ["%.6f,%.4f,%.4f,%.4f,100,0,%.4f" % (0.002 + 0.001 * k, 0.1 * k, -0.01 * k, 10.0 * k, 30 - 0.01 * k)
             for k in range(11)]
    (tmp_path / "shear.csv").write_text("\n".join(rows) + "\n")
    (tmp_path / "log.shear").write_text("something\nTIMESTEP: Rayleigh 1.1e-05 s, bond 7.7e-06 s; using 2e-6 s\n")
    return tmp_path


def test_u_at_a_step_interpolates_the_csv(rundir):
    run = Run(rundir)
    assert run.dt == 2e-6
    assert run.at_step(1000) == pytest.approx(0.0)             # t = 0.002 s: first row
    assert run.at_step(1250) == pytest.approx(0.05)            # t = 0.0025 s: halfway, rows 0 and 1
    assert run.at_step(3250, "S_N") == pytest.approx(45.0)     # t = 0.0065 s
    assert run.at_step(3250, "zplate_mm") == pytest.approx(30 - 0.045)
    with pytest.raises(SystemExit, match="outside shear.csv's times"):
        run.at_step(100000)
    assert Run(rundir, dt=1e-6).at_step(3000) == pytest.approx(0.1)   # --dt wins over the log
    (rundir / "log.shear").unlink()
    with pytest.raises(SystemExit, match="--dt"):
        Run(rundir).dt


def test_grains_reader_keeps_the_box_origin_and_sorts_by_id(tmp_path):
    path = tmp_path / "dump.grains.1500"
    path.write_text(grains_text())
    g = dumps.read_grains(path)
    ref = ATOMS[np.argsort(ATOMS[:, 0])]
    assert g.step == 1500 and list(g.ids) == [1, 2, 3] and list(g.types) == [1, 1, 2]
    assert np.allclose(g.pos, ref[:, 3:6], atol=1e-9)   # MDAnalysis shifts by the box's lower bound
    assert np.allclose(g.vel, ref[:, 6:9], atol=1e-7) and np.allclose(g.disp, ref[:, 9:12])
    assert np.array_equal(g.radius, ref[:, 2]) and list(g.bag) == [True, True, False]
    assert list(g.index([3, 1])) == [2, 0]
    with pytest.raises(SystemExit, match="missing from the grains dump"):
        g.index([7])


def test_local_readers(tmp_path):
    path = tmp_path / "dump.bonds.1500"
    path.write_text(local_text([[1, 1, 2, 1, 0.005, 0.001, 2.5], [2, 2, 3, 1, 0.005, -0.001, 0.0]],
                               ["index", "id1", "id2", "btype", "dist", "strain", "tension"]))
    b = dumps.read_bonds(path)
    assert list(b["id1"]) == [1, 2] and list(b["tension"]) == [2.5, 0.0] and b["step"] == 1500
    empty = tmp_path / "dump.contacts.1500"
    empty.write_text(local_text([], ["index", "id1", "id2", "type1", "type2", "dist", "ftx", "fty", "ftz",
                                     "fn", "overlap"]))
    c = dumps.read_contacts(empty)
    assert len(c["fn"]) == 0 and c["id1"].dtype.kind == "i"


@pytest.mark.parametrize("make,message", [
    (lambda: grains_text()[:-40], r"is truncated: 3 of 3 rows, last row cut"),
    (lambda: grains_text(ATOMS[:2], count=3), r"is truncated: 2 of 3 rows"),
    (lambda: grains_text()[:120], r"is truncated: 0 of 3 rows|header is truncated"),
    (lambda: grains_text()[:50], r"header is truncated"),
    (lambda: "time_s,u_mm\n1,2\n", r"not a LAMMPS dump"),
    (lambda: grains_text().replace(" dx dy dz", " c_disp[1] c_disp[2] c_disp[3]"), r"lacks the columns dx dy dz"),
])
def test_bad_grains_dumps_stop_with_one_line(tmp_path, make, message):
    path = tmp_path / "dump.grains.1500"
    path.write_text(make())
    with pytest.raises(SystemExit, match=message) as e:
        dumps.read_grains(path)
    text = str(e.value)
    assert text.startswith("tbagspost: ") and str(path) in text and "\n" not in text


def test_missing_dump_and_run(tmp_path):
    with pytest.raises(SystemExit, match="no dump .*dump.grains.7"):
        dumps.read_grains(tmp_path / "dump.grains.7")
    with pytest.raises(SystemExit, match="no run directory"):
        Run(tmp_path / "nowhere")
    with pytest.raises(SystemExit, match="no dump.grains"):
        Run(tmp_path).step_near(1.0)


def test_progress_bar():
    out = io.StringIO()
    assert list(Progress(range(3), "VTK", stream=out)) == [0, 1, 2]
    text = out.getvalue()
    assert text.count("\n") == 1 and "VTK [" in text and "3/3" in text and "#" * 30 in text


def test_command_line_checks(capsys):
    with pytest.raises(SystemExit) as e:
        cli.parse(["run", "--only", "shape,bogus"])
    assert e.value.code == 2 and "bogus" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        cli.parse(["run", "--u", "1,x"])
    a = cli.parse(["a", "b", "--u", "1,5", "--only", "none", "--vtk"])
    assert a.u == [1.0, 5.0] and a.only == set() and a.vtk and a.runs == ["a", "b"]
    with pytest.raises(SystemExit) as e:
        cli.parse(["--help"])
    assert e.value.code == 0
    help_text = capsys.readouterr().out
    for word in ("shear.png", "shape_u", "network_u", ".pvd", "shear-overlay.png"):
        assert word in help_text


def test_triaxial_runs(tmp_path):
    from tbagspost import triax
    head = "eps_a_pct,eps_v_pct,q_Pa,ratio,p_Pa,Z,sx_Pa,sy_Pa,sz_Pa,e,sxlo_Pa,sxhi_Pa,sylo_Pa,syhi_Pa\n# triaxial\n"
    dirs = []
    for s3 in (2e5, 5e5):
        d = tmp_path / ("s%d" % s3)
        d.mkdir()
        rows = []
        for k in range(30):
            ea = 0.5 * k
            ratio = 1 + 3 * ea / (ea + 2)
            rows.append("%g,%g,%g,%g,%g,4,%g,%g,%g,0.7,0,0,0,0" % (ea, 0.3 * ea - 0.02 * ea ** 2, (ratio - 1) * s3,
                                                                  ratio, s3, s3 * 1.001, s3 * 0.999, ratio * s3))
        (d / "triax.csv").write_text(head + "\n".join(rows) + "\n")
        dirs.append(d)
    fig, st = triax.figure([triax.find_csv(d) for d in dirs])
    a_r, a_v = fig.axes
    d = np.genfromtxt(dirs[1] / "triax.csv", delimiter=",", names=True, comments="#")
    assert np.allclose(a_r.get_lines()[1].get_ydata(), d["ratio"]) and np.allclose(a_v.get_lines()[1].get_ydata(), d["eps_v_pct"])
    assert [t.get_text() for t in a_r.get_legend().get_texts()] == ["$\\sigma_3$ = 200 kPa", "$\\sigma_3$ = 500 kPa"]
    r = d["ratio"].max()
    assert st[1]["phi_peak_deg"] == pytest.approx(np.degrees(np.arcsin((r - 1) / (r + 1))))
    cli.main([str(x) for x in dirs] + ["-o", str(tmp_path / "out")])
    assert (tmp_path / "out" / "triax-overlay.png").is_file() and (tmp_path / "out" / "s200000" / "triax.png").is_file()
    (dirs[0] / "triax.csv").write_text(head + "1,2,3")
    with pytest.raises(SystemExit, match="triax.csv"):
        triax.read(dirs[0] / "triax.csv")


def box_bag(bulge=0.0, tilt=0.0, drift=0.0, sink=0.0):
    """Bag particles on a 9 x 9 x 5 grid (s = 5 mm) as a Grains in its filled state, displaced:
    the +x wall bulges outward by `bulge` at mid-height (a sine over the height), every
    particle moves by tilt * z in x (shear) and by drift in y, and the top-centre particle
    sinks by `sink`."""
    from tbagspost import section
    s = section.S
    pts = np.array([(i, j, k) for i in range(9) for j in range(9) for k in range(5)
                    if i in (0, 8) or j in (0, 8) or k in (0, 4)], dtype=float) * s
    disp = np.zeros_like(pts)
    disp[:, 0] = tilt * pts[:, 2]
    disp[:, 1] = drift
    wall = pts[:, 0] == 8 * s
    disp[wall, 0] += bulge * np.sin(np.pi * pts[wall, 2] / (4 * s))
    top = (pts[:, 2] == 4 * s) & (pts[:, 0] == 4 * s) & (pts[:, 1] == 4 * s)
    disp[top, 2] -= sink
    n = len(pts)
    return dumps.Grains(step=1, ids=np.arange(1, n + 1), types=np.ones(n, dtype=int), radius=np.full(n, s / 2),
                        pos=pts + disp, vel=np.zeros((n, 3)), disp=disp, lo=pts.min(axis=0), hi=pts.max(axis=0))


def test_wall_bulge_and_top_gap_on_a_known_shape():
    from tbagspost import section, shape
    g = box_bag(bulge=0.001, tilt=0.1, drift=0.002, sink=0.0007)
    walls = {name: (z, off) for name, z, off in shape.wall_profiles(g, section.S / 2)}
    z, off = walls["leading wall ($+x$)"]
    assert np.allclose(z, [5, 10, 15]) and np.allclose(off, 1.0 * np.sin(np.pi * np.array([1, 2, 3]) / 4))
    for name in ("trailing wall ($-x$)", "side wall $-y$", "side wall $+y$"):   # tilt and drift do not count
        assert np.allclose(walls[name][1], 0, atol=1e-9), name
    z_top = 4 * section.S + section.S / 2 + 0.0001      # plate 0.1 mm above the top particles
    gaps = shape.top_gaps(g, z_top)
    assert len(gaps) == 7 * 7 and gaps.max() == pytest.approx(0.8) and np.median(gaps) == pytest.approx(0.1)
    x, gap = shape.gap_profile(g, z_top, section.in_xz(g, section.S / 2) & g.bag)
    assert gap.max() == pytest.approx(0.8) and np.sum(gap > 0.15) == 1


def test_loop_summaries_of_both_engines():
    """tbagspost.run.loops reads LAMMPS's section table and LIGGGHTS's older 'time (%)' lines."""
    lammps = ("Loop time of 2.5 on 2 procs for 100 steps with 50 atoms\n\n"
              "Section |  min time  |  avg time  |  max time  |%varavg| %total\n"
              "---------------------------------------------------------------\n"
              "Pair    | 1.0        | 1.2        | 1.4        |   1.0 | 48.00\n"
              "Other   |            | 0.3        |            |       | 12.00\n")
    liggghts = ("Loop time of 3.5 on 1 procs for 200 steps with 60 atoms, finish time Wed\n\n\n"
                "Pair  time (%) = 2.25 (64.3)\nBond  time (%) = 0.5 (14.3)\n"
                "Outpt time (%) = 0.25 (7.1)\nOther time (%) = 0.5 (14.3)\n")
    a, b = loops(lammps)[0], loops(liggghts)[0]
    assert (a["loop"], a["ranks"], a["steps"], a["atoms"]) == (2.5, 2, 100, 50)
    assert a["sections"] == {"Pair": (1.0, 1.2, 1.4), "Other": (0.3, 0.3, 0.3)}
    assert (b["loop"], b["ranks"], b["steps"], b["atoms"]) == (3.5, 1, 200, 60)
    assert b["sections"] == {"Pair": (2.25,) * 3, "Bond": (0.5,) * 3, "Output": (0.25,) * 3, "Other": (0.5,) * 3}
