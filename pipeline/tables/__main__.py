"""``python -m pipeline.tables --reference [--write]``: docs/tables.md
(:func:`pipeline.tables.reference.main`)."""

import sys

from .reference import main

sys.exit(main())
