"""yuxi.coarse_grain on a live simulation, held to what the engine itself reports: the grains'
mass, the walls' loads, and the virial of the engine's own forces on every grain."""

import numpy as np
import pytest

import yuxi


@pytest.fixture
def landed(box_scene, tmp_path):
    """343 grains that fell into a box with walls on its six faces, with the contacts of the
    last step recorded."""
    box_scene["run"]["t_end"] = 0.3
    sim = yuxi.Simulation(box_scene, output=tmp_path / "box", progress=False)
    sim.run()
    sim.record_contacts(True)
    sim.step()
    yield sim
    sim.close()


def _grains(sim):
    p = sim.particles
    grain = np.asarray(p.kind) == yuxi.Particles.GRAIN
    return grain, np.asarray(p.mass)[grain]


def test_bins_hold_the_mass_and_the_walls_loads(landed):
    f = yuxi.coarse_grain(landed, function="bins", n=(4, 4, 6))
    _, mass = _grains(landed)
    volume = f["cell_volume"]
    assert f["density"].shape == (4, 4, 6)
    assert f["density"].sum() * volume == pytest.approx(mass.sum(), rel=1e-12)
    # The walls' force density over the box is the force of every wall on the grains: minus the
    # loads that the engine books on the walls.
    loads = landed.wall_loads()
    on_walls = sum(np.asarray(load["force"]) for load in loads.values())
    on_grains = f["wall_force_density"].sum(axis=(0, 1, 2)) * volume
    assert np.allclose(on_grains, -on_walls, rtol=1e-9, atol=1e-9 * np.abs(on_walls).max())
    assert loads["box z lo"]["contacts"] > 10


def test_contact_stress_is_the_virial_of_the_engines_forces(landed):
    """Over a grid that holds every branch, the contact stress integrates to sum f b, and that
    is sum (F_i - m_i g) x_i - sum over wall contacts f c: F_i the engine's force on grain i."""
    f = yuxi.coarse_grain(landed, function="bins", n=(3, 5, 4))
    integral = f["contact_stress"].sum(axis=(0, 1, 2)) * f["cell_volume"]
    grain, mass = _grains(landed)
    p = landed.particles
    x = np.asarray(p.position)[grain]
    force = np.asarray(p.force)[grain]
    g = np.array([0.0, 0.0, -10.0])
    table = landed._core.contacts()
    walls = table["wall"] != ""
    virial = np.einsum("ia,ib->ab", force - mass[:, None] * g, x)
    virial -= np.einsum("ia,ib->ab", table["force"][walls], table["point"][walls])
    scale = np.abs(virial).max()
    assert scale > 0
    assert np.allclose(integral, virial, rtol=0, atol=1e-9 * scale)
    # So does a Gaussian on a grid beyond its reach (cut off at 6 w, sampled at w / 2).
    smooth = yuxi.coarse_grain(landed, width=0.5, cutoff=3.0, lo=[-3.5, -3.5, -3.5],
                               hi=[11.5, 11.5, 15.5], n=(60, 60, 76))
    total = smooth["contact_stress"].sum(axis=(0, 1, 2)) * smooth["cell_volume"]
    assert np.allclose(total, virial, rtol=0, atol=1e-6 * scale)


def test_a_cylindrical_grid_holds_the_mass_the_loads_and_the_virial(landed):
    """Bins of a cylindrical grid about the box's vertical centre line, out past its corners:
    the mass, the walls' vertical force and the virial's trace, which no turn about the axis
    changes, integrate to the engine's."""
    f = yuxi.coarse_grain(landed, function="bins", axis=(4.0, 4.0), lo=(0.0, -0.5),
                          hi=(6.0, 12.5), n=(6, 8, 13))
    assert f["density"].shape == (6, 8, 13)
    assert f["momentum"].shape == (6, 8, 13, 3)
    volume = f["cell_volume"][:, None, None]
    _, mass = _grains(landed)
    assert (f["density"] * volume).sum() == pytest.approx(mass.sum(), rel=1e-12)
    loads = landed.wall_loads()
    on_walls = sum(np.asarray(load["force"]) for load in loads.values())
    assert (f["wall_force_density"][..., 2] * volume).sum() == pytest.approx(-on_walls[2],
                                                                            rel=1e-9)
    trace = np.trace(f["contact_stress"], axis1=-2, axis2=-1)
    cartesian = yuxi.coarse_grain(landed, function="bins", n=(3, 5, 4))
    virial = np.trace(cartesian["contact_stress"].sum(axis=(0, 1, 2))) * cartesian["cell_volume"]
    assert (trace * volume).sum() == pytest.approx(virial, rel=1e-9)
    # A profile in r and z, averaged around the axis: the same mass.
    profile = yuxi.coarse_grain(landed, width=0.5, axis=(4.0, 4.0), lo=(0.0, -2.0),
                                hi=(8.0, 14.0), n=(32, 1, 64), average="theta", contacts=False)
    assert profile["density"].shape == (32, 64)
    assert "theta" not in profile
    cells = profile["cell_volume"][:, None]
    assert (profile["density"] * cells).sum() == pytest.approx(mass.sum(), rel=2e-3)
    with pytest.raises(ValueError, match="average"):
        yuxi.coarse_grain(landed, width=0.5, axis=(4.0, 4.0), average="xy")
    with pytest.raises(ValueError, match="axis"):
        yuxi.coarse_grain(landed, width=0.5, axis=(4.0, 4.0, 1.0))


