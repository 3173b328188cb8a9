"""python3 -m tbagspost: see tbagspost.cli."""
import sys

from tbagspost.cli import main

sys.exit(main())
