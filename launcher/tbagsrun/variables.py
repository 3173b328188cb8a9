"""The -var values of ./tbags shear, checked before any stage runs: a name some deck of the preset
declares (else the nearest names are suggested), a value of the declared kind (a number where the
deck's default is one), in its range, and the time step against the limit the decks state.

A deck declares what a user may set as `variable NAME index DEFAULT` (or tests it with
`is_defined(variable,NAME)`); the decks a preset runs are in.bag, in.fill and its runs' decks,
with the files they include from inputs/.
"""
import difflib
import math
import re

from . import ROOT, LaunchError

INPUTS = ROOT / "inputs"
DECLARED = re.compile(r"^variable\s+(\w+)\s+index\s+(\"[^\"]*\"|\S+)", re.M)
DECLARED_NAME = re.compile(r"^variable\s+(\w+)\s+index\b", re.M)
TESTED = re.compile(r"is_defined\(variable,(\w+)\)")
INCLUDED = re.compile(r"include\s+\$\{tbags\}/inputs/([\w.]+)")
# the decks' own statement of the plates' stable step (between_plates.lmp's TIMESTEP line)
DT_LIMIT = re.compile(r"stable below about (\S+) s")


def positive(x):
    return x > 0


def whole(low):
    return lambda x: x == int(x) and x >= low


def or_minus_one(test):
    return lambda x: x == -1 or test(x)


# name: (test of the number, what it must be)
RANGES = {
    **{n: (whole(3), "a whole number of particles, 3 or more") for n in ("nx", "ny", "nz")},
    **{n: (positive, "positive") for n in (
        "Fpaper", "v", "ufinal", "du_csv", "du_dump", "vpeak", "freq", "e0", "film_t", "film_rho",
        "film_E", "film_gap", "tau_f", "kp", "vmax", "vmax_compress", "ke_tol", "vtol")},
    **{n: (whole(1), "a whole number, 1 or more") for n in (
        "cycles", "rows", "bags", "nsettle", "settle_chunk", "settle_max", "start", "seed", "compress_every")},
    "Fv": (or_minus_one(positive), "positive (N), or -1 for Fpaper scaled by the plan area"),
    "film_mu": (or_minus_one(lambda x: x >= 0), "0 or more, or -1 (none given)"),
    "film_mu_below": (or_minus_one(lambda x: x >= 0), "0 or more, or -1 (film_mu)"),
    "yarn_shear": (or_minus_one(lambda x: x >= 0), "0 or more, or -1 (the fabric's value)"),
    "yarn_bendE": (or_minus_one(positive), "positive (Pa), or -1 (the fabric's value)"),
    "bag_mur": (or_minus_one(lambda x: x >= 0), "0 or more, or -1 (0.05)"),
    "per_size": (or_minus_one(whole(1)), "a whole number, 1 or more, or -1 (from e0)"),
    "compress_to": (lambda x: 0 <= x < 1, "from 0 (none) to below 1 (a fraction of F_v)"),
    "film_nu": (lambda x: 0 <= x < 0.5, "from 0 to below 0.5"),
    "ki": (lambda x: x >= 0, "0 or more"),
    "steps": (whole(0), "a whole number of steps, 0 or more"),
    **{n: (lambda x: x in (0, 1), "0 or 1") for n in ("trace", "state", "plan_only")},
}
CHOICES = {"damping": ("explicit", "implicit"), "wave": ("sine", "triangle"), "sand": ("paper", "calibrated"),
           "fabric": ("solid", "words", "woven")}


def deck_texts(decks):
    """The text of each deck (inputs/in.<deck>) and of every inputs/ file they include."""
    todo = [INPUTS / ("in." + d) for d in decks]
    seen = {}
    while todo:
        f = todo.pop()
        if f in seen or not f.is_file():
            continue
        seen[f] = f.read_text()
        todo += [INPUTS / name for name in INCLUDED.findall(seen[f])]
    return seen


