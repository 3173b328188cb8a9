"""postprocess/tbagspost on the dumps of a tiny shear run (9 x 9 x 5 bag, u to 1.5 mm, dumps every
0.5 mm): MDAnalysis reads the grains dumps, the figures carry the CSV's and the dumps' numbers,
the ParaView files read back with the dumps' counts and values, the command line writes everything,
and a truncated or missing dump stops with a one-line message naming the file."""
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import lmprun

sys.path.insert(0, str(lmprun.ROOT / "postprocess"))
from tbagspost import cli, dumps, forces, network, section, shape, shear, vtkout  # noqa: E402
from tbagspost.run import Run  # noqa: E402

INPUTS = lmprun.INPUTS
SIZE = lmprun.TINY_BAG


@pytest.fixture(scope="module")
def run(tiny_filled):
    wd = tiny_filled
    lmprun.run(INPUTS / "in.shear", wd, variables=dict(SIZE, v=0.02, ufinal=0.0015, du_dump=0.0005)).check()
    return Run(wd)


def table(path):
    """The dump's rows and column names (numpy; the reference the package is checked against)."""
    lines = path.read_text().splitlines()
    cols = lines[8].split()[2:]
    return cols, np.loadtxt(path, skiprows=9, ndmin=2)


def last(run, kind="grains"):
    return run.steps(kind)[-1]


def test_run_has_dumps_and_u_at_steps(run):
    steps = run.steps()
    assert len(steps) >= 2 and steps == run.steps("contacts") == run.steps("bonds")
    assert run.dt == 1.5e-6
    # dumps every 0.5 mm of u from u = 0; the CSV's rows are interval means (u at the interval's
    # mean time), and u is linear in time, so the interpolation gives the dump's u exactly (to the
    # CSV's 4 decimals)
    assert [run.at_step(s) for s in steps] == pytest.approx([0.5 * k for k in range(len(steps))], abs=2e-4)
    assert run.step_near(100.0) == steps[-1]


def test_mdanalysis_reads_the_grains_dump(run):
    path = run.dump("grains", last(run))
    u = dumps.universe(path)
    cols, t = table(path)
    t = t[np.argsort(t[:, 0])]
    assert u.atoms.n_atoms == len(t)
    assert np.array_equal(u.atoms.ids, t[:, 0].astype(int))
    g = run.grains(last(run))
    assert g.step == last(run)
    for name, values in (("x", g.pos[:, 0]), ("z", g.pos[:, 2]), ("vy", g.vel[:, 1]), ("radius", g.radius),
                         ("dz", g.disp[:, 2]), ("type", g.types)):
        assert np.allclose(values, t[:, cols.index(name)], rtol=1e-6, atol=1e-8), name
    assert set(g.types) == {1, 2} and g.bag.sum() == (t[:, 1] == 1).sum()


def test_shear_figure_plots_the_csv(run):
    fig, stats = shear.figure([run, run])
    a_s, a_w = fig.axes
    d = run.csv
    line = a_s.get_lines()[0]
    assert np.array_equal(line.get_xdata(), d["u_mm"]) and np.allclose(line.get_ydata(), d["S_N"] / 1000)
    assert np.allclose(a_w.get_lines()[0].get_ydata(), d["w_mm"] - d["w_mm"][0])
    assert len(a_s.get_lines()) == 2
    label = a_s.get_legend().get_texts()[0].get_text()
    # (the same run twice: labelled by F_v and, as both have it, by their folder)
    assert label.startswith("$F_v$ = %.2f kN" % (np.median(d["Fv_N"]) / 1000))
    assert "(kN)" in a_s.get_ylabel() and "(mm)" in a_w.get_ylabel() and "(mm)" in a_s.get_xlabel()
    assert stats[0]["S_peak_kN"] == pytest.approx(d["S_N"].max() / 1000)


