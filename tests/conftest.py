"""Suite-wide settings: on CI (CI=true) hypothesis draws the same examples every run, so a
red main always reproduces; locally it keeps exploring new ones."""

import os

from hypothesis import settings

settings.register_profile("ci", derandomize=True)
if os.environ.get("CI"):
    settings.load_profile("ci")
