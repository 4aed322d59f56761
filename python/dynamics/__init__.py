"""Robot dynamics with NumPy, and the sim-to-real gap diagnosis.

>>> import dynamics, numpy as np
>>> arm = dynamics.Robot("panda")
>>> tau = arm.rnea(np.zeros(7), np.zeros(7), np.zeros(7))   # (7,)
>>> M = arm.mass_matrix(np.zeros((100, 7)))                   # (100, 7, 7)

Every method takes one state ``(N,)`` or a batch ``(B, N)``; batches run
without the GIL, over threads above ``PARALLEL_FROM`` states. See
``docs/python.md`` in the repository for the whole API.
"""

from ._dynamics import PARALLEL_FROM, Robot, robots

__all__ = ["PARALLEL_FROM", "Robot", "robots"]
