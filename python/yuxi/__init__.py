"""yuxi: 3-D soft-sphere DEM for granular matter, from Python.

Build a scene (from a TOML file, a TOML string or nested dicts), run it, steer it between steps
and read its state as numpy arrays::

    import yuxi
    sim = yuxi.Simulation(yuxi.Scene("scenes/basin-small.toml"), output="runs/basin")
    sim.run(t_end=10.2)
    z = sim.particles.position[:, 2]

The same script under ``mpirun -np N python3 script.py`` runs one decomposed simulation; each
rank sees its own particles, and ``sim.gather(...)`` collects an array on rank 0. The guide is
docs/python.md.
"""

import atexit
import os
import struct
import sys
import weakref

import numpy as np

try:  # one MPI for both: mpi4py starts it (and finishes it) when it is there
    from mpi4py import MPI as _MPI  # noqa: F401
except ImportError:  # pragma: no cover - mpi4py is a dependency, but optional here
    _MPI = None

from . import _yuxi
from ._yuxi import CollectiveError, SceneError, built_in_models, has_cuda
from .coarse_graining import coarse_grain

__all__ = [
    "CollectiveError",
    "Scene",
    "SceneError",
    "Simulation",
    "StaleViewError",
    "built_in_models",
    "coarse_grain",
    "collide",
    "has_cuda",
    "two_grain",
    "validate",
    "validation_cases",
    "square",
    "write_stl",
]


class Scene:
    """A validated scene (docs/scene-format.md).

    ``Scene(source)`` takes a path to a TOML file, a TOML string, or a dict of tables (nested
    dicts and lists with the keys of the scene format; a list of dicts is an array of tables).
    A bad scene raises :class:`SceneError` with the message ``yuxi run`` prints; its ``key``
    attribute names the offending key.
    """

    def __init__(self, source):
        if isinstance(source, Scene):
            self._core = source._core
        elif isinstance(source, dict):
            self._core = _yuxi._Scene.from_dict(source)
        elif isinstance(source, os.PathLike) or (
            isinstance(source, str) and "\n" not in source and "=" not in source
        ):
            self._core = _yuxi._Scene.from_file(os.fspath(source))
        elif isinstance(source, str):
            self._core = _yuxi._Scene.from_toml(source)
        else:
            raise TypeError(f"a scene comes from a path, a TOML string or a dict, not {type(source)}")

    @classmethod
    def from_file(cls, path):
        return cls(os.fspath(path) if isinstance(path, os.PathLike) else path)

    @classmethod
    def from_toml(cls, text, source="<string>"):
        scene = cls.__new__(cls)
        scene._core = _yuxi._Scene.from_toml(text, source)
        return scene

    @classmethod
    def from_dict(cls, tables, source="<dict>"):
        scene = cls.__new__(cls)
        scene._core = _yuxi._Scene.from_dict(tables, source)
        return scene

    def resolved(self):
        """The filled-in scene (every default stated) as nested dicts and lists."""
        return self._core.resolved()

    def toml(self):
        """The filled-in scene as TOML text: what checkpoints keep."""
        return self._core.toml()

    def changed(self, changes):
        """A new scene: this one with the tables of ``changes`` merged in (for sweeps)."""
        return Scene.from_dict(_merged(self.resolved(), changes), source=self.source)

    name = property(lambda self: self._core.name)
    source = property(lambda self: self._core.source)
    t_end = property(lambda self: self._core.t_end)
    dt = property(lambda self: self._core.dt)
    materials = property(lambda self: list(self._core.materials))
    warnings = property(lambda self: list(self._core.warnings))

    def __repr__(self):
        return f"yuxi.Scene({self.name!r} from {self.source}, t_end = {self.t_end}, dt = {self.dt})"


def _merged(base, changes):
    out = dict(base)
    for key, value in changes.items():
        if isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = _merged(out[key], value)
        else:
            out[key] = value
    return out


class StaleViewError(RuntimeError):
    """A view of particle data read after the simulation stepped or was edited."""


