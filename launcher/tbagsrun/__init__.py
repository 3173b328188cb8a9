"""The launcher's Python side (./tbags stays bash for set-up, run, test and bench).

lammps.py   the one way to run LAMMPS with the plugin: the launcher, the tests, the benchmark and
            the calibration all call it
presets.py  the shear presets as data: bag size, the runs from one fill, post-processing, checks
shear.py    the preset workflow: bag, fill, the preset's runs (side by side where they fit the
            cores), figures, checks; realizations of it
stages.py   one stage (a deck run in its folder): made once and reused, or stamped and continued
            on --resume (resume.py: finished runs, checkpoints, the CSV merged); its progress
            on the console (progress.py)
states.py   committed states of long stages (states/: the paper bag's fill), restored by
            stage_once instead of running the stage
estimate.py the paper preset's time estimate (tbagspost.project_time runs the projection)
liggghts_stage.py  a shear run in LIGGGHTS (--engine liggghts), written as in.shear's CSV
cli.py      `python3 -m tbagsrun shear ...` (__main__.py), what `./tbags shear` runs: arguments,
            set-up, then shear.py
"""
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
POSTPROCESS = ROOT / "postprocess"


def use_postprocess():
    """Put postprocess/ (tbagspost) on the import path, once."""
    if str(POSTPROCESS) not in sys.path:
        sys.path.insert(0, str(POSTPROCESS))


class LaunchError(Exception):
    """Stops the launcher: a bad argument or a failed run. Printed as 'tbags: <message>'."""
