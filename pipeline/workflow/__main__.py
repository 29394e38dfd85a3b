"""``python -m pipeline.workflow --reference [--write]``: the workflow reference
(:func:`pipeline.workflow.load.main`)."""

import sys

from .load import main

sys.exit(main())
