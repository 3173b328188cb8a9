"""ParaView files of a shear run, written with VTK's Python module (python3-vtk9).

For every dump step, in OUTDIR (default RUN/paraview):
  particles_<step>.vtu  one vertex per particle; point data: id, type, radius (m),
                        velocity (m/s), displacement (m, from the filled state), |displacement|
  contacts_<step>.vtp   one line per contact between the particle centres; cell data: fn (N),
                        ft (tangential force vector, N), kind (0 bag-bag, 1 bag-sand, 2 sand-sand)
  bonds_<step>.vtp      one line per bag bond; cell data: tension (N, > 0 pulls), strain, btype
  plates_<step>.vtp     the bottom and top plates as two rectangles over the particles' extent
                        (the top at the CSV's zplate), to see the top surface detach
and particles.pvd, contacts.pvd, bonds.pvd, plates.pvd: the series with the shear displacement u in mm as
the time value (ParaView's time slider then reads u). In ParaView: open a .pvd, apply the
Glyph filter (Sphere, scale by radius, factor 2) to particles; colour contacts by fn.
"""
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import VTK_VERTEX, vtkCellArray, vtkPolyData, vtkUnstructuredGrid
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter, vtkXMLUnstructuredGridWriter

from tbagspost import fail, network, section
from tbagspost.progress import Progress

KIND_CODE = {"bag-bag": 0, "bag-sand": 1, "sand-sand": 2}


def _array(values, name):
    """A named VTK array holding a copy of values (1-D or (n, 3))."""
    arr = numpy_to_vtk(np.ascontiguousarray(values), deep=True)
    arr.SetName(name)
    return arr


def _points(xyz):
    pts = vtkPoints()
    pts.SetData(_array(np.asarray(xyz, dtype=np.float64), "points"))
    return pts


def _cells(n_per_cell, count):
    """A vtkCellArray of `count` cells of n_per_cell consecutive points each."""
    cells = vtkCellArray()
    offsets = numpy_to_vtkIdTypeArray(np.arange(count + 1, dtype=np.int64) * n_per_cell, deep=True)
    conn = numpy_to_vtkIdTypeArray(np.arange(count * n_per_cell, dtype=np.int64), deep=True)
    cells.SetData(offsets, conn)
    return cells


def _write(writer, data, path):
    writer.SetFileName(str(path))
    writer.SetInputData(data)
    writer.SetDataModeToAppended()
    writer.SetCompressorTypeToZLib()
    if not writer.Write():
        fail("VTK could not write %s" % path)
    return path


def particles(g, path):
    """Particles of one step as a .vtu of vertices with their data."""
    grid = vtkUnstructuredGrid()
    grid.SetPoints(_points(g.pos))
    grid.SetCells(VTK_VERTEX, _cells(1, len(g.ids)))
    pd = grid.GetPointData()
    for values, name in ((g.ids, "id"), (g.types, "type"), (g.radius, "radius"), (g.vel, "velocity"),
                         (g.disp, "displacement"), (np.linalg.norm(g.disp, axis=1), "displacement_magnitude")):
        pd.AddArray(_array(values, name))
    pd.SetActiveScalars("radius")
    return _write(vtkXMLUnstructuredGridWriter(), grid, path)


def lines(g, id1, id2, cell_data, path):
    """Lines between the centres of atoms id1[k] and id2[k] as a .vtp with cell data."""
    seg = network.ends(g, id1, id2).reshape(-1, 3)
    poly = vtkPolyData()
    poly.SetPoints(_points(seg))
    poly.SetLines(_cells(2, len(id1)))
    cd = poly.GetCellData()
    for name, values in cell_data.items():
        cd.AddArray(_array(values, name))
    return _write(vtkXMLPolyDataWriter(), poly, path)


def contacts(g, c, path):
    kind = np.array([KIND_CODE[k] for k in network.contact_kind(c)], dtype=np.int32)
    ft = np.column_stack([c["ftx"], c["fty"], c["ftz"]])
    return lines(g, c["id1"], c["id2"], {"fn": c["fn"], "ft": ft, "kind": kind}, path)


def bonds(g, b, path):
    data = {"tension": b["tension"]}
    for name in ("strain", "btype"):
        if name in b:
            data[name] = b[name]
    return lines(g, b["id1"], b["id2"], data, path)


def plates(g, z_top, path):
    """The bottom plate (z = -s/2) and, if known, the top plate (z_top) as rectangles (.vtp)
    covering the particles' extent in x and y plus one grid spacing."""
    lo, hi = g.pos[:, :2].min(axis=0) - section.S, g.pos[:, :2].max(axis=0) + section.S
    levels = [section.Z_BOTTOM] + ([z_top] if z_top is not None else [])
    corners = [(lo[0], lo[1]), (hi[0], lo[1]), (hi[0], hi[1]), (lo[0], hi[1])]
    poly = vtkPolyData()
    poly.SetPoints(_points([(x, y, z) for z in levels for x, y in corners]))
    poly.SetPolys(_cells(4, len(levels)))
    poly.GetCellData().AddArray(_array(np.array(levels), "z"))
    return _write(vtkXMLPolyDataWriter(), poly, path)


def pvd(entries, path):
    """A ParaView collection: entries = [(time value, file name relative to path's folder)]."""
    root = ET.Element("VTKFile", type="Collection", version="0.1", byte_order="LittleEndian")
    col = ET.SubElement(root, "Collection")
    for t, name in entries:
        ET.SubElement(col, "DataSet", timestep="%.6g" % t, group="", part="0", file=str(name))
    ET.ElementTree(root).write(path, xml_declaration=True, encoding="utf-8")
    return path


def convert(run, outdir=None):
    """Write the ParaView series of every dump step of a run; returns the .pvd paths.
    Contacts and bonds are written for the steps that have those dumps."""
    out = Path(outdir) if outdir else run.path / "paraview"
    out.mkdir(parents=True, exist_ok=True)
    steps = run.steps("grains")
    if not steps:
        fail("%s: no dump.grains.* files" % run.path)
    has = {kind: set(run.steps(kind)) for kind in ("contacts", "bonds")}
    series = {"particles": [], "contacts": [], "bonds": [], "plates": []}
    for step in Progress(steps, "ParaView %s" % run.name):
        u = run.at_step(step)
        g = run.grains(step)
        series["particles"].append((u, particles(g, out / ("particles_%d.vtu" % step)).name))
        series["plates"].append((u, plates(g, section.top_plate_z(run, step), out / ("plates_%d.vtp" % step)).name))
        if step in has["contacts"]:
            series["contacts"].append((u, contacts(g, run.contacts(step), out / ("contacts_%d.vtp" % step)).name))
        if step in has["bonds"]:
            series["bonds"].append((u, bonds(g, run.bonds(step), out / ("bonds_%d.vtp" % step)).name))
    return [pvd(entries, out / ("%s.pvd" % name)) for name, entries in series.items() if entries]
