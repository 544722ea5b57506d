import numpy as np
import pytest

from chainchaos import random_chain


@pytest.fixture(scope="session")
def chain():
    """An alpha = 5 chain whose mode 34 is localised at site 21 (a candidate of DESIGN section 4)."""
    return random_chain(879, 5.0)


@pytest.fixture(scope="session")
def homogeneous():
    from chainchaos import Chain

    return Chain(np.ones(40), 1.0)