def test_shape_figure_colours_bag_by_displacement(run):
    step = last(run)
    fig, st = shape.figure(run, step)
    g = run.grains(step)
    side = fig.axes[0]
    coll = side.collections[0]
    bag = g.bag
    dmag = np.linalg.norm(g.disp[bag], axis=1) * 1000
    order = np.argsort(g.pos[bag, 1])
    assert len(coll.get_offsets()) == bag.sum()
    assert np.allclose(coll.get_array(), dmag[order])
    assert np.allclose(coll.get_offsets(), g.pos[bag][order][:, [0, 2]] * 1000)
    assert st["d_bag_max_mm"] == pytest.approx(dmag.max())
    # the top plate drawn where the CSV puts it; the gap is plate z minus the top of the bag
    ztop = run.at_step(step, "zplate_mm")
    assert any(np.allclose(l.get_ydata(), ztop) for l in side.get_lines())
    assert 0 <= st["gap_median_mm"] <= st["gap_max_mm"] < ztop
    top = (g.pos[bag, 2] + g.radius[bag]).max() * 1000
    assert st["gap_max_mm"] >= ztop - top - 1e-9
    # the x-z section: bag particles within the band around mid y, coloured the same way
    half = section.default_half_band(g)
    sec = section.in_xz(g, half) & bag
    assert len(fig.axes[1].collections[1].get_offsets()) == sec.sum() > 0
    assert np.allclose(fig.axes[1].collections[1].get_array(), np.linalg.norm(g.disp[sec], axis=1) * 1000)


def test_network_figure_draws_the_contact_forces(run):
    step = last(run)
    fig, st = network.figure(run, step)
    g, c, b = run.grains(step), run.contacts(step), run.bonds(step)
    cols, t = table(run.dump("contacts", step))
    assert np.array_equal(c["fn"], t[:, cols.index("fn")]) and st["n_contacts"] == len(t)
    kind = network.contact_kind(c)
    seg = network.ends(g, c["id1"], c["id2"])
    in_sec = np.abs(seg.mean(axis=1)[:, 1] - section.mid_y(g)) <= section.default_half_band(g)
    a_net = fig.axes[0]
    ss, bs = a_net.collections[0], a_net.collections[1]
    for coll, name in ((ss, "sand-sand"), (bs, "bag-sand")):
        sel = in_sec & (kind == name)
        assert sel.sum() > 0 and len(coll.get_segments()) == sel.sum()
        assert np.allclose(coll.get_array(), np.clip(c["fn"][sel], 0, None))
        assert np.allclose(np.array(coll.get_segments()), seg[sel][:, :, [0, 2]] * 1000)
    wall = in_sec & (kind == "bag-bag")    # drawn too (be13c81 left out what carries most of F_v)
    assert wall.sum() > 0 and np.allclose(np.array(a_net.collections[2].get_segments()), seg[wall][:, :, [0, 2]] * 1000)
    assert "share of the section's normal force: sand-sand" in a_net.get_title()
    assert st["n_section"] == (in_sec & (kind != "bag-bag")).sum()
    assert st["tension_max_N"] == pytest.approx(b["tension"].max())
    edge = network.edge_mask(g, seg.mean(axis=1))
    assert st["fn_edge_N"] == pytest.approx(c["fn"][(kind == "sand-sand") & edge].mean())
    # bond panel: the taut bonds of the bag's central row coloured by tension
    taut = fig.axes[1].collections[1]
    b_sec = (np.abs(network.ends(g, b["id1"], b["id2"])[:, :, 1] - section.mid_y(g)) <= section.S / 2).all(axis=1)
    assert np.allclose(taut.get_array(), b["tension"][b_sec & (b["tension"] > 0)])


