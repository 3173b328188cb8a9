"""Constants, parameter ranges and errors of the calibration (shared by its modules)."""
from pathlib import Path


HERE = Path(__file__).resolve().parents[1]    # calibration/
ROOT = HERE.parent
PAPER = {"mu": 0.31, "mur": 0.05, "E": 1.8e9}
# physical ranges of the options (checked before anything runs)
RANGES = {
    "mu": (0.0, 1.5, "sliding friction"),
    "mur": (0.0, 0.5, "rolling friction (dimensionless)"),
    "E": (1e7, 1e12, "grain Young's modulus (Pa)"),
    "void_ratio": (0.45, 1.2, "void ratio"),
    "inertial": (1e-6, 1e-2, "inertial number"),
    "strain": (0.001, 0.4, "final axial strain"),
    "width": (0.01, 1.0, "cell width (m)"),
    "height": (0.01, 2.0, "cell height (m)"),
    "e_tol": (0.001, 0.1, "void ratio tolerance"),
}
PREP_MU_MAX = 1.0       # preparation friction searched in [0, PREP_MU_MAX]
PREP_SLOPE = 0.25       # d e / d mu_prep, first guess (measured on the 50 x 50 x 100 mm sample)
PREP_MU_START = 0.14
W_VOL = 0.5             # weight of the volumetric term in the misfit
RHO, D_MEAN = 2650.0, 0.005


class BudgetSpent(Exception):
    """The evaluation budget is used up (ends the search)."""


class FitError(Exception):
    """A clear message for the user (no traceback)."""


def fail(msg):
    raise FitError(msg)


def fmt(x):
    return "%.6g" % x
