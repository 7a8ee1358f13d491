"""CAN commands of the forceskill CLI (record, upload, run, status, monitor): each module has
``register(subparsers)`` and is listed in ``forceskill.cli.COMMAND_MODULES``."""
