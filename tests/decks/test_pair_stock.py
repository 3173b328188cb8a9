"""Same physics as stock LAMMPS: with rolling off, per-atom forces and torques of our
gran/hertz/rolling and of stock `pair granular hertz/material ... tangential mindlin ...
damping coeff_restitution` (mixed pairs written explicitly, doc/pair_gran_hertz_rolling.rst) agree after 100 steps."""
import math

import pytest

import lmprun
import packing

E = {1: 1.8e9, 2: 0.75e9}
NU = 0.1
MU = {(1, 1): 0.31, (2, 2): 0.26, (1, 2): 0.26}
COR = 0.2

RUN = lmprun.packing_head() + """PAIR_LINES
timestep 1e-6
fix 1 all nve/sphere
compute nc all contact/atom
compute cn all reduce ave c_nc
thermo_style custom step c_cn
run ${nsteps}
write_dump all custom forces.dump id x y z fx fy fz tqx tqy tqz modify sort id format float %.17g
"""


def stock_pair_lines():
    def estar(i, j):
        return 1.0 / ((1 - NU * NU) / E[i] + (1 - NU * NU) / E[j])

    xt = math.sqrt(2 * (1 - NU) / (2 - NU))    # sqrt(4 G*/E*) for equal Poisson ratios
    lines = ["pair_style granular"]
    for (i, j), mu in MU.items():
        Ep = 2 * (1 - NU * NU) * estar(i, j)
        lines.append("pair_coeff %d %d hertz/material %.17g %g %g tangential mindlin NULL %.17g %g "
                     "damping coeff_restitution" % (i, j, Ep, COR, NU, xt, mu))
    return lines


def ours_pair_lines():
    return ["pair_style gran/hertz/rolling none",
            "pair_coeff 1 1 material %g %g friction %g restitution %g" % (E[1], NU, MU[1, 1], COR),
            "pair_coeff 2 2 material %g %g friction %g restitution %g" % (E[2], NU, MU[2, 2], COR),
            "pair_coeff 1 2 friction %g restitution %g" % (MU[1, 2], COR)]


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    return packing.make(tmp_path_factory.mktemp("packing"))


def run_with(lines, workdir, data, nsteps=100):
    deck = RUN.replace("PAIR_LINES", "\n".join(lines))
    res = lmprun.run(deck, workdir, variables={"data": data, "nsteps": nsteps}).check()
    return res, workdir / "forces.dump"


def test_forces_and_torques_match_stock(tmp_path, data):
    res_o, ours = run_with(ours_pair_lines(), tmp_path / "ours", data)
    res_s, stock = run_with(stock_pair_lines(), tmp_path / "stock", data)
    cols, a = lmprun.read_dump(ours)
    _, b = lmprun.read_dump(stock)
    f = [cols.index(c) for c in ("fx", "fy", "fz")]
    t = [cols.index(c) for c in ("tqx", "tqy", "tqz")]
    ef = lmprun.max_rel_diff(a[:, f], b[:, f])
    et = lmprun.max_rel_diff(a[:, t], b[:, t])
    print("max |dF|/max|F| = %.3e, max |dT|/max|T| = %.3e" % (ef, et))
    assert abs(b[:, f]).max() > 0 and abs(b[:, t]).max() > 0
    assert ef < 1e-10 and et < 1e-10