class ArrayView:
    """A read-only view of one field of this rank's owned particles, without a copy.

    It is valid until the next step or edit: the engine re-sorts and reallocates its arrays at
    neighbour-list builds. Reading it later raises :class:`StaleViewError`. ``np.asarray(view)``
    gives the plain numpy array over the engine's memory, valid under the same rule but no
    longer checked; ``view.copy()`` gives a copy to keep.
    """

    __slots__ = ("_owner", "_generation", "_array", "_name")

    def __init__(self, owner, name):
        self._owner = owner
        self._generation = owner._core.generation
        self._array = owner._core._array(name)
        self._name = name

    def _checked(self):
        if self._owner._core.finished or self._owner._core.generation != self._generation:
            step, _ = self._generation
            raise StaleViewError(
                f"the view of '{self._name}' was taken at step {step}; the simulation has "
                "stepped or changed since, and its arrays have moved. Take a new view "
                "(sim.particles.<field>) or keep a copy (view.copy())."
            )
        return self._array

    def __array__(self, dtype=None, copy=None):
        a = self._checked()
        return a if dtype is None else a.astype(dtype)

    def __array_ufunc__(self, ufunc, method, *inputs, **kwargs):
        inputs = tuple(i._checked() if isinstance(i, ArrayView) else i for i in inputs)
        return getattr(ufunc, method)(*inputs, **kwargs)

    def __getitem__(self, index):
        return np.array(self._checked()[index])

    def __setitem__(self, index, value):
        raise TypeError(
            f"particle data is read-only here: change '{self._name}' with "
            "sim.set_velocities / set_positions / set_angular_velocities"
        )

    def __len__(self):
        return len(self._checked())

    def __iter__(self):
        return iter(self._checked().copy())

    def __getattr__(self, name):  # shape, dtype, mean(), sum(), min(), copy(), ...
        return getattr(self._checked(), name)

    def __repr__(self):
        try:
            return f"ArrayView({self._name}, {self._checked()!r})"
        except StaleViewError:
            return f"ArrayView({self._name}, stale)"

    def _binary(op):
        def f(self, other):
            other = other._checked() if isinstance(other, ArrayView) else other
            return op(self._checked(), other)

        return f

    __add__ = _binary(np.add)
    __radd__ = _binary(lambda a, b: np.add(b, a))
    __sub__ = _binary(np.subtract)
    __rsub__ = _binary(lambda a, b: np.subtract(b, a))
    __mul__ = _binary(np.multiply)
    __rmul__ = _binary(lambda a, b: np.multiply(b, a))
    __truediv__ = _binary(np.true_divide)
    __rtruediv__ = _binary(lambda a, b: np.true_divide(b, a))
    __pow__ = _binary(np.power)
    __lt__ = _binary(np.less)
    __le__ = _binary(np.less_equal)
    __gt__ = _binary(np.greater)
    __ge__ = _binary(np.greater_equal)
    __eq__ = _binary(np.equal)
    __ne__ = _binary(np.not_equal)
    __neg__ = lambda self: np.negative(self._checked())  # noqa: E731
    del _binary


class Particles:
    """This rank's owned particles (grains, then wall particles, in the engine's order)."""

    FIELDS = ("id", "kind", "material", "radius", "mass", "position", "velocity",
              "angular_velocity", "force", "torque", "clump")
    GRAIN, WALL = 0, 1  # values of `kind`

    def __init__(self, sim):
        self._sim = sim

    def __getattr__(self, name):
        if name in Particles.FIELDS:
            return ArrayView(self._sim, name)
        raise AttributeError(f"no particle field '{name}' (fields: {', '.join(Particles.FIELDS)})")

    @property
    def grains(self):
        """A boolean mask of the grains (a copy)."""
        return np.asarray(self.kind) == Particles.GRAIN

    def __len__(self):
        return len(self._sim._core._array("id"))

    def __dir__(self):
        return list(Particles.FIELDS) + ["grains"]


_live = weakref.WeakSet()


