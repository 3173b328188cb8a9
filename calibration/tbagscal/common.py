"""Constants, parameter ranges and errors of the calibration (shared by its modules)."""
import math
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
PREP_TRIES = 8          # preparations per sample before the search gives up
W_VOL = 0.5             # weight of the volumetric term in the misfit
RHO, D_MEAN = 2650.0, 0.005
COORDINATION = 4.5      # contacts per grain of the consolidated samples (measured 4.3-4.7)
RESTITUTION = 0.2


def twisting_coeffs(E, nu, mu, sigma3, void_ratio):
    """twisting sds coefficients (k_tw, c_tw, mu_tw) of the mean contact of a sample of equal
    grains of D_MEAN at the isotropic stress sigma3 (Pa): the mean contact force
    F = pi d^2 sigma3 (1 + e) / Z (from sigma = Z phi F / (pi d^2), phi = 1/(1+e)), its Hertz contact
    radius a, then the contact's own torsional stiffness k_tw = 16/3 G' a^3 (a circular contact without
    slip twisted on a half-space has 16/3 G a^3, Lubkin; two equal grains in series: G' = G/2; torsion
    is antiplane shear, so no (2 - nu) as in the tangential G*), the full-slip
    torque of a Hertz contact mu_tw F = 3 pi/16 mu a F (Lubkin), and the dashpot that gives the
    normal contact's damping ratio (restitution 0.2) on the pair's twisting inertia (I/2, I = 0.4 m r^2)."""
    d = D_MEAN
    F = math.pi * d * d * sigma3 * (1.0 + void_ratio) / COORDINATION
    Rs = d / 4.0
    Es = E / (2.0 * (1.0 - nu * nu))
    Gt = E / (4.0 * (1.0 + nu))            # G/2: the two grains' shear moduli in series
    delta = (F / (4.0 / 3.0 * Es * math.sqrt(Rs))) ** (2.0 / 3.0)
    a = math.sqrt(Rs * delta)
    k = 16.0 / 3.0 * Gt * a ** 3
    inertia = 0.5 * 0.4 * (RHO * math.pi * d ** 3 / 6.0) * (d / 2.0) ** 2
    lr = math.log(RESTITUTION)
    beta = -lr / math.sqrt(lr * lr + math.pi * math.pi)
    c = 2.0 * math.sqrt(5.0 / 6.0) * beta * math.sqrt(k * inertia)
    return k, c, 3.0 * math.pi / 16.0 * mu * a


class BudgetSpent(Exception):
    """The evaluation budget is used up (ends the search)."""


class FitError(Exception):
    """A clear message for the user (no traceback)."""


def fail(msg):
    raise FitError(msg)


def fmt(x):
    return "%.6g" % x
