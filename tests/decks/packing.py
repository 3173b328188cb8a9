"""A dense random polydisperse two-material packing (in.packing), made once per test module."""
from pathlib import Path

import lmprun

DECK = Path(__file__).resolve().parent / "in.packing"


def make(workdir, n=400, phi=0.64, L0=0.05, ncompress=20000, np_ranks=1):
    lmprun.run(DECK, workdir, np_ranks=np_ranks, variables={
        "n": n, "phi": phi, "L0": L0, "ncompress": ncompress}).check()
    return Path(workdir) / "packing.data"
