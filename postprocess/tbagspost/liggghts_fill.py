"""A filled bag of the LAMMPS decks (write_data, atom style bpm/sphere) as a LIGGGHTS data file
(atom_style hybrid granular molecular), the same numbers to the bit; atom types 1 (bag) and 2
(sand) as in LAMMPS, and a third type declared for the plates. The box is widened by 20 mm on
each side in x and y: LIGGGHTS keeps a mesh (the top plate, which moves sideways by u) inside
the box, and the plate must still cover the bag at the end of the shear.

    PYTHONPATH=postprocess /usr/bin/python3 -m tbagspost.liggghts_fill fill.data fill.liggghts.data
"""
import sys

from .datafile import DataFile

PLATE_TYPES = 1    # LIGGGHTS gives walls a particle type of their own (model.lig: type 3)
MARGIN = 0.02      # m added to the box on each side in x and y


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip())
        return 2
    data = DataFile(argv[1])
    data.box[:2, 0] -= MARGIN
    data.box[:2, 1] += MARGIN
    data.write_liggghts(argv[2], ntypes=int(data.type.max()) + PLATE_TYPES)
    print("wrote %s: %d atoms, %d bonds" % (argv[2], len(data.id), len(data.bonds)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
