"""python3 -m tbagsrun shear [PRESET] [options]: what `./tbags shear` runs."""
import sys

from .cli import main

main(sys.argv[1:])
