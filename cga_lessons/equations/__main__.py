"""``python -m cga_lessons.equations``: the registry as a table, or the README's section rewritten."""

import sys

from cga_lessons.equations.readme import main

sys.exit(main())