def test_a_profile_averages_over_the_other_axes(landed):
    f = yuxi.coarse_grain(landed, width=0.5, average="xy", n=(1, 1, 24), contacts=False)
    assert f["z"].shape == (24,) and "x" not in f
    assert f["stress"].shape == (24, 3, 3)
    _, mass = _grains(landed)
    # The grains rest near the floor: the profile's mass is near the bottom, and all of it is
    # there (the Gaussian's tails below the floor are cut off by the grid: most, not all).
    column = f["density"] * 8.0 * 8.0 * (12.0 / 24)
    assert column.sum() == pytest.approx(mass.sum(), rel=0.05)
    assert f["z"][np.argmax(f["density"])] < 4.0


def test_misuse_is_refused_with_the_argument_named(landed, tmp_path, box_scene):
    with pytest.raises(ValueError, match="width"):
        yuxi.coarse_grain(landed, width=0.0)
    with pytest.raises(ValueError, match="needs a width"):
        yuxi.coarse_grain(landed)
    with pytest.raises(ValueError, match="function"):
        yuxi.coarse_grain(landed, width=1.0, function="cubic")
    with pytest.raises(ValueError, match="average"):
        yuxi.coarse_grain(landed, width=1.0, average="q")
    with pytest.raises(ValueError, match="hi"):
        yuxi.coarse_grain(landed, width=1.0, lo=[0, 0, 5], hi=[8, 8, 5])
    with pytest.raises(ValueError, match="need n"):
        yuxi.coarse_grain(landed, function="bins")
    fresh = yuxi.Simulation(box_scene, output=tmp_path / "fresh", progress=False)
    fresh.step()
    with pytest.raises(ValueError, match="record_contacts"):
        yuxi.coarse_grain(fresh, width=1.0)
    assert yuxi.coarse_grain(fresh, width=1.0, contacts=False)["density"].sum() > 0
    fresh.close()


def test_arrays_saved_from_a_run(tmp_path):
    """From plain arrays: two grains pressed together along x by a force of 2, as a contact."""
    arrays = {
        "x": [[1.0, 1.0, 1.0], [1.8, 1.0, 1.0]], "v": np.zeros((2, 3)), "mass": [1.0, 1.0],
        "radius": [0.5, 0.5],
        "box": {"lo": [0, 0, 0], "hi": [3, 2, 2], "periodic": ""},
        "contacts": {"a": [1], "b": [0], "force": [[2.0, 0, 0]], "branch": [[0.8, 0, 0]],
                     "point": [[1.4, 1.0, 1.0]], "elastic": [0.01]},
    }
    f = yuxi.coarse_grain(arrays, function="bins", n=(3, 1, 1), average="yz")
    # The branch from x = 1.0 to 1.8 lies in cells [0, 1) (none), [1, 2) (all): f b / V_cell.
    assert f["contact_stress"][:, 0, 0] == pytest.approx([0.0, 2.0 * 0.8 / 4.0, 0.0])
    assert f["coordination"][1] == pytest.approx(1.0)