def _device(device):
    if device is None or isinstance(device, str):
        return device
    raise TypeError(f"device: expected \"cpu\", \"gpu\" or \"host\", got {type(device).__name__}")


def _stderr_shows_progress():
    return sys.stderr.isatty() or "ipykernel" in sys.modules


class Simulation:
    """A simulation of a scene, writing the files of ``yuxi run`` into its output folder.

    ``output`` defaults to ``runs/<scene name>``; a folder that holds files is refused unless
    ``overwrite``. ``progress`` (steps, simulated time, rate, ETA) shows on a terminal and in a
    notebook by default. ``device`` ("cpu", "gpu" or "host") overrides the scene's
    ``[run] device``: the engine that steps the run (docs/gpu.md).
    """

    def __init__(self, scene, output=None, overwrite=False, progress=None, force_dt=False,
                 device=None, _core=None):
        if _core is None:
            scene = scene if isinstance(scene, Scene) else Scene(scene)
            _core = _yuxi._Simulation(scene._core, _path(output), overwrite,
                                      _progress(progress), force_dt, _device(device))
        self._core = _core
        self._stop = False
        _live.add(self)

    @classmethod
    def resume(cls, folder, t_end=None, progress=None, device=None):
        """Continues the run in ``folder`` from its newest valid checkpoint, bit for bit.

        ``device`` moves it to another engine ("cpu", "gpu", "host"): a correct continuation,
        not a bitwise one."""
        return cls(None, _core=_yuxi._Simulation.resume(os.fspath(folder), t_end,
                                                         _progress(progress), _device(device)))

    @classmethod
    def branch(cls, checkpoint, scene, output=None, overwrite=False, progress=None,
               force_dt=False, device=None):
        """A checkpoint's state (a file, or a run folder's newest) under another scene.

        What ``yuxi run SCENE --from CHECKPOINT`` does: particles, walls' state, contact history
        (dropped where the contact model changes), time and energy books come from the
        checkpoint, everything else from ``scene``.
        """
        scene = scene if isinstance(scene, Scene) else Scene(scene)
        return cls(None, _core=_yuxi._Simulation.branch(
            os.fspath(checkpoint), scene._core, _path(output), overwrite, _progress(progress),
            force_dt, _device(device)))

    # -- running ---------------------------------------------------------------------------
    def run(self, t_end=None, steps=None, callback=None, every=100):
        """Runs to ``t_end``, or ``steps`` more steps, or the scene's end.

        ``callback(sim)``, if given, is called every ``every`` steps; it may read arrays, set
        velocities or a controlled wall's speed, add or remove grains, and stop the run by
        returning False (or calling ``sim.stop()``). Ctrl-C writes a checkpoint, then raises
        KeyboardInterrupt; ``Simulation.resume(sim.folder)`` continues from it.
        """
        core = self._core
        if t_end is not None and steps is not None:
            raise ValueError("give t_end or steps, not both")
        if steps is not None:
            until = core.step_count + _step_count(steps, "steps")
        elif t_end is not None:
            t_end = _number(t_end, "t_end")
            until = int(round(t_end / core.dt))
            if until < core.step_count:
                raise ValueError(f"t_end = {t_end:g} is before the simulation's time t = "
                                 f"{core.time:g}: it runs forwards only")
        else:
            until = core.end_step
        self._stop = False
        hook = None
        if callback is not None:
            def hook(_core):
                answer = callback(self)
                return not (answer is False or self._stop)
        core.advance(until, hook, int(every))
        return self

    def step(self, n=1):
        """Advances ``n`` steps."""
        self._core.advance(self._core.step_count + _step_count(n, "n"), None, 100)
        return self

    def stop(self):
        """From a callback: stop the run after it returns."""
        self._stop = True

    def checkpoint(self, path=None):
        """Writes a checkpoint, into the run folder's checkpoints/ or to ``path``; returns the
        path of the file written. Collective."""
        return self._core.checkpoint("" if path is None else os.fspath(path))

    def close(self):
        """Finishes the run's analyses and frees the engine; returns the run's summary."""
        summary = self._core.finish()
        self._core.close()
        return summary

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    # -- state -----------------------------------------------------------------------------
    time = property(lambda self: self._core.time)
    step_count = property(lambda self: self._core.step_count)
    dt = property(lambda self: self._core.dt)
    folder = property(lambda self: self._core.folder)
    rank = property(lambda self: self._core.rank)
    ranks = property(lambda self: self._core.ranks)
    materials = property(lambda self: list(self._core.materials))

    @property
    def particles(self):
        """Views of this rank's owned particles, valid until the next step (ArrayView)."""
        return Particles(self)

    @property
    def collective_timeout(self):
        """Seconds a rank waits at a collective call for the other ranks to make it.

        Every collective call (``run``, ``gather``, ``energies``, ``wall_loads``, ``outflow``,
        ``checkpoint``, ``finish``, ``close``, ``set_positions``, ``add_grains``,
        ``remove_grains``, ``add_insert``) first checks that every rank makes the same call:
        ranks that meet in different calls raise :class:`CollectiveError` on every rank, naming
        each rank's call; a rank whose others do not come (a call under ``if rank == 0:``)
        raises it after this many seconds, and the job must then end. The default is 600 s, or
        ``$YUXI_COLLECTIVE_TIMEOUT``.
        """
        return self._core.collective_timeout

    @collective_timeout.setter
    def collective_timeout(self, seconds):
        self._core.collective_timeout = _number(seconds, "collective_timeout")

    def gather(self, field):
        """The field of every rank's particles, sorted by id, on rank 0 (None elsewhere).

        Collective: every rank must call it.
        """
        return self._core.gather(field)

    def energies(self):
        """The energy books now, summed over the ranks (a dict). Collective."""
        return self._core.energies()

    def energy_history(self):
        """energies.csv as a numpy record array (rank 0; None elsewhere)."""
        if self.rank != 0:
            return None
        return np.genfromtxt(os.path.join(self.folder, "energies.csv"), delimiter=",",
                             names=True).view(np.recarray)

    def wall_loads(self):
        """Each named wall's load at the last step, by name: ``force`` and ``torque`` (numpy
        arrays of shape (3,), on the wall), ``work`` (cumulative, done by the wall on the grains)
        and ``contacts`` (docs/python.md). Collective."""
        return self._core.wall_loads()

    def inflow(self):
        """Each insert's cumulative grains, mass and grains owed (due but not placed yet)."""
        return self._core.inflow()

    # -- pouring in stages -------------------------------------------------------------------
    def start_insert(self, name):
        """Starts (or resumes) the insert ``name``: it pours from the next step on, at its rate,
        until its total (what it poured before counts) or the scene's end. An insert with
        ``held = true`` in the scene waits for this. Checkpoints, resumes and branches keep the
        pouring as it stands."""
        self._core.start_insert(name)

    def pause_insert(self, name):
        """No batch of the insert ``name`` until it is started again."""
        self._core.pause_insert(name)

    def stop_insert(self, name):
        """The insert ``name`` pours no more, for good."""
        self._core.stop_insert(name)

    def add_insert(self, table):
        """Adds an insert from a dict with the keys of a scene's ``[[insert]]`` table (a
        ``name`` among them, new to the run); it pours from the next step on (or from its
        ``start``, if later). It joins the run's scene: its checkpoints and scene.resolved.toml
        hold it. Returns its name."""
        if not isinstance(table, dict):
            raise TypeError(f"add_insert: a dict with the keys of an [[insert]] table, not "
                            f"{type(table).__name__}")
        return self._core.add_insert(_yuxi._toml_of({"insert": [table]}))

    def outflow(self):
        """Each outlet's cumulative grains and mass. Collective."""
        return self._core.outflow()

    # -- changes between steps (booked as inserted energy) ---------------------------------
    def set_velocities(self, ids, velocities):
        """Sets the velocities of grains this rank owns (by id)."""
        self._core.set_velocities(np.asarray(ids), np.asarray(velocities))

    def set_angular_velocities(self, ids, angular_velocities):
        self._core.set_angular_velocities(np.asarray(ids), np.asarray(angular_velocities))

    def set_positions(self, ids, positions):
        """Moves grains this rank owns; the neighbour list is rebuilt. Collective."""
        self._core.set_positions(np.asarray(ids), np.asarray(positions))

    def add_grains(self, positions, radii, velocities=None, material=None):
        """Adds grains (the same on every rank); returns their ids. ``radii``: one radius for
        all, or one per grain. A grain that would overlap another particle or a wall (flat, mesh
        or cylinder) is refused (ValueError naming it). Collective."""
        positions = _positions(positions, "add_grains")
        n = len(positions)
        radii = _one_or_each(radii, n, "add_grains", "radii", "radius", "grain")
        velocities = (np.zeros_like(positions) if velocities is None
                      else np.atleast_2d(np.asarray(velocities, dtype=float)))
        if velocities.shape != positions.shape:
            raise ValueError(f"add_grains: {n} positions but velocities of shape "
                             f"{velocities.shape}: give one (3,) velocity per grain")
        material = self.materials[0] if material is None else material
        return self._core.add_grains(positions, radii, velocities, material)

    def remove_grains(self, ids):
        """Removes the grains of these ids (where any rank owns them); returns how many went.

        Collective. Their energy is booked as removed.
        """
        return self._core.remove_grains(np.atleast_1d(np.asarray(ids)))

    def set_clump_velocities(self, ids, velocities):
        """Sets the velocities of the centres of mass of clumps this rank owns, by clump id
        (``sim.clumps()["id"]``); their members move with them."""
        self._core.set_clump_velocities(np.asarray(ids), np.asarray(velocities))

    def set_clump_angular_velocities(self, ids, angular_velocities):
        """Sets the angular velocities (lab frame) of clumps this rank owns, by clump id."""
        self._core.set_clump_angular_velocities(np.asarray(ids), np.asarray(angular_velocities))

    def set_clump_poses(self, ids, positions, orientations=None):
        """Moves clumps this rank owns (by clump id) to these centres of mass and, where given,
        orientations (unit quaternions w, x, y, z of the principal frame, as ``clumps()`` gives
        them); each keeps its velocity and angular velocity. The neighbour list is rebuilt.
        Collective."""
        self._core.set_clump_poses(np.asarray(ids), np.asarray(positions),
                                   None if orientations is None else np.asarray(orientations))

    def add_clumps(self, shape, positions, orientations=None, velocities=None,
                   angular_velocities=None, scale=1.0, material=None, frame="shape"):
        """Adds clumps of the scene's ``[[shape]]`` named ``shape`` (the same on every rank);
        returns their ids. ``positions``: the centres of mass, (n, 3); ``orientations``: unit
        quaternions (w, x, y, z), (n, 4), that turn the shape as its table writes it (or, with
        ``frame="principal"``, its principal frame, as ``clumps()`` gives them) onto the lab's;
        (1, 0, 0, 0) where not given; ``scale``: one factor for all or one per clump (1: the
        shape's size). A member that would overlap another particle or a wall is refused
        (ValueError naming it), as are clumps the time step cannot resolve (SceneError). A shape
        of one member gives spheres. Collective."""
        if frame not in ("shape", "principal"):
            raise ValueError(f"add_clumps: frame must be 'shape' or 'principal', not {frame!r}")
        positions = _positions(positions, "add_clumps")
        n = len(positions)

        def rows(values, width, what, default):
            if values is None:
                return np.tile(np.asarray(default, dtype=float), (n, 1))
            values = np.atleast_2d(np.asarray(values, dtype=float))
            if values.shape != (n, width):
                raise ValueError(f"add_clumps: {n} positions but {what} of shape "
                                 f"{values.shape}: give one ({width},) row per clump")
            return values

        orientations = rows(orientations, 4, "orientations", [1.0, 0.0, 0.0, 0.0])
        velocities = rows(velocities, 3, "velocities", [0.0, 0.0, 0.0])
        angular_velocities = rows(angular_velocities, 3, "angular_velocities", [0.0, 0.0, 0.0])
        scale = _one_or_each(scale, n, "add_clumps", "scale", "factor", "clump")
        material = self.materials[0] if material is None else material
        return self._core.add_clumps(shape, positions, orientations, velocities,
                                     angular_velocities, scale, material, frame == "principal")

    def remove_clumps(self, ids):
        """Removes the clumps of these ids, whole (where any rank owns them); returns how many
        went. Collective. Their energy is booked as removed."""
        return self._core.remove_clumps(np.atleast_1d(np.asarray(ids)))

    def set_wall_speed(self, name, speed):
        """Sets a controlled mesh's speed along its servo_axis, held until set again."""
        self._core.set_wall_speed(name, float(speed))

    def set_wall_controller(self, name, controller):
        """Controls a mesh every step: ``controller(resisting_force, t) -> speed``."""
        self._core.set_wall_controller(name, controller)

    def wall_motion(self, name):
        """A controlled mesh's speed and how far it has moved along its axis."""
        return self._core.wall_motion(name)

    def record_contacts(self, on=True):
        """Records every contact's force from the next step on (costs time and memory)."""
        self._core.record_contacts(on)

    def contacts(self):
        """This rank's touching contacts at the last step, as arrays: partner ids (id_b = -1 and
        ``wall`` named for a wall; ``element``: a mesh's triangle or a cylinder's patch), force on
        the first partner, normal, point, overlap, stored elastic energy, and ``state``: the
        contact model's state, one array per field (docs/python.md)."""
        return self._core.contacts()

    def clumps(self):
        """This rank's clumps (docs/clumps.md) as arrays: id (member k of a clump has id + k; a
        member's ``particles.clump`` is its clump's id, -1 for a free grain), shape (an index into
        ``shapes``, -1 for none), position (the centre of mass), velocity, orientation (the unit
        quaternion w, x, y, z from the principal frame to the lab's), angular_velocity, mass,
        inertia (the principal moments, ascending), members, force, torque."""
        return self._core.clumps()

    @property
    def shapes(self):
        """The names of the scene's [[shape]] tables, in order (a clump's ``shape`` indexes it)."""
        return list(self._core.shapes)

    def shape(self, name):
        """The scene's [[shape]] ``name`` in its principal frame: the members' ``centres`` (k, 3)
        and ``radii``, ``volume``, ``inertia_per_density`` (the principal moments over the
        density, ascending), ``bounding_radius``, and where the table gave it: ``frame``, the
        quaternion that turns the principal frame onto the table's (``add_clumps`` with
        ``orientations=[frame], frame="principal"`` places the shape as written, as the default
        frame does with no orientation), and ``centre``, the centre of mass in the table's
        frame."""
        return self._core.shape(name)

    def __repr__(self):
        return (f"yuxi.Simulation(step {self.step_count}, t = {self.time:.6g}, "
                f"folder {self.folder!r}, rank {self.rank} of {self.ranks})")


