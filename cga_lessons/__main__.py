"""``python -m cga_lessons ...``: the same program as the ``cga-lessons`` command."""

import sys

from cga_lessons.cli import main

if __name__ == "__main__":
    sys.exit(main())