def test_a_bed_at_rest_carries_the_weight_above(box_scene, tmp_path):
    """343 grains settled between smooth frictionless side walls (no tangential spring and no
    tangential dashpot: the linear law damps sliding even at mu = 0): at rest, the momentum
    balance is d sigma_zz / dz = -rho g, so sigma_zz(z) is the weight above, g times the
    integral of the density above z. Checked inside the bed, a cutoff above the floor and
    below the surface's fall-off; and the floor carries the grains' weight."""
    box_scene["contact"]["pair"][1].update(mu_s=0.0, mu_d=0.0, gamma_t=0.0)
    for pair in box_scene["contact"]["pair"]:
        pair["gamma_n"] = 200.0
    box_scene["run"]["t_end"] = 6.0
    sim = yuxi.Simulation(box_scene, output=tmp_path / "bed", progress=False)
    sim.run()
    books = sim.energies()
    assert books["translational"] < 0.01 * books["elastic"]  # at rest
    sim.record_contacts(True)
    sim.step()
    _, mass = _grains(sim)
    g = 10.0
    floor = sim.wall_loads()["box z lo"]["force"][2]
    assert -floor == pytest.approx(mass.sum() * g, rel=0.01)
    f = yuxi.coarse_grain(sim, width=0.5, average="xy", n=(1, 1, 96))
    z, rho, h = f["z"], f["density"], f["z"][1] - f["z"][0]
    weight_above = g * (np.cumsum(rho[::-1])[::-1] - rho / 2) * h
    inside = (z > 1.5) & (z < 4.0)
    assert inside.sum() > 15
    assert np.allclose(f["stress"][inside, 2, 2], weight_above[inside], rtol=0.01)
    # Side walls without friction carry no weight.
    for name in ("box x lo", "box x hi", "box y lo", "box y hi"):
        assert abs(sim.wall_loads()[name]["force"][2]) < 1e-9 * mass.sum() * g
    sim.close()


@pytest.mark.parametrize("function", ["gaussian", "lucy"])
def test_fields_of_a_falling_pile_satisfy_the_balances(box_scene, tmp_path, function):
    """Grains landing on the floor, in full motion: d rho/dt + div(rho V) and d(rho V)/dt +
    div(rho V V + sigma) - rho g - t vanish, the time derivatives from the steps before and
    after, the divergences by central differences on a grid of w / 4: what is left is the
    differences' truncation, 2 to 3 % of the balance's terms (docs/coarse-graining.md)."""
    box_scene["run"]["t_end"] = 1.0
    sim = yuxi.Simulation(box_scene, output=tmp_path / "pile", progress=False)
    sim.run()
    dt = sim.dt
    grid = dict(width=0.8, n=(40, 40, 60), function=function)
    before = yuxi.coarse_grain(sim, contacts=False, **grid)
    sim.record_contacts(True)
    sim.step()
    now = yuxi.coarse_grain(sim, **grid)
    sim.step()
    after = yuxi.coarse_grain(sim, contacts=False, **grid)
    sim.close()
    h = [now["x"][1] - now["x"][0], now["y"][1] - now["y"][0], now["z"][1] - now["z"][0]]
    inner = (slice(3, -3),) * 3  # (one-sided differences at the grid's edges)

    def divergence(field):  # of a vector (..., 3) or of a tensor's rows (..., 3, 3)
        return sum(np.gradient(field[..., b], h[b], axis=b) for b in range(3))

    density_rate = (after["density"] - before["density"]) / (2 * dt)
    mass = density_rate + divergence(now["momentum"])
    assert np.abs(mass[inner]).max() < 0.05 * np.abs(density_rate[inner]).max()
    rate = (after["momentum"] - before["momentum"]) / (2 * dt)
    v = now["velocity"]
    flux = now["density"][..., None, None] * v[..., :, None] * v[..., None, :] + now["stress"]
    flux_divergence = divergence(flux)  # sum over b of d flux[a, b] / dx_b
    gravity = now["density"][..., None] * np.array([0.0, 0.0, -10.0])
    residual = rate + flux_divergence - gravity - now["wall_force_density"]
    scale = np.abs(flux_divergence[inner]).max()
    assert np.abs(rate[inner]).max() > 0.5 * scale  # a flow, not a bed at rest
    assert np.abs(residual[inner]).max() < 0.03 * scale


