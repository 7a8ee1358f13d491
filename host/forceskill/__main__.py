"""``python -m forceskill`` is the ``forceskill`` command."""

import sys

from .cli import main

sys.exit(main())
