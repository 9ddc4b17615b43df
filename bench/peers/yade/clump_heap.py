# A heap of rod-shaped clumps in YADE: the scene scenes/clumps/heap-rod<k>[-seed<s>].toml of
# yuxi (written by scenes/bulk/make_heap.py), for a side-by-side comparison of the angle of repose.
#
# What it reproduces (every number is read from the scene file):
#   - units d = 1, g = 1 along -z; grains are rods of k spheres of radius 0.5, centres 0.5 apart
#     in a row ([[shape]]), each rod scaled uniformly (its bounding radius drawn uniform in
#     0.9-1.1 of the shape's), density 1.909859317, mass and inertia of the union of its spheres
#     (each overlap counted once); k = 1: plain spheres of radius 0.45-0.55;
#   - a rough floor: fixed spheres of radius 0.5 on a cubic lattice of spacing 1.2 filling the
#     disc of radius 14 at z = 0 row by row (the same sites and count as yuxi's lattice fill:
#     packing_fraction 0.25 of the slab, 359 spheres), each jittered within a ball of 0.1;
#   - the pour ([[insert]]): every `interval` the rods due at `rate` are drawn (size, velocity
#     (0, 0, -0.5) plus 0.3 times a point uniform in the unit ball, a uniformly random
#     orientation, no spin) and each takes the first of `attempts` random places whose bounding
#     ball lies in the source cylinder and overlaps no sphere and no rod placed before it in the
#     batch; a rod that finds no place is owed to the next batch, which tries it first with the
#     size and velocity it was drawn with;
#   - rods whose centre of mass falls below z = -4 ([[outlet]]) or leaves the domain are removed;
#   - fixed dt = 8e-4, NewtonIntegrator without numerical damping, run to t_end;
#   - the angle of repose ([[measure]] quantity = "angle"): the highest grain top z + r over
#     columns 2 d wide on the domain's x-y grid, fitted by least squares against the distance of
#     the column's centre from the vertical axis through the origin, between 2.8 d and 9.8 d.
#
# The contact law: yuxi's linear spring-dashpot (src/contact/linear_spring_dashpot.hpp)
#     F_n = k_n delta - m_eff gamma_n v_n,  F_t = -k_t s_t - m_eff gamma_t v_t,  |F_t| <= mu |F_n|
# with m_eff = m_i m_j / (m_i + m_j) (a clump's member: the clump's mass; against the fixed
# floor: m_eff = m_i), maps onto YADE's ViscElMat / Ip2_ViscElMat_ViscElMat_ViscElPhys /
# Law2_ScGeom_ViscElPhys_Basic with explicit constants. YADE joins the two materials' constants
# in series, A = a1 a2 / (a1 + a2) (a zero constant drops out), so
#     grain material (one per rod): kn = 2 k_n, ks = 2 k_t, cn = gamma_n m, cs = gamma_t m
#                                    (m: that rod's mass)
#     floor material:                kn = 2 k_n, ks = 2 k_t, cn = 0, cs = 0
#     both:                          frictionAngle = atan(mu)
# which gives, for every pair, K_n = k_n, K_s = k_t, C_n = gamma_n m_eff, C_s = gamma_t m_eff.
# What YADE's law does differently (README.md): it clamps the normal force at zero (no pull
# while the dashpot would pull), so a collision restitutes more than exp(-gamma_n t_c / 2); it
# caps the tangential spring alone at mu F_n and drops the tangential dashpot while sliding
# (yuxi's scene caps spring + dashpot together, friction_cap = "total"); and it carries the
# tangential spring by YADE's own rotation of the shear force.
#
# usage: yade -j1 -n -x clump_heap.py K [--seed S] [--t-end T] [--total N] [--out DIR]
#   K       spheres per rod: 1, 2, 3 or 5 (or the environment's ROD)
#   --seed  1, 2 or 3: the scene file (heap-rodK.toml, heap-rodK-seedS.toml) and this script's
#           random stream (or SEED); yuxi's random streams are not reproduced
#   --t-end stop earlier than the scene's t_end (a shortened run) (or T_END)
#   --total pour at most N rods (or TOTAL)
#   --out   the folder for the outputs (default yade-heap-rodK[-seedS] here) (or OUT)
# outputs in DIR: grains.csv (x,y,z,radius,clump: every grain sphere at the end), floor.csv
# (x,y,z,radius), measurements.csv (time, angle, angle_r2, height, grains, inserted, owed,
# removed, ke per grain, every 1 time unit), angle.txt (the final angle and the run's settings);
# the final angle is also printed.
import argparse
import math
import os
import pathlib
import random
import sys
import time
import tomllib