def test_a_run_writes_its_coarse_grain_tables(box_scene, tmp_path):
    """[[coarse_grain]] tables: a CSV and a VTK image per sample and a .pvd series, the same
    fields that yuxi.coarse_grain gives at that step, and the bins' mass the grains'."""
    box_scene["run"]["t_end"] = 0.3
    box_scene["coarse_grain"] = [
        {"name": "cells", "function": "bins", "n": [4, 4, 6], "interval": 0.1},
        {"name": "profile", "width": 0.5, "average": "xy", "n": [1, 1, 24], "interval": 0.1,
         "fields": ["density", "stress"]},
    ]
    sim = yuxi.Simulation(box_scene, output=tmp_path / "run", progress=False)
    sim.record_contacts(True)
    sim.run()
    assert sim.step_count == 1500
    folder = tmp_path / "run" / "coarse_grain"
    cells = np.genfromtxt(folder / "cells" / "cells_000001500.csv", delimiter=",", names=True)
    _, mass = _grains(sim)
    assert cells["density"].sum() * 8.0 == pytest.approx(mass.sum(), rel=1e-9)
    profile = np.genfromtxt(folder / "profile" / "profile_000001500.csv", delimiter=",",
                            names=True)
    assert profile.dtype.names == ("x", "y", "z", "density", *(
        f"stress_{a}{b}" for a in "xyz" for b in "xyz"))
    now = yuxi.coarse_grain(sim, width=0.5, average="xy", n=(1, 1, 24))
    assert np.allclose(profile["z"], now["z"])
    assert np.allclose(profile["stress_zz"], now["stress"][:, 2, 2], rtol=1e-9,
                       atol=1e-9 * np.abs(now["stress"]).max())
    series = (folder / "profile" / "profile.pvd").read_text()
    assert series.count("<DataSet") == 3 and "profile_000000500.vti" in series
    image = (folder / "profile" / "profile_000001500.vti").read_text()
    assert 'WholeExtent="0 0 0 0 0 23"' in image and 'Name="stress" NumberOfComponents="9"' in image
    sim.close()


def test_a_run_writes_a_cylindrical_table(box_scene, tmp_path):
    """A [[coarse_grain]] table about a vertical axis, averaged around it: CSV by r, theta, z
    and a VTK structured grid for ParaView."""
    box_scene["run"]["t_end"] = 0.3
    box_scene["coarse_grain"] = [
        {"name": "rz", "width": 0.5, "axis": [4.0, 4.0], "lo": [0.0, 0.0], "hi": [4.0, 12.0],
         "n": [8, 1, 24], "average": "theta", "interval": 0.3, "fields": ["density", "stress"]},
    ]
    sim = yuxi.Simulation(box_scene, output=tmp_path / "run", progress=False)
    sim.run()
    folder = tmp_path / "run" / "coarse_grain" / "rz"
    written = np.genfromtxt(folder / "rz_000001500.csv", delimiter=",", names=True)
    assert written.dtype.names[:4] == ("r", "theta", "z", "density")
    sim.close()
    grid = (folder / "rz_000001500.vts").read_text()
    assert '<StructuredGrid WholeExtent="0 7 0 0 0 23">' in grid and "<Points>" in grid
    assert "rz_000001500.vts" in (folder / "rz.pvd").read_text()
    assert len(written) == 8 * 24 and written["density"].max() > 0


def test_a_cylindrical_table_matches_the_call(box_scene, tmp_path):
    box_scene["run"]["t_end"] = 0.3
    table = {"name": "rz", "width": 0.5, "axis": [4.0, 4.0], "lo": [0.0, 0.0],
             "hi": [4.0, 12.0], "n": [8, 6, 24], "interval": 0.1, "fields": ["density", "stress"]}
    box_scene["coarse_grain"] = [table]
    sim = yuxi.Simulation(box_scene, output=tmp_path / "run", progress=False)
    sim.record_contacts(True)
    sim.run()
    written = np.genfromtxt(tmp_path / "run" / "coarse_grain" / "rz" / "rz_000001500.csv",
                            delimiter=",", names=True)
    now = yuxi.coarse_grain(sim, width=0.5, axis=(4.0, 4.0), lo=(0.0, 0.0), hi=(4.0, 12.0),
                            n=(8, 6, 24))
    # The CSV's rows run r fastest, then theta, then z: the call's arrays are [r, theta, z].
    density = now["density"].transpose(2, 1, 0).ravel()
    assert np.allclose(written["density"], density, rtol=1e-9, atol=1e-12)
    stress = now["stress"][..., 0, 2].transpose(2, 1, 0).ravel()  # sigma_rz
    assert np.allclose(written["stress_xz"], stress, rtol=1e-9,
                       atol=1e-9 * np.abs(now["stress"]).max())
    sim.close()


