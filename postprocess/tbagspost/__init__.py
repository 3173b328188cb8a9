"""tbagspost: figures and ParaView files from T-BAGS shear runs (inputs/in.shear), cyclic runs
(inputs/in.cyclic) and triaxial runs (calibration/in.triax).

Modules, one job each:
  dumps     readers of one dump file (grains through MDAnalysis, contacts and bonds), checks
  run       a run directory: CSV, time step, dump steps, u at a dump step; LAMMPS logs' runs
  datafile  a LAMMPS data file of the decks: box, atoms, bonds
  progress  a plain progress bar on stderr
  style     the paper style of the figures, saving
  shear     S-u and w-u figures (one run, several runs overlaid)
  shape     deformed shape of the bag (side view and two central cross-sections)
  network   contact-force network and bond tension in the central cross-section
  triax     triaxial runs (calibration/in.triax): stress ratio and volumetric strain
  loadpath  what carries the load: forces the contacts and bonds pass across the bag's mid-height
            (summary line, loadpath.csv at every dump)
  bounds    the S/F_v the sand alone can give, from its triaxial friction angle
  fabric    what the fabric carries alone (./tbags fabric)
  realizations  several realizations of one test: mean curves, spread of the reported figures
  rate      the rate study: speeds against the slowest, within the realizations' spread
  protocol  the protocol study: the compression's approach speed and the fill's settling
  height    the height study: bags of one ratio at equal shear strain u/H against the tallest
  hysteresis  loop measures (K_eq, W_d, h_eq), Ramberg-Osgood and Masing, the fit
  cyclic    cyclic runs (inputs/in.cyclic): cycles, table, R-O fit per load, figures, report
  isolator  isolator models (R-O/Masing, R-O/Phillips-Hashash, bilinear, Bouc-Wen, slider in
            series) run along a displacement history, their fits, the recommended one
  design    a designer's properties of a loop (ASCE 7-22 / AASHTO) and property modification factors
  isolator_report  the isolator section of a cyclic report (models, properties, factors)
  history   a displacement history run (in.cyclic -var history): the DEM's S against each model's
  stack     a stack of bags on films (in.cyclic -var bags N): displacement split, slip fraction
  vtkout    ParaView series (.vtu particles, .vtp contacts and bonds, .pvd indexes)
  cli       the command line (python3 -m tbagspost --help)
Every reader stops with a one-line SystemExit message naming the file on a missing, truncated
or malformed input (no traceback).
"""
__version__ = "1.0"


def fail(message):
    """Stop with a one-line message (SystemExit): for a user error, not a bug."""
    raise SystemExit("tbagspost: " + message)


def read_columns(path, columns, maker):
    """A CSV with a header line (and '#' comment lines) as a numpy structured array; stops with
    one line if the file is missing (run `maker` first), malformed or lacks the columns."""
    from pathlib import Path

    import numpy as np

    import io
    import sys

    path = Path(path)
    if not path.is_file():
        fail("no %s (run %s first)" % (path, maker))
    lines = path.read_text(errors="replace").splitlines()
    data = [k for k, line in enumerate(lines) if line.strip() and not line.startswith("#")]
    if len(data) > 1 and lines[data[-1]].count(",") < lines[data[0]].count(","):
        print("tbagspost: %s: its last line is cut short (the run stopped while writing it): left "
              "out" % path, file=sys.stderr)
        del lines[data[-1]]
    try:
        d = np.atleast_1d(np.genfromtxt(io.StringIO("\n".join(lines)), delimiter=",", names=True,
                                        comments="#"))
    except ValueError as e:
        fail("%s is malformed or truncated: %s" % (path, str(e).splitlines()[0]))
    if d.dtype.names is None or not set(columns) <= set(d.dtype.names):
        fail("%s lacks the columns %s" % (path, ", ".join(columns)))
    return d


def finite_rows(d, columns, path, where=None):
    """d without a last row that is not finite in columns (the row an interrupted run was
    writing); stops on any other such row, naming it (where(d, k): more words on row k) and its
    columns."""
    import numpy as np

    finite = np.all([np.isfinite(d[c]) for c in columns], axis=0)
    if len(d) and not finite[-1]:
        d, finite = d[:-1], finite[:-1]
    if not finite.all():
        k = int(np.flatnonzero(~finite)[0])
        cols = [c for c in columns if not np.isfinite(d[c][k])]
        fail("%s: data row %d%s has no finite %s" % (path, k + 1, " (%s)" % where(d, k) if where else "",
                                                    ", ".join(cols)))
    return d


def rms(x):
    """Root mean square of x (e.g. the difference of two curves on one grid)."""
    import numpy as np

    return float(np.sqrt(np.mean(np.square(x))))


def superseded(times, tol=0.0):
    """The rows of a resumed run's CSV that a later row rewrote: a resumed deck appends from its
    checkpoint's time, so a row is superseded when some later row is at its time or earlier
    (within tol). times: the rows' times in file order; returns a boolean array."""
    import numpy as np

    times = np.asarray(times, dtype=float)
    if len(times) == 0:
        return np.zeros(0, dtype=bool)
    later_min = np.minimum.accumulate(times[::-1])[::-1]
    return np.append(times[:-1] >= later_min[1:] - tol, False)