import yade
from yade import O, utils
from yade.wrapper import (ForceResetter, InsertionSortCollider, Bo1_Sphere_Aabb, InteractionLoop,
                          Ig2_Sphere_Sphere_ScGeom, Ip2_ViscElMat_ViscElMat_ViscElPhys,
                          Law2_ScGeom_ViscElPhys_Basic, NewtonIntegrator, PyRunner, ViscElMat,
                          Sphere)

HERE = pathlib.Path(sys.argv[0]).resolve().parent  # (yade -x: __file__ is yade's own)
SCENES = HERE.parents[2] / "scenes" / "clumps"

# ---------------------------------------------------------------------------------------------
# the command line and the scene file

parser = argparse.ArgumentParser(prog="clump_heap.py")
parser.add_argument("rod", type=int, nargs="?", default=int(os.environ.get("ROD", "3")))
parser.add_argument("--seed", type=int, default=int(os.environ.get("SEED", "1")))
parser.add_argument("--t-end", type=float, default=float(os.environ.get("T_END", "nan")))
parser.add_argument("--total", type=int, default=int(os.environ.get("TOTAL", "-1")))
parser.add_argument("--out", default=os.environ.get("OUT", ""))
args = parser.parse_args(sys.argv[1:])

name = f"heap-rod{args.rod}" + (f"-seed{args.seed}" if args.seed != 1 else "")
scene = tomllib.loads((SCENES / f"{name}.toml").read_text())
out_dir = pathlib.Path(args.out or f"yade-{name}")
out_dir.mkdir(parents=True, exist_ok=True)
rng = random.Random(args.seed)  # (a stream of its own: yade's utils draw from `random` too)

DENSITY = scene["material"]["grain"]["density"]
DT = scene["run"]["dt"]
T_END = scene["run"]["t_end"] if math.isnan(args.t_end) else args.t_end
LO, HI = scene["domain"]["lo"], scene["domain"]["hi"]
GRAVITY = tuple(scene["domain"]["gravity"])

pairs = {tuple(p["materials"]): p for p in scene["contact"]["pair"]}
law = pairs[("grain", "grain")]
for key in ("k_n", "k_t", "gamma_n", "gamma_t", "mu_s", "mu_d"):
    if pairs[("grain", "floor")][key] != law[key]:
        sys.exit(f"{name}: grain-floor {key} differs from grain-grain; not mapped")
if law["mu_s"] != law["mu_d"] or law.get("friction_cap") != "total":
    sys.exit(f"{name}: one friction coefficient with friction_cap = 'total' is what is mapped")
K_N, K_T, GAMMA_N, GAMMA_T, MU = (law[k] for k in ("k_n", "k_t", "gamma_n", "gamma_t", "mu_s"))

floor_fill = scene["fill"][0]
pour = scene["insert"][0]
outlet = scene["outlet"][0]["region"]
measure = {m["name"]: m for m in scene["measure"]}
angle_measure, height_measure = measure["angle"], measure["height"]
TOTAL = pour["total"] if args.total < 0 else min(args.total, pour["total"])

# ---------------------------------------------------------------------------------------------
# the rod: members along x in the shape's frame; the union's volume, centroid and inertia

shape = scene["shape"][0]["spheres"] if "shape" in pour else [[0.0, 0.0, 0.0, 1.0]]
if any(abs(s[1]) > 0 or abs(s[2]) > 0 for s in shape):
    sys.exit("the members must lie on the shape's x axis")


