# Head-on collisions in YADE with the linear spring-dashpot law of yuxi's heap scenes, mapped
# onto ViscElMat as in clump_heap.py; compares the contact duration and the restitution with the
# closed form of the law (docs/models/validation.md L1):
#
#     t_c = pi / sqrt(k_n/m_eff - (gamma_n/2)^2),   e = exp(-gamma_n t_c / 2)
#
# Three cases, no gravity, closing speed 1:
#   free-free   two equal free spheres (d = 1, m = 1): m_eff = 1/2
#   free-fixed  a sphere against a fixed floor sphere: m_eff = m = 1
#   rod-fixed   a rod of three spheres (a clump, mass of the union 2.375) along its axis against a
#               fixed floor sphere: m_eff = the clump's mass
# each at the scene's dt = 8e-4 and at dt = 1e-6 (the law itself, without the step's error).
#
# t_overlap: the time the spheres overlap (the closed form's t_c);
# t_force:   the time the normal force is non-zero (YADE clamps the force at zero: a contact stops
#            pushing, and the grains part, while they still overlap);
# e:         the closing speed after over before.
#
# usage: yade -j1 -n -x check_collision.py      (prints a table)
import math
import sys

from yade import O, utils
from yade.wrapper import (ForceResetter, InsertionSortCollider, Bo1_Sphere_Aabb, InteractionLoop,
                          Ig2_Sphere_Sphere_ScGeom, Ip2_ViscElMat_ViscElMat_ViscElPhys,
                          Law2_ScGeom_ViscElPhys_Basic, NewtonIntegrator, ViscElMat)

K_N, K_T, GAMMA_N, GAMMA_T, MU = 2.0e4, 5714.2857, 50.0, 25.0, 0.5
DENSITY = 1.909859317
SPHERE_MASS = DENSITY * math.pi / 6  # d = 1: m = 1


def rod_mass(k, r=0.5):
    """The mass of the union of k spheres of radius r, r apart in a row."""
    lens = math.pi * (4 * r + r) * (2 * r - r) ** 2 / 12
    return DENSITY * (4 / 3 * math.pi * r**3 + (k - 1) * (4 / 3 * math.pi * r**3 - lens))


def grain_material(mass):
    # YADE joins the two materials' constants in series, a1 a2 / (a1 + a2): twice the pair's
    # stiffness on each side, and the dashpot gamma times the grain's own mass on each side
    # gives gamma m1 m2 / (m1 + m2) = gamma m_eff.
    return O.materials.append(ViscElMat(kn=2 * K_N, ks=2 * K_T, cn=GAMMA_N * mass,
                                        cs=GAMMA_T * mass, frictionAngle=math.atan(MU),
                                        density=DENSITY))


def floor_material():
    # a zero dashpot drops out of the series sum: against the floor cn = gamma m (m_eff = m)
    return O.materials.append(ViscElMat(kn=2 * K_N, ks=2 * K_T, cn=0.0, cs=0.0,
                                        frictionAngle=math.atan(MU), density=DENSITY))


def closed_form(m_eff):
    tc = math.pi / math.sqrt(K_N / m_eff - 0.25 * GAMMA_N**2)
    return tc, math.exp(-0.5 * GAMMA_N * tc)


def collide(case, dt):
    O.reset()
    O.dt = dt
    O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb()], verletDist=0.05),
        InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_ViscElMat_ViscElMat_ViscElPhys()],
                        [Law2_ScGeom_ViscElPhys_Basic()]),
        NewtonIntegrator(damping=0.0, gravity=(0, 0, 0)),
    ]
    gap = 0.01
    if case == "free-free":
        mat = grain_material(SPHERE_MASS)
        a = O.bodies.append(utils.sphere((0, 0, 0), 0.5, material=mat))
        b = O.bodies.append(utils.sphere((1 + gap, 0, 0), 0.5, material=mat))
        O.bodies[a].state.vel = (0.5, 0, 0)
        O.bodies[b].state.vel = (-0.5, 0, 0)
        mover, tip, target, m_eff = a, a, b, 0.5 * SPHERE_MASS
    elif case == "free-fixed":
        mat = grain_material(SPHERE_MASS)
        a = O.bodies.append(utils.sphere((0, 0, 0), 0.5, material=mat))
        b = O.bodies.append(utils.sphere((1 + gap, 0, 0), 0.5, material=floor_material(),
                                         fixed=True))
        O.bodies[a].state.vel = (1, 0, 0)
        mover, tip, target, m_eff = a, a, b, SPHERE_MASS
    else:  # rod-fixed
        mass = rod_mass(3)
        mat = grain_material(mass)
        cid, members = O.bodies.appendClumped(
            [utils.sphere((x, 0, 0), 0.5, material=mat) for x in (-1.0, -0.5, 0.0)])
        O.bodies[cid].state.mass = mass  # the union's (appendClumped sums the members)
        O.bodies[cid].state.vel = (1, 0, 0)
        b = O.bodies.append(utils.sphere((1 + gap, 0, 0), 0.5, material=floor_material(),
                                         fixed=True))
        mover, tip, target, m_eff = cid, members[2], b, mass
    bodies = O.bodies

    def closing():
        v = bodies[mover].state.vel[0] - bodies[target].state.vel[0]
        return v

    def overlap():
        return 1.0 - (bodies[target].state.pos - bodies[tip].state.pos).norm()

    v0 = closing()
    t, prev_ov, prev_t = 0.0, overlap(), 0.0
    start = end = force_end = None
    phys = None
    for _ in range(int(0.2 / dt)):
        O.step()
        t = O.time
        ov = overlap()
        if start is None and ov > 0:
            start = prev_t + (t - prev_t) * (0 - prev_ov) / (ov - prev_ov)
        if start is not None and phys is None and O.interactions.has(tip, target):
            i = O.interactions[tip, target]
            if i.isReal:
                phys = (i.phys.kn, i.phys.cn, i.phys.ks, i.phys.cs)
        if start is not None and force_end is None and O.interactions.has(tip, target):
            i = O.interactions[tip, target]
            if i.isReal and t > start + dt and i.phys.normalForce.norm() == 0 and ov > 0:
                force_end = t
        if start is not None and ov <= 0 and prev_ov > 0:
            end = prev_t + (t - prev_t) * (0 - prev_ov) / (ov - prev_ov)
            force_end = force_end or end
            break
        prev_ov, prev_t = ov, t
    e = -closing() / v0
    tc, e_closed = closed_form(m_eff)
    return dict(case=case, dt=dt, m_eff=m_eff, kn=phys[0], cn=phys[1], ks=phys[2], cs=phys[3],
                t_overlap=end - start, t_force=force_end - start, e=e, tc_closed=tc,
                e_closed=e_closed)


print("case        dt      m_eff   K_n      C_n/m_eff C_s/m_eff t_overlap t_force  t_c(closed) "
      "e       e(closed)")
for case in ("free-free", "free-fixed", "rod-fixed"):
    for dt in (8e-4, 1e-6):
        r = collide(case, dt)
        print(f"{r['case']:<11} {dt:<7.0e} {r['m_eff']:.4f}  {r['kn']:<8.6g} {r['cn'] / r['m_eff']:<9.4g} "
              f"{r['cs'] / r['m_eff']:<9.4g} {r['t_overlap']:.6f}  {r['t_force']:.6f} "
              f"{r['tc_closed']:.6f}    {r['e']:.4f}  {r['e_closed']:.4f}")
sys.stdout.flush()
