"""Shared scenes of the Python API's tests: small, so that each test takes seconds."""
import copy
import os

import pytest

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))

_PAIR = {"k_n": 2.0e4, "k_t": 5.7e3, "gamma_n": 60.0, "gamma_t": 20.0, "mu_s": 0.5, "mu_d": 0.5}

# A box with a floor and 343 grains on a lattice, falling under gravity: contacts within a few
# hundred steps.
BOX = {
    "materials": ["grain", "wall"],
    "material": {"grain": {"density": 1.909859317}},
    "run": {"name": "box", "dt": 2.0e-4, "t_end": 0.2},
    "output": {"energy_interval": 0.01, "snapshot_interval": 0.1},
    "domain": {"lo": [0.0, 0.0, 0.0], "hi": [8.0, 8.0, 12.0], "gravity": [0.0, 0.0, -10.0],
               "boundary": ["wall", "wall", "wall"], "wall_material": "wall"},
    "contact": {
        "model": "linear",
        "pair": [
            dict(_PAIR, materials=["grain", "grain"]),
            dict(_PAIR, materials=["grain", "wall"]),
        ],
    },
    "fill": [{
        "material": "grain",
        "radius": 0.5,
        "count": 343,
        "placement": "lattice",
        "jitter": 0.02,
        "region": {"shape": "box", "lo": [0.2, 0.2, 0.2], "hi": [7.8, 7.8, 11.5]},
    }],
}


@pytest.fixture
def box_scene():
    return copy.deepcopy(BOX)


BOX_TOML = """\
materials = ["grain", "wall"]
[material.grain]
density = 1.909859317
[run]
name = "box"
dt = 2.0e-4
t_end = 0.2
[output]
energy_interval = 0.01
snapshot_interval = 0.1
[domain]
lo = [0.0, 0.0, 0.0]
hi = [8.0, 8.0, 12.0]
gravity = [0.0, 0.0, -10.0]
boundary = ["wall", "wall", "wall"]
wall_material = "wall"
[contact]
model = "linear"
[[contact.pair]]
materials = ["grain", "grain"]
k_n = 2.0e4
k_t = 5.7e3
gamma_n = 60.0
gamma_t = 20.0
mu_s = 0.5
mu_d = 0.5
[[contact.pair]]
materials = ["grain", "wall"]
k_n = 2.0e4
k_t = 5.7e3
gamma_n = 60.0
gamma_t = 20.0
mu_s = 0.5
mu_d = 0.5
[[fill]]
material = "grain"
radius = 0.5
count = 343
placement = "lattice"
jitter = 0.02
region = { shape = "box", lo = [0.2, 0.2, 0.2], hi = [7.8, 7.8, 11.5] }
"""


def add_square_mesh(scene, folder, name, height, **keys):
    """Adds a [[mesh]] to the box scene: a square of side 7.8 (two triangles, binary STL)
    centred over the box at `height`."""
    import yuxi

    stl = folder / f"{name}.stl"
    yuxi.write_stl(stl, yuxi.square(3.9, 0.0))
    scene.setdefault("mesh", []).append(dict({"name": name, "file": str(stl), "material": "wall",
                                              "translate": [4.0, 4.0, height]}, **keys))