def union_of(spheres, n=40001):
    """Volume, centroid x, and the inertia per unit density about the centroid (along the axis,
    across it) of the union of spheres on the x axis, by slicing along x."""
    a = min(s[0] - s[3] for s in spheres)
    b = max(s[0] + s[3] for s in spheres)
    h = (b - a) / (n - 1)
    xs = [a + i * h for i in range(n)]
    rho2 = [max(max(s[3] ** 2 - (x - s[0]) ** 2, 0.0) for s in spheres) for x in xs]
    w = [h * (0.5 if i in (0, n - 1) else 1.0) for i in range(n)]
    volume = sum(wi * math.pi * r2 for wi, r2 in zip(w, rho2))
    centre = sum(wi * math.pi * r2 * x for wi, r2, x in zip(w, rho2, xs)) / volume
    along = sum(wi * math.pi * r2 * r2 / 2 for wi, r2 in zip(w, rho2))
    across = sum(wi * math.pi * r2 * (r2 / 4 + (x - centre) ** 2) for wi, r2, x in zip(w, rho2, xs))
    return volume, centre, along, across


SHAPE_VOLUME, SHAPE_CENTRE, SHAPE_I_ALONG, SHAPE_I_ACROSS = union_of(shape)
SHAPE_BOUNDING = max(abs(s[0] - SHAPE_CENTRE) + s[3] for s in shape)
size = pour["size"]
R_MIN, R_MAX = size["min"], size["max"]  # the bounding radius drawn for each rod

# ---------------------------------------------------------------------------------------------
# materials: the law in series form (see the header)

FRICTION_ANGLE = math.atan(MU)
floor_material = O.materials.append(ViscElMat(kn=2 * K_N, ks=2 * K_T, cn=0.0, cs=0.0,
                                              frictionAngle=FRICTION_ANGLE, density=1.0,
                                              label="floor"))


def grain_material(mass):
    """One material a rod: its dashpots are proportional to its own mass."""
    return O.materials.append(ViscElMat(kn=2 * K_N, ks=2 * K_T, cn=GAMMA_N * mass,
                                        cs=GAMMA_T * mass, frictionAngle=FRICTION_ANGLE,
                                        density=DENSITY))


# ---------------------------------------------------------------------------------------------
# regions (cylinders about z, as the scene uses them)


def in_cylinder(region, x, y, z, r=0.0):
    c = region["center"]
    return (math.hypot(x - c[0], y - c[1]) <= region["radius"] - r
            and c[2] + region["lo"] + r <= z <= c[2] + region["hi"] - r)


def sample_cylinder(region):
    c = region["center"]
    while True:
        x, y = (rng.uniform(-1, 1) for _ in range(2))
        if x * x + y * y <= 1:
            break
    return (c[0] + region["radius"] * x, c[1] + region["radius"] * y,
            c[2] + rng.uniform(region["lo"], region["hi"]))


def unit_ball():
    while True:
        u = [rng.uniform(-1, 1) for _ in range(3)]
        if sum(v * v for v in u) <= 1:
            return u


# ---------------------------------------------------------------------------------------------
# the floor: yuxi's lattice fill (src/scene/particle_fill.cpp): sites 2 (r + jitter) apart over
# the region's bounding box, bottom layer first, row by row in y then x, each whose ball of
# r + jitter lies in the cylinder; as many spheres as make the packing fraction asked for.

floor_r, jitter = floor_fill["radius"], floor_fill["jitter"]
region = floor_fill["region"]
c = region["center"]
box_lo = [c[0] - region["radius"], c[1] - region["radius"], c[2] + region["lo"]]
box_hi = [c[0] + region["radius"], c[1] + region["radius"], c[2] + region["hi"]]
ball = 4 / 3 * math.pi * floor_r**3
target = floor_fill["packing_fraction"] * math.pi * region["radius"] ** 2 * (region["hi"] - region["lo"])
n_floor = 0
while (n_floor + 1) * ball - target <= target - n_floor * ball:  # the count nearest the target
    n_floor += 1