@pytest.mark.parametrize("table, key, message", [
    ({"name": "a", "width": 0.0}, "width", "must be > 0"),
    ({"name": "a", "width": 1.0, "lo": [20, 0, 0], "hi": [30, 8, 12]}, "lo", "outside the box"),
    ({"name": "a", "width": 1.0, "fields": ["density", "pressure"]}, "fields", "pressure"),
    ({"name": "a", "function": "bins"}, "n", "cells"),
    ({"name": "a/b", "width": 1.0}, "name", "folder"),
    ({"name": "a", "width": 1.0, "average": "xyz"}, "average", "resolve one"),
    ({"name": "a", "width": 1.0, "function": "cubic"}, "function", "cubic"),
    ({"name": "a", "width": 1.0, "axis": [4.0]}, "axis", "two numbers"),
    ({"name": "a", "width": 1.0, "axis": [4.0, 4.0], "lo": [0, 0, 0]}, "lo", "r and z"),
    ({"name": "a", "width": 1.0, "axis": [4.0, 4.0], "lo": [-1, 0]}, "lo", "0 or more"),
    ({"name": "a", "width": 1.0, "axis": [4.0, 4.0], "average": "xy"}, "average", "theta"),
    ({"name": "a", "function": "bins", "axis": [4.0, 4.0]}, "n", "r, theta, z"),
])
def test_a_bad_coarse_grain_table_names_its_key(box_scene, table, key, message):
    box_scene["coarse_grain"] = [table]
    with pytest.raises(yuxi.SceneError, match=message) as refused:
        yuxi.Scene(box_scene)
    assert refused.value.key == f"coarse_grain[1].{key}"  # (tables count from 1)


def test_a_table_averages_over_a_window(box_scene, tmp_path):
    """average_every = 1: each write is the mean of every step's sums since the last, so its
    density and contact stress (sums, not ratios) are the means of the steps' fields."""
    box_scene["run"]["t_end"] = 0.3
    box_scene["coarse_grain"] = [{"name": "mean", "width": 0.5, "average": "xy",
                                  "n": [1, 1, 24], "interval": 0.01, "average_every": 1}]
    sim = yuxi.Simulation(box_scene, output=tmp_path / "run", progress=False)
    sim.record_contacts(True)
    sim.run(t_end=0.29)
    assert sim.step_count == 1450
    density, stress = 0.0, 0.0
    for _ in range(50):
        sim.step()
        f = yuxi.coarse_grain(sim, width=0.5, average="xy", n=(1, 1, 24))
        density = density + f["density"] / 50
        stress = stress + f["contact_stress"][:, 2, 2] / 50
    table = np.genfromtxt(tmp_path / "run" / "coarse_grain" / "mean" / "mean_000001500.csv",
                          delimiter=",", names=True)
    assert np.allclose(table["density"], density, rtol=1e-9, atol=1e-12 * density.max())
    assert np.allclose(table["contact_stress_zz"], stress, rtol=1e-9,
                       atol=1e-9 * np.abs(stress).max())
    assert np.abs(stress).max() > 0
    sim.close()


# A linear spring-dashpot pair of the two-grain scenes below.
_LINEAR_PAIR = {"k_n": 2.0e4, "k_t": 5.7e3, "gamma_n": 60.0, "gamma_t": 20.0, "mu_s": 0.5,
                "mu_d": 0.5}


def _books_around_a_recorded_step(sim, t_end):
    """Runs to t_end, then one step with its contacts recorded: the books before and after."""
    sim.run(t_end=t_end)
    before = sim.energies()
    sim.record_contacts(True)
    sim.step()
    return before, sim.energies()


def _two_contacts(model):
    """Grains a and b meeting head-on, and grain c landing on the floor, without gravity: both
    contacts start at t = 0.025, and at 0.027 neither has ended (the thermodynamic law's, the
    shorter, last about 0.007)."""
    scene = {
        "materials": ["grain", "wall"],
        "run": {"name": "two-contacts", "dt": 2.0e-4, "t_end": 0.05},
        "output": {"energy_interval": 0.01, "snapshot_interval": 0.0},
        "domain": {"lo": [0.0, 0.0, 0.0], "hi": [8.0, 8.0, 8.0], "gravity": [0.0, 0.0, 0.0],
                   "boundary": ["wall", "wall", "wall"], "wall_material": "wall"},
        "particle": [
            {"position": [3.0, 4.0, 5.0], "velocity": [1.0, 0.1, 0.0], "radius": 0.5,
             "density": 1.909859317, "material": "grain"},
            {"position": [4.05, 4.0, 5.0], "velocity": [-1.0, 0.0, 0.0], "radius": 0.5,
             "density": 1.909859317, "material": "grain"},
            {"position": [6.0, 6.0, 0.525], "velocity": [0.3, 0.0, -1.0], "radius": 0.5,
             "density": 1.909859317, "material": "grain"}],
    }
    if model == "linear":
        pair = _LINEAR_PAIR
        scene["material"] = {"grain": {"density": 1.909859317}}
        scene["contact"] = {"model": "linear",
                            "pair": [dict(pair, materials=["grain", "grain"]),
                                     dict(pair, materials=["grain", "wall"])]}
    else:
        scene["material"] = {"grain": {"youngs_modulus": 4.55e6, "poisson_ratio": 0.3},
                             "wall": {"youngs_modulus": 1.82e7, "poisson_ratio": 0.3}}
        scene["contact"] = {"model": "thermodynamic", "pair": [
            {"materials": ["grain", "grain"], "friction": 0.5, "eta_hat": 0.3,
             "eta_power": 0.5, "lambda_hat": 10.0, "tau_hat": 5.0},
            {"materials": ["grain", "wall"], "friction": 0.5}]}
    return scene


