"""Helpers shared by the test folders, a package on pytest's path (pytest.ini `pythonpath = tests`),
so any combination of folders runs in one invocation:

- ``paths``: the repository, the scenarios, the golden vectors and the built hil_sim;
- ``canbus``: ``Server``, a running ``hil_sim serve`` on a free port (socketcand);
- ``socketcan``: the same on a SocketCAN interface, skipped where the kernel has none;
- ``recordings``: demonstration files in every format the readers accept;
- ``tools``: imports a script of tools/ as a module.
"""