a = 2.0 * (floor_r + jitter) * (1.0 + 1e-9)
n = [int(math.floor((box_hi[k] - box_lo[k]) / a)) for k in range(3)]
floor = []
for iz in range(n[2]):
    for iy in range(n[1]):
        for ix in range(n[0]):
            if len(floor) == n_floor:
                break
            site = [box_lo[0] + (ix + 0.5) * a, box_lo[1] + (iy + 0.5) * a, box_lo[2] + (iz + 0.5) * a]
            if not in_cylinder(region, *site, floor_r + jitter):
                continue
            u = unit_ball()
            floor.append(tuple(site[k] + jitter * u[k] for k in range(3)))
if len(floor) < n_floor:
    sys.exit(f"the floor lattice holds {len(floor)} of {n_floor} spheres")
floor_ids = O.bodies.append([utils.sphere(x, floor_r, material=floor_material, fixed=True)
                             for x in floor])
with open(out_dir / "floor.csv", "w") as f:
    f.write("x,y,z,radius\n")
    for x in floor:
        f.write(f"{x[0]:.8g},{x[1]:.8g},{x[2]:.8g},{floor_r}\n")

# ---------------------------------------------------------------------------------------------
# the pour

rods = {}  # grain id (a clump's id, or a plain sphere's) -> its member ids
stats = dict(inserted=0, owed=0, removed=0, batches=0)
EVERY = max(1, round(pour.get("interval", 500 * DT) / DT))
ATTEMPTS = pour.get("attempts", 20)
v0, spread = pour["velocity"], pour.get("velocity_spread", 0.0)
source = pour["region"]


def random_rotation():
    """A rotation matrix uniform over all rotations (Shoemake's quaternion)."""
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    w = math.sqrt(1 - u1) * math.sin(2 * math.pi * u2)
    x = math.sqrt(1 - u1) * math.cos(2 * math.pi * u2)
    y = math.sqrt(u1) * math.sin(2 * math.pi * u3)
    z = math.sqrt(u1) * math.cos(2 * math.pi * u3)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def add_rod(centre, bounding, velocity):
    s = bounding / SHAPE_BOUNDING
    mass = DENSITY * SHAPE_VOLUME * s**3
    mat = grain_material(mass)
    if len(shape) == 1:
        b = utils.sphere(centre, shape[0][3] * s, material=mat)
        gid = O.bodies.append(b)
        O.bodies[gid].state.vel = velocity
        rods[gid] = [gid]
        return
    rot = random_rotation()
    members = []
    for m in shape:
        d = [(m[0] - SHAPE_CENTRE) * s, m[1] * s, m[2] * s]
        x = [centre[k] + sum(rot[k][j] * d[j] for j in range(3)) for k in range(3)]
        members.append(utils.sphere(x, m[3] * s, material=mat))
    cid, ids = O.bodies.appendClumped(members)  # (mass and inertia summed over the members:
    st = O.bodies[cid].state                    #  replaced by the union's below)
    along = min(range(3), key=lambda k: st.inertia[k])  # the rod's axis in the clump's frame
    inertia = [DENSITY * SHAPE_I_ACROSS * s**5] * 3
    inertia[along] = DENSITY * SHAPE_I_ALONG * s**5
    st.mass = mass
    st.inertia = inertia
    st.vel = velocity
    rods[cid] = list(ids)


def grain_spheres():
    """(x, y, z, r) of every grain sphere."""
    out = []
    for gid, ids in rods.items():
        for i in ids:
            b = O.bodies[i]
            p = b.state.pos
            out.append((p[0], p[1], p[2], b.shape.radius))
    return out


owed = []  # (bounding radius, velocity) of the rods the last batch found no place for


