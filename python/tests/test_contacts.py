"""Contacts as arrays: partners, geometry, forces and each contact model's state."""
import numpy as np
import pytest

import yuxi
from conftest import add_square_mesh


def settled_contacts(scene, tmp_path, steps=1500):
    sim = yuxi.Simulation(scene, output=tmp_path / "out", progress=False)
    sim.record_contacts(True)
    sim.step(steps)
    return sim, sim.contacts()


def test_contacts_come_as_arrays(box_scene, tmp_path):
    sim, c = settled_contacts(box_scene, tmp_path)
    n = len(c["id_a"])
    assert n > 0
    for name in ("force", "normal", "point"):
        assert c[name].shape == (n, 3), name
    assert (c["overlap"] > 0).all()
    assert np.allclose(np.linalg.norm(c["normal"], axis=1), 1.0, rtol=0, atol=1e-12)
    floor = c["wall"] == "box z lo"
    assert floor.any() and (c["id_b"][floor] == -1).all() and (c["element"] == -1).all()
    # The floor pushes the grains up, from its surface at z = 0.
    assert (c["force"][floor][:, 2] > 0).all()
    assert np.allclose(c["point"][floor][:, 2], 0.0, atol=1e-12)
    # A pair's normal points from id_b to id_a, and its point lies between their centres.
    pairs = c["id_b"] >= 0
    x = dict(zip(sim.particles.id.tolist(), sim.particles.position.copy()))
    a = np.array([x[i] for i in c["id_a"][pairs]])
    b = np.array([x[i] for i in c["id_b"][pairs]])
    d = a - b
    assert np.allclose(c["normal"][pairs], d / np.linalg.norm(d, axis=1)[:, None], atol=1e-12)
    assert np.allclose(c["point"][pairs], 0.5 * (a + b), atol=1e-9)  # equal radii
    sim.close()


def test_linear_springs_obey_coulomb_and_stay_in_the_tangent_plane(box_scene, tmp_path):
    mu_s = 0.2
    for pair in box_scene["contact"]["pair"]:
        pair.update(mu_s=mu_s, mu_d=mu_s)
    sim, c = settled_contacts(box_scene, tmp_path)
    st = c["state"]
    assert list(st) == ["tangential_spring", "tangential_sliding", "tangential_stiffness",
                        "rolling_spring", "rolling_sliding", "rolling_stiffness"]
    s, n = st["tangential_spring"], c["normal"]
    assert s.shape == (len(n), 3) and st["tangential_sliding"].shape == (len(n),)
    # Each touching contact's spring has the scene's k_t ...
    assert (st["tangential_stiffness"] == 5.7e3).all()
    # ... lies in the plane normal to the contact (docs/scene-format.md, tangential_carry) ...
    spring = np.linalg.norm(s, axis=1)
    assert spring.max() > 0
    assert np.abs((s * n).sum(axis=1)).max() <= 1e-9 * spring.max()
    # ... and its force k_t |s| keeps to the Coulomb limit mu_s F_n (friction_cap = spring).
    f_n = (c["force"] * n).sum(axis=1)
    assert (5.7e3 * spring <= mu_s * np.abs(f_n) * (1 + 1e-9)).all()
    sim.close()


def test_cylinder_contacts_lie_on_its_surface_and_add_up_to_its_load(box_scene, tmp_path):
    radius = 3.5
    box_scene["cylinder"] = [{"name": "silo", "center": [4.0, 4.0, 0.0], "radius": radius,
                              "lo": 0.1, "hi": 11.9, "material": "wall"}]
    del box_scene["fill"][0]["jitter"]
    box_scene["fill"][0].update(count=150, placement="random", seed=7,
                                region={"shape": "cylinder", "center": [4.0, 4.0, 0.0],
                                        "radius": radius - 0.05, "lo": 0.15, "hi": 11.85})
    sim, c = settled_contacts(box_scene, tmp_path, steps=6000)
    silo = c["wall"] == "silo"
    side, cap = silo & (c["element"] == 0), silo & (c["element"] == 1)
    assert side.any() and cap.any() and (c["id_b"][silo] == -1).all()
    # Side contacts: the point on the mantle, the normal pointing in to the axis.
    p = c["point"][side]
    r = np.hypot(p[:, 0] - 4.0, p[:, 1] - 4.0)
    assert np.allclose(r, radius, rtol=0, atol=1e-9)
    inward = -(p[:, :2] - 4.0) / r[:, None]
    assert np.allclose(c["normal"][side][:, :2], inward, atol=1e-9)
    # Bottom cap: the point on it, the normal straight up.
    assert np.allclose(c["point"][cap][:, 2], 0.1, atol=1e-12)
    assert np.allclose(c["normal"][cap], [0.0, 0.0, 1.0], atol=1e-12)
    # The contacts' forces on the grains sum to minus the grains' force on the wall.
    load = sim.wall_loads()["silo"]
    assert np.allclose(c["force"][silo].sum(axis=0), -np.asarray(load["force"]),
                       rtol=1e-12, atol=1e-12 * np.abs(load["force"]).max())
    assert silo.sum() == load["contacts"]
    sim.close()


