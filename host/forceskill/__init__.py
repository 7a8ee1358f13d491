"""forceskill: learn interaction force skills from one demonstration (host side).

Modules: ``params`` (gains -> DMP constants), ``dmp`` (the numpy reference of the firmware's DMP),
``fit`` (learning from a demonstration), ``skill`` (the image v2 and its JSON twin), ``demo``
(loading and validating demonstrations), ``readers`` (file formats, ``forceskill.readers`` entry
points), ``tolerance`` (error at the recorded samples, kernel count from a tolerance), ``plot``,
``cli`` (the ``forceskill`` command).
"""

__version__ = "0.1.0"