def pour_batch():
    """One batch of the pour, as yuxi's [[insert]] (src/sim/sources.cpp): the rods owed by the
    last batch first, with the sizes and velocities they were drawn with, then new ones."""
    if stats["inserted"] >= TOTAL or O.time > pour.get("end", math.inf):
        return
    elapsed = (stats["batches"] + 1) * EVERY * DT
    stats["batches"] += 1
    due = min(int(math.floor(pour["rate"] * elapsed + 1e-9)), TOTAL) - stats["inserted"]
    drawn = owed[:max(due, 0)]
    while len(drawn) < due:
        drawn.append((rng.uniform(R_MIN, R_MAX),
                      [v0[k] + spread * u for k, u in enumerate(unit_ball())]))
    owed.clear()
    if not drawn:
        return
    near = [s for s in grain_spheres()
            if in_cylinder(source, s[0], s[1], s[2], -(s[3] + R_MAX))]
    taken = []
    for r, v in drawn:
        for _ in range(ATTEMPTS):
            x = sample_cylinder(source)
            if not in_cylinder(source, *x, r):
                continue
            if any((x[0] - p[0]) ** 2 + (x[1] - p[1]) ** 2 + (x[2] - p[2]) ** 2 < (r + p[3]) ** 2
                   for p in near + taken):
                continue
            taken.append((x[0], x[1], x[2], r))
            add_rod(x, r, v)
            stats["inserted"] += 1
            break
        else:
            owed.append((r, v))
    stats["owed"] = len(owed)


def drain():
    """Removes the grains whose centre of mass is below the outlet's plane or out of the domain."""
    z_out = outlet["point"][2]
    gone = []
    for gid in rods:
        p = O.bodies[gid].state.pos
        if p[2] < z_out or any(p[k] < LO[k] or p[k] > HI[k] for k in range(3)):
            gone.append(gid)
    for gid in gone:
        if len(rods[gid]) > 1:
            O.bodies.erase(gid, True)  # the clump and its members
        else:
            O.bodies.erase(gid)
        del rods[gid]
    stats["removed"] += len(gone)


# ---------------------------------------------------------------------------------------------
# measurements (src/run/bed_measurements.cpp)


def column_tops(spheres, lo, hi, bin_):
    nx = max(1, int(math.floor((hi[0] - lo[0]) / bin_)))
    ny = max(1, int(math.floor((hi[1] - lo[1]) / bin_)))
    dx, dy = (hi[0] - lo[0]) / nx, (hi[1] - lo[1]) / ny
    tops = {}
    for x, y, z, r in spheres:
        i, j = int(math.floor((x - lo[0]) / dx)), int(math.floor((y - lo[1]) / dy))
        if 0 <= i < nx and 0 <= j < ny:
            tops[i, j] = max(tops.get((i, j), -math.inf), z + r)
    return {(lo[0] + (i + 0.5) * dx, lo[1] + (j + 0.5) * dy): h for (i, j), h in tops.items()}


def heap_angle(spheres):
    """atan |slope| [degrees] and R^2 of the column tops against the distance from the axis."""
    m = angle_measure
    p = m["axis_point"]
    s, h = [], []
    for (x, y), top in column_tops(spheres, LO, HI, m["bin"]).items():
        d = math.hypot(x - p[0], y - p[1])
        if m["from"] <= d <= m["to"]:
            s.append(d)
            h.append(top)
    ms, mh = sum(s) / max(len(s), 1), sum(h) / max(len(h), 1)
    sxx = sum((a - ms) ** 2 for a in s)
    if sxx == 0:
        return math.nan, math.nan
    sxy = sum((a - ms) * (b - mh) for a, b in zip(s, h))
    syy = sum((b - mh) ** 2 for b in h)
    slope = sxy / sxx
    r2 = sxy * sxy / (sxx * syy) if syy > 0 else 1.0
    return math.degrees(math.atan(abs(slope))), r2