def test_forces_figure_draws_the_papers_three_views(run):
    """The paper's Fig. 5: the resultant |f| of every contact on sand, from the dump's columns."""
    step = last(run)
    fig, st = forces.figure(run, step)
    g, c = run.grains(step), run.contacts(step)
    cols, t = table(run.dump("contacts", step))
    f = np.sqrt(sum(t[:, cols.index(k)] ** 2 for k in ("fn", "ftx", "fty", "ftz")))
    on_sand = (t[:, cols.index("type1")] == 2) | (t[:, cols.index("type2")] == 2)
    f = f[on_sand]
    assert st["n_sand_contacts"] == on_sand.sum() > 0 and st["mean_N"] == pytest.approx(f.mean())
    mid = network.ends(g, c["id1"], c["id2"])[on_sand].mean(axis=1)
    centre = np.abs(mid[:, 1] - section.mid_y(g)) <= section.default_half_band(g)
    a3, a_centre, a_side = fig.axes[:3]
    # each view draws its contacts' |f|, the strongest last (on top)
    assert np.allclose(a_centre.collections[0].get_array(), np.sort(f[centre]))
    assert st["centre_N"] == pytest.approx(f[centre].mean())
    assert 0 < st["n_side"] == len(a_side.collections[0].get_array()) < len(f)
    strong = min((f > 2 * f.mean()).sum(), forces.N_3D)
    assert st["n_3d"] == strong and len(a3.collections[0].get_array()) == strong


def test_vtk_files_read_back(run, tmp_path):
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLUnstructuredGridReader

    def read(reader, path):
        reader.SetFileName(str(path))
        reader.Update()
        return reader.GetOutput()

    pvds = vtkout.convert(run, tmp_path)
    assert sorted(p.name for p in pvds) == ["bonds.pvd", "contacts.pvd", "particles.pvd", "plates.pvd"]
    step = last(run)
    cols, t = table(run.dump("grains", step))
    t = t[np.argsort(t[:, 0])]
    grid = read(vtkXMLUnstructuredGridReader(), tmp_path / ("particles_%d.vtu" % step))
    pd = grid.GetPointData()
    assert grid.GetNumberOfPoints() == grid.GetNumberOfCells() == len(t)
    assert np.allclose(vtk_to_numpy(grid.GetPoints().GetData()), t[:, [cols.index(c) for c in "xyz"]],
                       rtol=1e-6, atol=1e-8)
    for name, cs in (("id", ["id"]), ("type", ["type"]), ("radius", ["radius"]),
                     ("velocity", ["vx", "vy", "vz"]), ("displacement", ["dx", "dy", "dz"])):
        ref = t[:, [cols.index(c) for c in cs]]
        got = vtk_to_numpy(pd.GetArray(name)).reshape(len(t), -1)
        assert np.allclose(got, ref, rtol=1e-6, atol=1e-8), name
    for kind, column, reader in (("contacts", "fn", vtkXMLPolyDataReader()),
                                 ("bonds", "tension", vtkXMLPolyDataReader())):
        cols, t = table(run.dump(kind, step))
        poly = read(reader, tmp_path / ("%s_%d.vtp" % (kind, step)))
        assert poly.GetNumberOfLines() == len(t) and poly.GetNumberOfPoints() == 2 * len(t)
        assert np.array_equal(vtk_to_numpy(poly.GetCellData().GetArray(column)), t[:, cols.index(column)])
    # a line runs between the two atoms' centres
    c = run.contacts(step)
    g = run.grains(step)
    poly = read(vtkXMLPolyDataReader(), tmp_path / ("contacts_%d.vtp" % step))
    pts = vtk_to_numpy(poly.GetPoints().GetData())
    assert np.allclose(pts[0], g.pos[g.index([c["id1"][0]])][0]) and np.allclose(pts[1], g.pos[g.index([c["id2"][0]])][0])
    # the plates: bottom at -s/2, top where the CSV puts it
    poly = read(vtkXMLPolyDataReader(), tmp_path / ("plates_%d.vtp" % step))
    z = vtk_to_numpy(poly.GetPoints().GetData())[:, 2]
    assert poly.GetNumberOfPolys() == 2 and np.allclose(z[:4], section.Z_BOTTOM)
    assert np.allclose(z[4:], run.at_step(step, "zplate_mm") / 1000)
    index = ET.parse(tmp_path / "particles.pvd").getroot().findall("Collection/DataSet")
    assert [d.get("file") for d in index] == ["particles_%d.vtu" % s for s in run.steps()]
    assert [float(d.get("timestep")) for d in index] == pytest.approx([run.at_step(s) for s in run.steps()], abs=1e-5)


