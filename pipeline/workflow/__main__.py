"""``python -m pipeline.workflow --reference [--write]``: the workflow reference;
``--schema``: the scene format as a JSON Schema (:func:`pipeline.workflow.load.main`)."""

import sys

from .load import main

sys.exit(main())
