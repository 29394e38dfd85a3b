"""``python -m pipeline`` is the ``bbb`` command."""

import sys

from .cli import main

sys.exit(main())