def test_command_line_writes_everything(run, tmp_path):
    out = tmp_path / "out"
    cli.main([str(run.path), "--vtk", "--u", "0.5,100", "-o", str(out)])
    names = sorted(p.name for p in out.iterdir())
    u_first, u_last = run.at_step(run.step_near(0.5)), run.at_step(last(run))
    for name in ("shear.png", "summary.txt", "shape_u%.1fmm.png" % u_first, "shape_u%.1fmm.png" % u_last,
                 "network_u%.1fmm.png" % u_last, "forces_u%.1fmm.png" % u_last, "paraview"):
        assert name in names, (name, names)
    assert (out / "paraview" / "particles.pvd").is_file()
    assert (out / "shear.png").stat().st_size > 20000
    summary = (out / "summary.txt").read_text()
    assert "top plate" in summary and "bond tension max" in summary and "side/centre" in summary
    # several runs: per-run folders and the overlay
    cli.main([str(run.path), str(run.path), "--only", "shear", "-o", str(tmp_path / "two")])
    assert (tmp_path / "two" / "shear-overlay.png").is_file()
    # the launcher's way: python3 -m tbagspost, and the old plot_shear.py entry
    env_path = str(lmprun.ROOT / "postprocess")
    res = subprocess.run([sys.executable, "-m", "tbagspost", "--help"], capture_output=True, text=True,
                         env={"PYTHONPATH": env_path})
    assert res.returncode == 0 and "paraview" in res.stdout.lower()
    res = subprocess.run([sys.executable, str(lmprun.ROOT / "postprocess" / "plot_shear.py"), str(run.path),
                          "-o", str(tmp_path / "s.png")], capture_output=True, text=True)
    assert res.returncode == 0 and (tmp_path / "s.png").is_file(), res.stderr


def test_truncated_and_missing_dumps(run, tmp_path):
    step = last(run)
    bad = tmp_path / "bad"
    bad.mkdir()
    for f in ("shear.csv", "log.lammps"):
        shutil.copy(run.path / f, bad)
    for kind in ("grains", "contacts", "bonds"):
        text = run.dump(kind, step).read_bytes()
        (bad / run.dump(kind, step).name).write_bytes(text[: len(text) // 2])   # cut mid-file
    broken = Run(bad)
    for kind, read in (("grains", broken.grains), ("contacts", broken.contacts), ("bonds", broken.bonds)):
        with pytest.raises(SystemExit, match=r"dump\.%s\.%d is truncated" % (kind, step)) as e:
            read(step)
        assert "\n" not in str(e.value)
    with pytest.raises(SystemExit, match=r"no dump .*dump\.grains\.%d" % (step + 1)):
        broken.grains(step + 1)
    # the command line: the message, no traceback
    res = subprocess.run([sys.executable, "-m", "tbagspost", str(bad), "--only", "shape"], capture_output=True,
                         text=True, env={"PYTHONPATH": str(lmprun.ROOT / "postprocess")})
    assert res.returncode != 0 and "Traceback" not in res.stderr
    assert res.stderr.strip() == "tbagspost: %s is truncated: %s" % (
        bad / ("dump.grains.%d" % step), res.stderr.split("is truncated: ")[1].strip())
    # a dump without the extended columns (older in.shear): named columns in the message
    old = bad / ("dump.contacts.%d" % step)
    lines = run.dump("contacts", step).read_text().splitlines()
    lines[8] = "ITEM: ENTRIES index c_contacts[1] c_contacts[2] c_contacts[3] c_contacts[4] c_contacts[5] " \
               "c_contacts[6] c_contacts[7] c_contacts[8] c_contacts[9] c_contacts[10]"
    old.write_text("\n".join(lines) + "\n")
    with pytest.raises(SystemExit, match="lacks the columns id1 id2 type1 type2"):
        broken.contacts(step)
