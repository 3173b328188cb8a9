"""Shared set-up of the plate tests: a settled sand column (in.column), made once per module."""
from pathlib import Path

import lmprun

COLUMN = Path(__file__).resolve().parent / "in.column"

# the deck lines every plate test starts with (the column data file as ${data})
HEAD = """
units si
atom_style sphere
atom_modify map array
boundary p p fm
comm_modify vel yes
read_data ${data}
pair_style gran/hertz/rolling ${rolling}
pair_coeff 1 1 material 1.8e9 0.1 friction 0.31 rolling 0.05 restitution 0.2
timestep 2e-6
"""


def make_column(workdir, n=250):
    lmprun.run(COLUMN, workdir, variables={"n": n}).check()
    return Path(workdir) / "column.data"
