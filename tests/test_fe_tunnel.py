"""The eroded share of the tunnel (penetration.fe.shot.tunnel_eroded_share) against exact volumes."""
import numpy as np
import pytest

from penetration.fe.constitutive import Elastic
from penetration.fe.mesh import Grid
from penetration.fe.shot import tunnel_eroded_share
from penetration.fe.model import Controls, Model


@pytest.fixture
def model():
    g = Grid.tensor(np.linspace(0, 0.2, 21), np.linspace(0, 1.0, 101))  # 10 mm elements
    return Model(g, Elastic(2440, 30e9, 0.2), Controls())


def test_a_tunnel_all_eroded_is_one_and_none_is_zero(model):
    assert tunnel_eroded_share(model, 0.07, 0.5) == 0.0
    rc = 0.005 + 0.01 * np.arange(20)
    zc = 0.005 + 0.01 * np.arange(100)
    inside = (zc[:, None] < 0.5) & (rc[None, :] < 0.07)
    model.alive[inside.ravel()] = 0
    assert tunnel_eroded_share(model, 0.07, 0.5) == 1.0
    assert tunnel_eroded_share(model, 0.07, 0.8) == pytest.approx(0.5 / 0.8)  # the depth share


def test_an_eroded_core_counts_by_volume_not_by_elements(model):
    """The inner 4 of the 7 columns inside r = 0.07 m eroded: (4/7)^2 of the volume (49/49 of r^2 dr), 4/7 of the
    elements."""
    cols = np.arange(20)[None, :] < 4
    model.alive[np.broadcast_to(cols, (100, 20)).ravel()] = 0
    assert tunnel_eroded_share(model, 0.07, 1.0) == pytest.approx((0.04 / 0.07) ** 2)
