"""Continuum fields from grains: ``yuxi.coarse_grain`` (the definitions: docs/coarse-graining.md)."""

import math

import numpy as np

from . import _yuxi

# The fields that need the contacts.
CONTACT_FIELDS = ("contact_stress", "wall_force_density", "coordination", "fabric",
                  "elastic_energy_density", "dissipation_rate_density", "wall_power_density",
                  "relaxation_energy_density")


def coarse_grain(source, width=None, function="gaussian", cutoff=None, n=None, lo=None, hi=None,
                 average="", contacts=True, axis=None):
    """Coarse-grained fields of a simulation's grains now, or of arrays saved from one.

    ``source`` is a :class:`yuxi.Simulation` (its grains, and the contacts of its last step: call
    ``sim.record_contacts(True)`` before that step; on several ranks a collective call, every
    rank getting the fields of the whole) or a dict of arrays: ``x``, ``v`` (n, 3),
    ``mass`` (n,), ``radius`` or ``volume`` (n,), and optionally ``contacts`` (a dict with ``a``,
    ``b`` (grain indices, b = -1 for a wall), ``force`` on a, ``branch`` to a's centre from b's
    centre or from the wall's contact point, ``point``; optionally ``elastic``, ``dissipation``,
    ``relaxation``, ``wall_power``) and ``box`` (``lo``, ``hi``,
    ``periodic``, such as "xy").

    ``function`` is "gaussian" (standard deviation ``width``, cut off at ``cutoff``, 3 width by
    default), "lucy" (radius ``cutoff``, 3 width by default) or "bins" (plain cells, no width).
    The grid has ``n`` = (nx, ny, nz) points between ``lo`` and ``hi`` (the box by default; ``n``
    by default one point per width); ``average`` names the axes averaged over ("xy" for a
    profile along z). With ``contacts=False`` only the kinetic fields are computed.

    With ``axis`` = (x0, y0) the grid is cylindrical, about the vertical line through that point:
    ``lo`` = (r_lo, z_lo) and ``hi`` = (r_hi, z_hi) (by default from the axis to the box's farthest
    corner, and the box's height), ``n`` = (n_r, n_theta, n_z), and ``average`` names "theta",
    "z" or both (a profile in r and z: "theta"). Its arrays are indexed [i, j, k] over r, theta
    and z (the resolved ones), with coordinates ``r``, ``theta``, ``z``; vectors and tensors are
    in the local basis (e_r, e_theta, e_z); ``cell_volume`` is then an array over r.

    Returns a dict of numpy arrays indexed [i, j, k] over the resolved axes (then a vector's or
    tensor's components): the points' coordinates ``x``, ``y``, ``z`` (resolved axes only),
    ``density``, ``number_density``, ``volume_fraction``, ``momentum``, ``velocity``,
    ``kinetic_stress``, ``contact_stress``, ``stress`` (positive in compression),
    ``wall_force_density``, ``temperature``, ``coordination``, ``fabric``,
    ``kinetic_energy_density``, ``elastic_energy_density``, ``dissipation_rate_density``,
    ``relaxation_energy_density``, ``wall_power_density`` and ``cell_volume``.
    """
    arrays = _from_simulation(source, contacts) if hasattr(source, "_core") else \
        _from_dict(source, contacts)
    box = arrays["box"]
    if axis is not None:
        return _cylinder(arrays, width, function, cutoff, n, lo, hi, average, axis)
    lo = np.asarray(box["lo"] if lo is None else lo, dtype=float)
    hi = np.asarray(box["hi"] if hi is None else hi, dtype=float)
    if lo.shape != (3,) or hi.shape != (3,):
        raise ValueError("coarse_grain: lo and hi take three values (x, y, z)")
    if _needs_points(function, width, n):
        n = [max(1, math.ceil((h - l) / width)) for l, h in zip(lo, hi)]
    elif n is None:
        raise ValueError("coarse_grain: plain bins need n, the number of cells along each axis")
    n = [int(k) for k in n]
    if len(n) != 3:
        raise ValueError("coarse_grain: n takes three values (x, y, z)")
    # A periodic axis wraps where the grid spans the box along it.
    periodic = "".join(a for k, a in enumerate("xyz") if a in box.get("periodic", "")
                       and lo[k] == box["lo"][k] and hi[k] == box["hi"][k])
    return _yuxi.coarse_grain(arrays["x"], arrays["v"], arrays["mass"], arrays["volume"],
                              arrays["contacts"], function, float(width or 0.0), cutoff, lo, hi,
                              n, average, periodic, arrays.get("reduce"))


def _needs_points(function, width, n):
    """Checks a function's width; whether n is to be chosen from it (one point per width)."""
    if function == "bins":
        return False
    if width is None:
        raise ValueError(f"coarse_grain: the {function} function needs a width")
    if not width > 0:
        raise ValueError(f"coarse_grain: width must be positive (got {width})")
    return n is None