@pytest.mark.parametrize("model", ["linear", "thermodynamic"])
def test_dissipation_and_relaxation_densities_hold_the_books(model, tmp_path):
    """Over bins that cover the box, the dissipation rate density integrates to the energy the
    books dissipate over the step, divided by it, and the relaxation energy density to the
    books' relaxation energy (two contacts, neither ending in the step)."""
    sim = yuxi.Simulation(_two_contacts(model), output=tmp_path / "run", progress=False)
    before, after = _books_around_a_recorded_step(sim, 0.027)
    assert after["contacts"] == 2
    f = yuxi.coarse_grain(sim, function="bins", n=(4, 4, 4))
    volume = f["cell_volume"]
    rate = (after["dissipated"] - before["dissipated"]) / sim.dt
    assert rate > 0
    assert f["dissipation_rate_density"].sum() * volume == pytest.approx(rate, rel=1e-9)
    relaxation = f["relaxation_energy_density"].sum() * volume
    assert relaxation == pytest.approx(after["relaxation"], rel=1e-9, abs=1e-300)
    if model == "thermodynamic":
        assert after["relaxation"] > 0
    sim.close()


def test_wall_power_density_holds_the_books(tmp_path):
    """Over bins that cover the box, the walls' power density integrates to the work the books
    credit to the moving walls over the step, divided by it: a floor that oscillates along its
    normal under two grains, one of them also pressed against a turning cylinder (a shaped wall
    whose surface slides past it)."""
    pair = _LINEAR_PAIR
    grain = {"radius": 0.5, "density": 1.909859317, "material": "grain"}
    scene = {
        "materials": ["grain", "wall"],
        "run": {"name": "wall-power", "dt": 1.0e-4, "t_end": 0.05},
        "output": {"energy_interval": 0.01, "snapshot_interval": 0.0},
        "domain": {"lo": [0.0, 0.0, 0.0], "hi": [10.0, 10.0, 4.0], "gravity": [0.0, 0.0, -10.0],
                   "boundary": ["open", "open", "open"]},
        "material": {"grain": {"density": 1.909859317}},
        "contact": {"model": "linear", "pair": [dict(pair, materials=["grain", "grain"]),
                                                dict(pair, materials=["grain", "wall"])]},
        "plane": [{"point": [0.0, 0.0, 0.5], "normal": [0.0, 0.0, 1.0], "material": "wall",
                   "amplitude": 0.001, "omega": 50.0}],
        "cylinder": [{"center": [5.0, 5.0, 0.0], "radius": 2.0, "omega": 5.0,
                      "material": "wall"}],
        "particle": [dict(grain, position=[5.0, 5.0, 0.9995]),
                     dict(grain, position=[6.505, 5.0, 0.9995])],
    }
    sim = yuxi.Simulation(scene, output=tmp_path / "run", progress=False)
    before, after = _books_around_a_recorded_step(sim, 0.002)
    assert after["contacts"] == 3
    f = yuxi.coarse_grain(sim, function="bins", n=(10, 10, 16))
    power = (after["wall_work"] - before["wall_work"]) / sim.dt
    assert power != 0
    assert f["wall_power_density"].sum() * f["cell_volume"] == pytest.approx(power, rel=1e-9)
    # The turning cylinder's share: its contact point lies at z = 1, the floor's at z = 0.5.
    cylinder = f["wall_power_density"][:, :, 3].sum() * f["cell_volume"]
    assert cylinder > 0  # friction drags the grain along the sliding surface
    sim.close()
