"""What the sand alone can give a sandbag in simple shear: the ratio S/F_v on horizontal planes of
a sand layer at failure, from the sand's peak friction angle phi measured by calibration/'s
drained triaxial tests: the simulated peak ratio sigma_1/sigma_3 at 0.2, 0.5 and 1 MPa of the paper's
set under the decks' conventions (calibration/results/conventions/effective-none-walled/report.md,
row "start (paper)") and of the calibrated set (calibration/results/report.md, row "best"), the
samples' mean when there are several; the largest is used, sin phi = (R - 1)/(R + 1).

Bounds: sin phi, when the principal axes of stress and strain rate coincide at failure without
volume change (Davis 1968; the horizontal plane is then not the plane of maximum obliquity), and
tan phi, when the horizontal plane is itself the failure plane. A bag whose S/F_v lies far above
tan phi takes the rest from its fabric, not from its sand.
"""
import math
import re
from pathlib import Path

RESULTS = Path(__file__).resolve().parents[2] / "calibration" / "results"
REPORTS = {"paper": RESULTS / "conventions" / "effective-none-walled" / "report.md",
           "calibrated": RESULTS / "report.md"}
ROWS = {"paper": "| start (paper) |", "calibrated": "| best |"}
# "4.39 / 4.56 (" or, with several samples, "4.388 +- 0.028 / 4.560 (": the simulated mean
RATIO = re.compile(r"([\d.]+)(?: \+- [\d.]+)? / [\d.]+ \(")


def peak_ratio(sand, report=None):
    """The largest simulated peak sigma_1/sigma_3 of the sand set (paper or calibrated)."""
    if sand not in ROWS:
        raise ValueError("sand %r: paper or calibrated" % sand)
    report = report or REPORTS[sand]
    for line in Path(report).read_text().splitlines():
        if line.startswith(ROWS[sand]):
            ratios = [float(x) for x in RATIO.findall(line)]
            if ratios:
                return max(ratios)
    raise ValueError("%s: no peak ratios in the row %s" % (report, ROWS[sand]))


def sand_bounds(sand, report=None):
    """dict(phi_deg, sin, tan) of the sand set's peak friction angle."""
    R = peak_ratio(sand, report)
    s = (R - 1) / (R + 1)
    phi = math.asin(s)
    return dict(sand=sand, phi_deg=math.degrees(phi), sin=s, tan=math.tan(phi))


def describe(ratio, sand):
    """'S/F_v 0.18 (the paper sand alone: 0.39-0.43, phi 23.3 deg)'."""
    try:
        b = sand_bounds(sand)
    except (ValueError, OSError):
        return "S/F_v %.2f" % ratio
    return ("S/F_v %.2f (the %s sand alone: sin phi %.2f to tan phi %.2f, peak phi %.1f deg in the triaxial)"
            % (ratio, sand, b["sin"], b["tan"], b["phi_deg"]))