def _cylinder(arrays, width, function, cutoff, n, lo, hi, average, axis):
    box = arrays["box"]
    axis = np.asarray(axis, dtype=float)
    if axis.shape != (2,):
        raise ValueError("coarse_grain: axis takes two values (x, y)")
    if lo is None:
        lo = (0.0, box["lo"][2])
    if hi is None:
        corners = [(x, y) for x in (box["lo"][0], box["hi"][0]) for y in (box["lo"][1], box["hi"][1])]
        hi = (max(math.hypot(x - axis[0], y - axis[1]) for x, y in corners), box["hi"][2])
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    if lo.shape != (2,) or hi.shape != (2,):
        raise ValueError("coarse_grain: on a cylindrical grid lo and hi take two values (r, z)")
    if _needs_points(function, width, n):
        n = [max(1, math.ceil((hi[0] - lo[0]) / width)),
             max(1, math.ceil(2 * math.pi * hi[0] / width)),
             max(1, math.ceil((hi[1] - lo[1]) / width))]
    elif n is None:
        raise ValueError("coarse_grain: plain bins need n, the number of cells along r, theta, z")
    n = [int(k) for k in n]
    if len(n) != 3:
        raise ValueError("coarse_grain: on a cylindrical grid n takes three values (r, theta, z)")
    return _yuxi.coarse_grain_cylinder(arrays["x"], arrays["v"], arrays["mass"], arrays["volume"],
                                       arrays["contacts"], function, float(width or 0.0), cutoff,
                                       axis, lo, hi, n, average, arrays.get("reduce"))


def _from_dict(d, contacts):
    try:
        x = np.asarray(d["x"], dtype=float)
        v = np.asarray(d["v"], dtype=float)
        mass = np.asarray(d["mass"], dtype=float)
    except KeyError as e:
        raise ValueError(f"coarse_grain: the arrays need the key {e} (x, v, mass, radius)") from None
    if "volume" in d:
        volume = np.asarray(d["volume"], dtype=float)
    elif "radius" in d:
        volume = 4.0 / 3.0 * np.pi * np.asarray(d["radius"], dtype=float) ** 3
    else:
        raise ValueError("coarse_grain: the arrays need 'radius' or 'volume'")
    box = d.get("box")
    if box is None:
        if len(x) == 0:
            raise ValueError("coarse_grain: no grains and no box: give lo and hi")
        box = {"lo": x.min(axis=0), "hi": x.max(axis=0), "periodic": ""}
    table = d.get("contacts") if contacts else None
    if table is not None and "centre" not in table:
        table = _indexed_contacts(table, x, volume)
    return {"x": x, "v": v, "mass": mass, "volume": volume, "box": box, "contacts": table}


def _indexed_contacts(table, x, volume):
    """Contacts given by grain index (a, and b or -1 for a wall) in the coarse-graining's form."""
    try:
        a = np.asarray(table["a"], dtype=np.int64)
        b = np.asarray(table["b"], dtype=np.int64)
        force, branch, point = (np.asarray(table[k], dtype=float)
                                for k in ("force", "branch", "point"))
    except KeyError as e:
        raise ValueError(f"coarse_grain: contacts need the key {e} (a, b, force, branch, point; "
                         "elastic, dissipation, relaxation, wall_power optional)") from None
    n = len(x)
    if a.ndim != 1 or b.shape != a.shape or np.any((a < 0) | (a >= n)) or np.any(b >= n):
        raise ValueError(f"coarse_grain: contacts' a and b must be grain indices below {n} "
                         "(b = -1 for a wall)")
    wall = b < 0
    return {"centre": x[a], "volume": volume[a], "wall": wall.astype(float),
            "volume_b": np.where(wall, 0.0, volume[np.where(wall, 0, b)]), "force": force,
            "branch": branch, "point": point,
            **{key: np.asarray(table.get(key, np.zeros(len(a))), dtype=float)
               for key in ("elastic", "dissipation", "relaxation", "wall_power")}}


def _from_simulation(sim, contacts):
    core = sim._core
    p = sim.particles
    grain = np.asarray(p.kind) == 0
    radius = np.asarray(p.radius)[grain]
    arrays = {"x": np.asarray(p.position)[grain], "v": np.asarray(p.velocity)[grain],
              "mass": np.asarray(p.mass)[grain], "volume": 4.0 / 3.0 * np.pi * radius ** 3,
              "box": core._box(), "contacts": None,
              # every rank adds the sums of its grains and contacts, and makes the fields
              "reduce": core._sum_over_ranks if core.ranks > 1 else None}
    if not contacts:
        return arrays
    try:
        arrays["contacts"] = core._cg_contacts()
    except RuntimeError as e:
        raise ValueError("coarse_grain: the contact fields need the contacts of the last step: "
                         "call sim.record_contacts(True) before it (or pass contacts=False)") \
            from e
    return arrays