def _positions(positions, call):
    """Positions as an (n, 3) array of floats (one position may be given alone)."""
    positions = np.atleast_2d(np.asarray(positions, dtype=float))
    if positions.ndim != 2 or positions.shape[1] != 3:
        raise ValueError(f"{call}: positions must be of shape (n, 3), not {np.shape(positions)}")
    return positions


def _one_or_each(values, n, call, what, one, item):
    """One number for all n items, or one per item, as an (n,) array of floats."""
    values = np.asarray(values, dtype=float)
    if values.ndim == 0:
        return np.full(n, float(values))
    if values.shape != (n,):
        raise ValueError(f"{call}: {n} positions but {what} of shape {values.shape}: give one "
                         f"{one}, or one per {item}")
    return values


def _path(output):
    return "" if output is None else os.fspath(output)


def _step_count(n, name):
    """A number of steps: a whole number, not negative."""
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)):
        if isinstance(n, (float, np.floating)) and float(n).is_integer():
            n = int(n)
        else:
            raise TypeError(f"{name} must be a whole number of steps, not {n!r}")
    if n < 0:
        raise ValueError(f"{name} = {n}: the simulation runs forwards only")
    return int(n)


def _number(x, name):
    if isinstance(x, bool) or not isinstance(x, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name} must be a number, not {x!r}")
    if not np.isfinite(x):
        raise ValueError(f"{name} = {x} is not finite")
    return float(x)


