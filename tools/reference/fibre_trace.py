"""A path tracer for fibres thinner than Mitsuba's ray offset (not run by CI).

Mitsuba 3 starts every shadow ray and every continued path at the surface point moved along
the normal by (1 + max |p|) x RayEpsilon, about 1e-4 m in float32 variants for a scene within
a metre of the origin: 2.5 radii of a 40 µm fibre. Each ray leaving a fibre therefore starts
past the fibres touching it, which in dense hair are the ones that shadow it most (measured on
the dense brown side-lit case: a shadow ray from the hit itself leaves 5% less light than
Mitsuba's, weighted by the BSDF). This module keeps Mitsuba's scene, intersection, `hair` BSDF
(its `eval` and `sample`), emitter and camera, and replaces only where rays start:

- a ray leaving the fibre's surface outward starts `delta_m` off the surface, along the
  fibre's radius;
- a ray leaving into the fibre (the BSDF's transmitted lobes, or a light behind the point)
  crosses it: it starts `delta_m` beyond where its line leaves the fibre's cylinder. The
  fibre's interior is the BSDF's business (the `hair` BSDF is a whole-fibre scattering
  function), so the fibre does not shadow itself.

Otherwise it is Mitsuba's `path` integrator: next-event estimation of the (delta) light, the
scene's directional or point light (whose shadow rays end at it), at every interaction whose depth + 1 < max_depth, BSDF sampling to continue, Russian
roulette from depth 5 with probability min(max throughput, 0.95), a box pixel filter, alpha =
the camera ray's coverage. With `spawn="mitsuba"` it starts rays where Mitsuba does
(`SurfaceInteraction.spawn_ray`), which reproduces Mitsuba's own renders within their noise
(ACCURACY.md section 2, "The path tracer's ray offset").

Each curve of the scene is one straight polyline segment (hairfile.py), so a hit's fibre is
the segment of its primitive index, whose axis gives the radius and the way out.
"""

import numpy as np

RR_DEPTH = 5


def unit(v):
    return v / np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), 1e-12)


class Fibres:
    """Each curve's straight axis (its polyline segment): start point and unit tangent."""

    def __init__(self, strands):
        self.a = strands.points[strands.seg_first]
        self.t = unit(strands.points[strands.seg_first + 1] - self.a)


def leave(fibres, prim, p, d, delta_m):
    """Where a ray in unit direction `d` from surface point `p` of curve `prim` starts: `delta_m`
    off the surface outward, or, into the fibre, `delta_m` past its exit through the fibre's
    cylinder (float64 arrays, [n, 3])."""
    a, t = fibres.a[prim], fibres.t[prim]
    rel = p - a
    w = rel - (rel * t).sum(1)[:, None] * t
    radial = unit(w)
    outward = (d * radial).sum(1) >= 0.0
    dperp = d - (d * t).sum(1)[:, None] * t
    # |w + s dperp| = |w| again at s = -2 w.dperp / |dperp|^2 (the far side of the circle).
    s = -2.0 * (w * dperp).sum(1) / np.maximum((dperp * dperp).sum(1), 1e-12)
    exit_p = p + d * np.maximum(s, 0.0)[:, None]
    rel2 = exit_p - a
    exit_radial = unit(rel2 - (rel2 * t).sum(1)[:, None] * t)
    return np.where(outward[:, None], p + radial * delta_m, exit_p + exit_radial * delta_m)


def _vec(mi, x, kind):
    x = np.ascontiguousarray(x, np.float32)
    return kind(x[:, 0], x[:, 1], x[:, 2])


def lit_at(mi, mscene, fibres, prim, p, hit, to_light, delta_m, light_pos=None):
    """Whether the light in direction `to_light` (Mitsuba Vector3f, unit) reaches surface points
    `p` of curves `prim` (numpy, the `hit` lanes only): a shadow ray leaving each fibre as
    `leave` starts it. A point light at `light_pos` (metres) ends the ray just short of it; a
    directional light's ray is unbounded."""
    d = np.array(to_light, np.float64).T
    start = leave(fibres, prim, p, unit(d), delta_m)
    if light_pos is None:
        shadow = mi.Ray3f(_vec(mi, start, mi.Point3f), to_light)
    else:
        maxt = np.linalg.norm(np.asarray(light_pos, np.float64) - start, axis=1) * (1 - 1e-4)
        shadow = mi.Ray3f(_vec(mi, start, mi.Point3f), to_light,
                          mi.Float(maxt.astype(np.float32)), 0.0, [])
    return ~np.array(mscene.ray_test(shadow, mi.Bool(hit)), bool) & hit


