"""Moved to :mod:`pipeline.execute.cluster`; kept for one release (code in pipeline/ imports the
new path, tests/test_layout.py).  ``python -m pipeline.cluster`` still runs its check."""

import sys

from .execute.cluster import *  # noqa: F403
from .execute.cluster import main

if __name__ == "__main__":
    sys.exit(main())