def _progress(progress):
    return _stderr_shows_progress() if progress is None else bool(progress)


def write_stl(path, triangles, header="yuxi"):
    """Writes triangles (an (n, 3, 3) array-like of vertices) as a binary STL file, for a
    scene's [[mesh]]: an 80-byte header, the count, then per triangle its normal (from the
    vertices' order), three float32 vertices and a zero attribute, little-endian."""
    tris = np.asarray(triangles, dtype=float).reshape(-1, 3, 3)
    with open(path, "wb") as f:
        f.write(header.encode()[:80].ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            n = np.cross(t[1] - t[0], t[2] - t[0])
            n = n / (np.linalg.norm(n) or 1.0)
            f.write(struct.pack("<3f", *n))
            for v in t:
                f.write(struct.pack("<3f", *v))
            f.write(struct.pack("<H", 0))


def square(half, z=0.0):
    """The two triangles of a square of side 2 half in the plane at height z, centred on the
    axis (a lid or a piston for write_stl)."""
    return [((-half, -half, z), (half, -half, z), (half, half, z)),
            ((-half, -half, z), (half, half, z), (-half, half, z))]


# -- studies -------------------------------------------------------------------------------
def collide(models=None, scene=None, v0_min=1e-5, v0_max=1e-1, per_decade=4, mass=1.0,
            radius=0.5, steps_per_contact=200):
    """Restitution against impact speed (``yuxi collide``'s restitution.csv) as arrays.

    Every built-in model by default, or the first material pair of ``scene`` (a path). For
    the thermodynamic model the exact two-grain solver's rows come beside the engine's
    (``source`` = "exact").
    """
    if isinstance(models, str):
        models = [models]
    return _yuxi._collide(list(models or []), "" if scene is None else os.fspath(scene),
                          v0_min, v0_max, per_decade, mass, radius, steps_per_contact)


def two_grain(v0=1e-3, model="thermodynamic", mass=1.0, radius=0.5):
    """The exact two-grain solver's head-on collision, with its time series (Fig. 3)."""
    return _yuxi._two_grain(model, v0, mass, radius)


def _source_dir():
    here = os.path.dirname(os.path.abspath(__file__))
    for up in (os.path.join(here, "..", "..", ".."), os.path.join(here, "..", "..")):
        if os.path.isdir(os.path.join(up, "scenes")) and os.path.isdir(
                os.path.join(up, "tests", "validation", "data")):
            return os.path.abspath(up)
    return os.getcwd()


def validation_cases():
    """The validation cases: id, title, source, long."""
    return _yuxi._validation_cases()


def validate(cases=None, include_long=False, scenes=None, reference=None):
    """Runs validation cases (the quick ones by default) and returns the table as a list of
    dicts: case, quantity, expected, measured, tolerance, passed."""
    if isinstance(cases, str):
        cases = [cases]
    root = _source_dir()
    return _yuxi._validate(list(cases or []), include_long,
                           os.fspath(scenes) if scenes else os.path.join(root, "scenes"),
                           os.fspath(reference) if reference else
                           os.path.join(root, "tests", "validation", "data"))


@atexit.register
def _finish():
    # Every simulation is closed before MPI ends (their halos may still hold messages).
    for sim in list(_live):
        try:
            sim._core.close()
        except Exception:  # pragma: no cover - exiting anyway
            pass
    if _yuxi._mpi_started_here:
        _yuxi._finish_mpi()