def hit_points(si, hit):
    """The curve and surface point of each hit of `si` (numpy; 0 where `hit` is false)."""
    prim = np.array(si.prim_index, np.int64) * hit
    p = np.array(si.p, np.float64).T
    p[~hit] = 0.0
    return prim, p


def lit_at_hits(mi, mscene, fibres, si, hit, to_light, delta_m=1e-6):
    """`lit_at` for the hits `si` (numpy bool mask `hit`)."""
    prim, p = hit_points(si, hit)
    return lit_at(mi, mscene, fibres, prim, p, hit, to_light, delta_m)


def render(mi, mscene, scene, strands, spp, seed, max_depth, spawn="fibre", delta_m=1e-6):
    """One pass of `spp` paths per pixel: an [H, W, 4] float64 image (linear RGB, alpha)."""
    w, h = scene["image"]["width"], scene["image"]["height"]
    n = w * h * spp
    rng = np.random.default_rng([seed, max_depth, 7])
    fibres = Fibres(strands)
    light_pos = scene["light"].get("position_m")
    ctx = mi.BSDFContext()
    sensor = mscene.sensors()[0]
    pixel = np.arange(n) // spp
    pos = np.stack([(pixel % w + rng.random(n)) / w, (pixel // w + rng.random(n)) / h], 1)
    ray, _ = sensor.sample_ray(0.0, 0.0, mi.Point2f(pos[:, 0].astype(np.float32),
                                                    pos[:, 1].astype(np.float32)),
                               mi.Point2f(0.5, 0.5))
    o = np.array(ray.o, np.float64).T
    d = np.array(ray.d, np.float64).T
    radiance = np.zeros((n, 3))
    alpha = np.zeros(n)
    lane = np.arange(n)
    throughput = np.ones((n, 3))
    for depth in range(max_depth):
        if len(lane) == 0:
            break
        si = mscene.ray_intersect(mi.Ray3f(_vec(mi, o, mi.Point3f), _vec(mi, d, mi.Vector3f)))
        hit = np.array(si.is_valid(), bool)
        if depth == 0:
            alpha[lane] = hit
        if depth + 1 >= max_depth or not hit.any():
            break
        m = len(lane)
        active = mi.Bool(hit)
        prim, p = hit_points(si, hit)
        bsdf = si.bsdf()
        # Next-event estimation of the directional light.
        ds, em_weight = mscene.sample_emitter_direction(
            si, mi.Point2f(rng.random(m).astype(np.float32), rng.random(m).astype(np.float32)),
            False, active)
        f = bsdf.eval(ctx, si, si.to_local(ds.d), active)
        if spawn == "mitsuba":
            shadow = si.spawn_ray(ds.d) if light_pos is None else si.spawn_ray_to(ds.p)
            lit = ~np.array(mscene.ray_test(shadow, active), bool) & hit
        else:
            lit = lit_at(mi, mscene, fibres, prim, p, hit, ds.d, delta_m, light_pos)
        contrib = np.array(f, np.float64).T * np.array(em_weight, np.float64).T
        radiance[lane] += np.where(lit[:, None], throughput * contrib, 0.0)
        # Continue by sampling the BSDF.
        bs, weight = bsdf.sample(ctx, si, mi.Float(rng.random(m).astype(np.float32)),
                                 mi.Point2f(rng.random(m).astype(np.float32),
                                            rng.random(m).astype(np.float32)), active)
        wo = si.to_world(bs.wo)
        d_new = np.array(wo, np.float64).T
        throughput = throughput * np.array(weight, np.float64).T
        throughput[~hit] = 0.0
        alive = hit & (np.array(bs.pdf, np.float64) > 0.0) & (throughput.max(1) > 0.0)
        if depth + 1 >= RR_DEPTH:
            q = np.minimum(throughput.max(1), 0.95)
            survive = rng.random(m) < q
            throughput = throughput / np.maximum(q, 1e-30)[:, None]
            alive &= survive
        if spawn == "mitsuba":
            o_new = np.array(si.spawn_ray(wo).o, np.float64).T
        else:
            o_new = leave(fibres, prim, p, unit(d_new), delta_m)
        lane, o, d, throughput = lane[alive], o_new[alive], d_new[alive], throughput[alive]
    img = np.zeros((h * w, 4))
    np.add.at(img[:, :3], pixel, radiance)
    np.add.at(img[:, 3], pixel, alpha)
    return (img / spp).reshape(h, w, 4)
