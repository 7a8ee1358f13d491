"""forceskill: learn interaction force skills from one demonstration (host side).

Modules: ``params`` (gains -> DMP constants), ``dmp`` (the numpy reference of the firmware's DMP),
``fit`` (learning from a demonstration), ``skill`` (the image v1 and its JSON twin), ``demo``
(reading demonstrations), ``plot``, ``cli`` (the ``forceskill`` command).
"""

__version__ = "0.1.0"