def test_mesh_contacts_name_their_triangles(box_scene, tmp_path):
    add_square_mesh(box_scene, tmp_path, "floor", 0.05)
    sim, c = settled_contacts(box_scene, tmp_path)
    floor = c["wall"] == "floor"
    assert floor.any() and (c["wall"] != "box z lo").all()
    assert set(c["element"][floor].tolist()) <= {0, 1}
    assert np.allclose(c["point"][floor][:, 2], 0.05, atol=1e-12)
    assert np.allclose(c["normal"][floor], [0.0, 0.0, 1.0], atol=1e-12)
    # The tangential springs of mesh contacts are kept like any other contact's.
    assert np.linalg.norm(c["state"]["tangential_spring"][floor], axis=1).max() > 0
    assert np.allclose(c["force"][floor].sum(axis=0), -np.asarray(sim.wall_loads()["floor"]["force"]),
                       rtol=1e-12)
    sim.close()


def test_thermodynamic_state_holds_its_elastic_energy_and_yield_limit(box_scene, tmp_path):
    youngs, poisson, mu = 1.0e6, 0.3, 0.5
    box_scene["material"] = {
        "grain": {"density": 1.909859317, "youngs_modulus": youngs, "poisson_ratio": poisson},
        "wall": {"youngs_modulus": youngs, "poisson_ratio": poisson},
    }
    box_scene["contact"] = {"model": "thermodynamic", "pair": [
        {"materials": ["grain", "grain"], "friction": mu},
        {"materials": ["grain", "wall"], "friction": mu},
    ]}
    sim, c = settled_contacts(box_scene, tmp_path)
    st = c["state"]
    assert list(st) == ["un", "ut", "w_relax", "stored", "n_prev", "delta_prev", "owed",
                        "owed_energy"]
    un, ut = st["un"], st["ut"]
    assert (un < 0).all() and (st["w_relax"] >= 0).all()
    # w = k (-u_n)^(1/2) ((2/5) u_n^2 + |u_t|^2 / xi), k = (4/3) E* sqrt(R*), xi = 2 / mu^2
    # (docs/scene-format.md, "thermodynamic"); E* of two equal materials is E / (2 (1 - nu^2)).
    e_star = youngs / (2 * (1 - poisson**2))
    r_star = np.where(c["id_b"] >= 0, 0.25, 0.5)  # radius 0.5: grain pairs, grain and wall
    k = 4.0 / 3.0 * e_star * np.sqrt(r_star)
    xi = 2.0 / mu**2
    w = k * np.sqrt(-un) * (0.4 * un**2 + (ut**2).sum(axis=1) / xi)
    assert np.allclose(w, c["elastic"], rtol=1e-9, atol=0)
    assert np.allclose(st["stored"], c["elastic"], rtol=1e-12, atol=0)
    # The yield limit |u_t| <= sqrt(2 xi) (-u_n) holds.
    assert (np.linalg.norm(ut, axis=1) <= np.sqrt(2 * xi) * -un * (1 + 1e-9)).all()
    sim.close()


@pytest.mark.parametrize("model,fields", [
    ("hooke", []),
    ("luding", ["delta_max", "delta", "f_hys", "stored_n", "tangential_spring"]),
])
def test_every_model_names_its_state(box_scene, tmp_path, model, fields):
    pair = {"hooke": {"k_n": 2.0e4, "gamma_n": 60.0},
            "luding": {"k1": 2.0e4, "kp": 4.0e4, "gamma_n": 60.0, "k_t": 5.7e3, "mu_s": 0.5}}
    box_scene["contact"] = {"model": model, "pair": [
        dict(pair[model], materials=["grain", "grain"]),
        dict(pair[model], materials=["grain", "wall"]),
    ]}
    sim, c = settled_contacts(box_scene, tmp_path)
    assert list(c["state"])[:len(fields)] == fields
    if model == "luding":
        # The largest overlap reached is at least the overlap now.
        assert (c["state"]["delta_max"] >= c["overlap"] * (1 - 1e-9)).all()
    sim.close()
