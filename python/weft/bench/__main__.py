"""``python -m weft.bench <subsystem> [options]``; see :mod:`weft.bench`."""

import sys

from weft.bench import main

if __name__ == "__main__":
    sys.exit(main())
