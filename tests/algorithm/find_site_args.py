"""Arguments for ``search.find_site`` that the tests of other rules leave neutral."""

import numpy as np

from etswarm.algorithm.former_site import ANY_REACH
from etswarm.algorithm.memory import R_FIELDS

#: ``ri, reach`` for a robot with no former site (``former_site``): any reach.
ANYWHERE = (np.zeros((1, R_FIELDS), dtype=np.int64), ANY_REACH)
