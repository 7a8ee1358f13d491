"""forceskill: learn interaction force skills from one demonstration (host side).

Packages, lowest first (tools/check_layers.py keeps imports pointing down):
``readers`` (demonstration file formats, ``forceskill.readers`` entry points); ``model`` (pure maths
and formats: ``params``, ``dmp``, ``fit``, ``skill``, ``demo``, ``tolerance``, ``limits``,
``fwimage``, ``synthetic``); ``link`` (the bus, the device's frames, the one UDS client, the
firmware update protocol); ``commands`` (one module per command); ``cli`` (the ``forceskill``
command: parser and dispatch). Beside them: ``errors`` and ``codes`` (numbered codes), ``outputs``
(atomic writes), ``sim`` (finding the HIL simulator), ``plot``.
"""

__version__ = "0.1.0"