def declared(decks):
    """{name: default or None} of the variables the decks let a user set."""
    names = {}
    for text in deck_texts(decks).values():
        for name, default in DECLARED.findall(text):
            names.setdefault(name, default.strip('"'))
        for name in TESTED.findall(text):
            names.setdefault(name, None)
    return names


def dt_limit():
    m = DT_LIMIT.search((INPUTS / "between_plates.lmp").read_text())
    return float(m.group(1)) if m else math.inf


def number(name, text):
    try:
        x = float(text)
    except ValueError:
        raise LaunchError("shear: -var %s %s: a number is needed" % (name, text))
    if not math.isfinite(x):
        raise LaunchError("shear: -var %s %s: a finite number is needed" % (name, text))
    return x


def check(preset, variables):
    """Stop with one line on the first -var value no deck of the preset takes, or that is of the
    wrong kind or out of range (variables: name -> a word or a list of words)."""
    decks = ["bag", "fill"] + sorted({r.deck for r in preset.runs})
    names = declared(decks)
    internal = {"tbags", "deck", "fill", "bag", "out", "restart", "compress_from"}    # set by the launcher
    for name, value in variables.items():
        if name not in names or name in internal:
            near = difflib.get_close_matches(name, [n for n in names if n not in internal], n=3)
            hint = "; did you mean %s?" % " or ".join(near) if near else ""
            why = "is set by the launcher" if name in internal else \
                "is not a variable of the %s preset's decks (%s)" % (preset.name, ", ".join("in." + d for d in decks))
            raise LaunchError("shear: -var %s %s%s" % (name, why, hint))
        words = value if isinstance(value, list) else [value]
        if name == "amps":    # one quoted word of amplitudes in mm, or several words
            amps = [number(name, w) for w in " ".join(words).split()]
            if not amps or min(amps) <= 0 or any(b <= a for a, b in zip(amps, amps[1:])):
                raise LaunchError("shear: -var amps %s: positive amplitudes in mm, increasing" % " ".join(words))
            continue
        if len(words) > 1:
            raise LaunchError("shear: -var %s takes one value (got %s)" % (name, " ".join(words)))
        text = words[0]
        if name in CHOICES:
            if text not in CHOICES[name]:
                raise LaunchError("shear: -var %s %s: must be %s" % (name, text, " or ".join(CHOICES[name])))
            continue
        default = names[name]
        if name not in RANGES and default is not None and not is_number(default):
            continue    # a word (a file name ...): the deck judges it
        x = number(name, text)
        test, what = RANGES.get(name, (lambda x: True, ""))
        if not test(x):
            raise LaunchError("shear: -var %s %s: must be %s" % (name, text, what))
        if name == "dt" and not 0 < x <= dt_limit():
            raise LaunchError("shear: -var dt %s: the plates' contacts are stable below about %g s "
                              "(the decks' TIMESTEP line, inputs/between_plates.lmp); give dt <= %g"
                              % (text, dt_limit(), dt_limit()))


def is_number(text):
    try:
        float(text)
        return True
    except ValueError:
        return False


# -var values the LIGGGHTS shear takes besides its decks' own: the launcher reads them itself
LIGGGHTS_LAUNCHER = {"trace", "sand"}


def check_liggghts(variables):
    """--engine liggghts: stop on a -var value that only LAMMPS's shear decks take (the LIGGGHTS
    shear would run without it): a name must be declared by in.bag, in.fill (their stages run in
    LAMMPS) or the LIGGGHTS decks (inputs/liggghts/in.shear, model.lig), or read by the launcher."""
    lig = "".join((INPUTS / "liggghts" / f).read_text() for f in ("in.shear", "model.lig"))
    taken = set(declared(["bag", "fill"])) | set(DECLARED_NAME.findall(lig)) | LIGGGHTS_LAUNCHER
    for name in variables:
        if name not in taken:
            raise LaunchError("shear: -var %s: the LIGGGHTS shear (inputs/liggghts/in.shear) does not take "
                              "it, only LAMMPS's in.shear does: run without --engine liggghts" % name)