def heap_height(spheres):
    """The median column top over the grains in the height measure's cylinder."""
    reg = height_measure["region"]
    c = reg["center"]
    lo = [c[0] - reg["radius"], c[1] - reg["radius"]]
    hi = [c[0] + reg["radius"], c[1] + reg["radius"]]
    inside = [q for q in spheres if in_cylinder(reg, q[0], q[1], q[2])]
    tops = sorted(column_tops(inside, lo, hi, height_measure.get("bin", 2.0)).values())
    if not tops:
        return math.nan
    k = len(tops)
    return tops[k // 2] if k % 2 else 0.5 * (tops[k // 2 - 1] + tops[k // 2])


def kinetic_per_grain():
    total = 0.0
    for gid in rods:
        st = O.bodies[gid].state
        w = st.ori.conjugate() * st.angVel
        total += 0.5 * st.mass * st.vel.squaredNorm() + 0.5 * sum(
            st.inertia[k] * w[k] ** 2 for k in range(3))
    return total / len(rods) if rods else 0.0


MEASURE_EVERY = max(1, round(scene["output"].get("energy_interval", 1.0) / DT))
log = open(out_dir / "measurements.csv", "w")
log.write("time,angle,angle_r2,height,grains,inserted,owed,removed,ke\n")
wall_start = time.time()


def record():
    spheres = grain_spheres()
    angle, r2 = heap_angle(spheres)
    row = (f"{O.time:.4f},{angle:.6g},{r2:.6g},{heap_height(spheres):.6g},{len(rods)},"
           f"{stats['inserted']},{stats['owed']},{stats['removed']},{kinetic_per_grain():.6g}")
    log.write(row + "\n")
    log.flush()
    print(f"[{time.time() - wall_start:7.1f} s] t = {O.time:7.3f}  angle {angle:6.2f}  "
          f"grains {len(rods)}  inserted {stats['inserted']}  owed {stats['owed']}  "
          f"removed {stats['removed']}", flush=True)


# ---------------------------------------------------------------------------------------------
# the engines and the run

O.dt = DT
O.engines = [
    PyRunner(iterPeriod=EVERY, initRun=True, command="drain(); pour_batch()"),
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_ViscElMat_ViscElMat_ViscElPhys()],
                    [Law2_ScGeom_ViscElPhys_Basic()]),
    NewtonIntegrator(damping=0.0, gravity=GRAVITY),
    PyRunner(iterPeriod=MEASURE_EVERY, command="record()"),
]

steps = int(round(T_END / DT))
print(f"{name}: {len(floor)} floor spheres; rods of {len(shape)} spheres, mass "
      f"{DENSITY * SHAPE_VOLUME:.4f} at bounding radius {SHAPE_BOUNDING}; pouring {TOTAL} at "
      f"{pour['rate']:.4g} per unit time; dt = {DT}, {steps} steps to t = {T_END}", flush=True)
O.run(steps, True)
drain()
wall = time.time() - wall_start

spheres = []
with open(out_dir / "grains.csv", "w") as f:
    f.write("x,y,z,radius,clump\n")
    for gid, ids in rods.items():
        for i in ids:
            b = O.bodies[i]
            p = b.state.pos
            spheres.append((p[0], p[1], p[2], b.shape.radius))
            f.write(f"{p[0]:.8g},{p[1]:.8g},{p[2]:.8g},{b.shape.radius:.8g},{gid}\n")
angle, r2 = heap_angle(spheres)
summary = (f"scene {name}.toml (YADE {yade.config.version}, -j1)\n"
           f"t_end {O.time:.4f} ({O.iter} steps of dt {DT}), rods poured {stats['inserted']} of "
           f"{TOTAL}, owed at the end {stats['owed']}, removed {stats['removed']}, in the heap "
           f"{len(rods)}\n"
           f"angle {angle:.4f} degrees (R^2 {r2:.4f}), fitted from {angle_measure['from']} to "
           f"{angle_measure['to']} d over columns {angle_measure['bin']} d wide\n"
           f"height {heap_height(spheres):.4f}, kinetic energy per grain {kinetic_per_grain():.4g}\n"
           f"wall time {wall:.1f} s\n")
(out_dir / "angle.txt").write_text(summary)
print(summary, flush=True)
