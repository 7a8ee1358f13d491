"""Pure maths and formats of forceskill: no bus, no command line.

``dmp`` (the force DMP and its rollout), ``params`` (gains and the derived DMP constants), ``skill``
(the skill image), ``fit`` (learning a skill from a demonstration), ``demo`` (demonstrations: load,
validate, resample), ``tolerance`` (approximation error, kernel search), ``limits`` (force limit,
scale and step checks), ``fwimage`` (signed firmware images), ``synthetic`` (generated demonstrations).
"""
