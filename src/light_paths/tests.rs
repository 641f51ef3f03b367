//! The light paths' parts against analytic cases: the paths' free flights against Beer–Lambert in a
//! slab of parallel fibres, the gather's units in a white furnace, and the same records for
//! any thread count.

use super::cells::Cells;
use super::trace::Walker;
use super::*;
use crate::fiber::{FiberModel, FiberParams};
use crate::light::Light;
use crate::rng::SplitMix64;

/// The solids of a depth function.
type DepthSolids = Solids<'static, fn(Vec3) -> f32>;
/// No solids (the type of the closure `LightPaths::build` would take).
const NO_SOLIDS: Option<DepthSolids> = None;
/// A box around everything.
const EVERYWHERE: [(Vec3, Vec3); 1] = [(Vec3::NEG_INFINITY, Vec3::INFINITY)];

fn chiang(sigma_a: [f32; 3]) -> Fiber {
    Fiber::new(&FiberParams {
        model: FiberModel::Chiang,
        sigma_a,
        alpha_r_deg: 0.0,
        ..Default::default()
    })
}

/// `n` pieces of fibre along +X, `len_m` long, at uniform random points of the box
/// [−w, w] × [0, depth] × [−w, w] (metres).
fn slab(n: usize, len_m: f32, w: f32, depth: f32, seed: u64) -> (Vec<Vec3>, Vec<Vec3>, Vec<f32>) {
    let mut rng = SplitMix64::new(seed);
    let positions = (0..n)
        .map(|_| {
            Vec3::new(
                -w + 2.0 * w * rng.unit(),
                depth * rng.unit(),
                -w + 2.0 * w * rng.unit(),
            )
        })
        .collect();
    (positions, vec![Vec3::X; n], vec![len_m; n])
}

/// The points of [`slab`] as one fibre per strand.
fn points<'a>(p: &'a [Vec3], u: &'a [Vec3], l: &'a [f32]) -> StrandPoints<'a> {
    StrandPoints {
        positions: p,
        tangents: u,
        lengths_m: l,
        fibers_per_strand: 1.0,
    }
}

/// Paths shot down into a slab of fibres at right angles, and at 60° to them, pass without a
/// hit with probability exp(−2r λ sin ψ L): λ the fibre length per volume, L the path's length
/// in the slab. Delta tracking, the majorant and the acceptance (ℓ/ℓ_max · sin ψ) together
/// must give that rate.
#[test]
fn free_flights_follow_beer_lambert_in_a_slab() {
    let (w, depth, len) = (0.02f32, 0.008f32, 0.0015f32);
    let n = 12_000;
    let (p, u, l) = slab(n, len, w, depth, 5);
    let cells = Cells::build(&points(&p, &u, &l), 0.004).expect("cells");
    let r = 40e-6f32;
    let walker = Walker {
        cells: &cells,
        sigma_per_len: 2.0 * r / cells.cell_m.powi(3),
    };
    // Fibre length per volume: the pieces fill [−w − len/2, w + len/2] along X.
    let lambda = n as f32 * len / ((2.0 * w + len) * depth * (2.0 * w));
    let mut rng = SplitMix64::new(9);
    for cos_to_fiber in [0.0f32, 0.5] {
        let sin = (1.0 - cos_to_fiber * cos_to_fiber).sqrt();
        let d = Vec3::new(cos_to_fiber, -sin, 0.0);
        let tau = 2.0 * r * lambda * (depth / sin) * sin;
        let shots = 200_000;
        let mut passed = 0;
        for _ in 0..shots {
            // Entering the slab's top well inside its edges, from above.
            let at = Vec3::new(
                -0.5 * w + w * rng.unit(),
                depth + 0.01,
                -0.5 * w + w * rng.unit(),
            );
            let start = at - d * (0.01 / sin);
            let mut sink = Vec::new();
            if walker
                .fly(start, d, false, Vec3::ONE, &mut rng, &mut sink)
                .is_none()
            {
                passed += 1;
            }
            assert!(sink.is_empty(), "unscattered light leaves no record");
        }
        let measured = passed as f64 / shots as f64;
        let want = (-tau as f64).exp();
        // Binomial error (0.001) plus the cells' Poisson counts (about 0.5% of the value).
        assert!(
            (measured - want).abs() < 0.004 + 0.01 * want,
            "cos to fibre {cos_to_fiber}: τ {tau:.3}, passed {measured:.4}, Beer–Lambert {want:.4}"
        );
    }
}

/// Records of isotropic light (directions uniform on the sphere) of total share φ give a
/// white fibre the radiance φ/4π whatever its tangent and view: Chiang's model has
/// ∫ S cos θi dωi = 1 for every ωo (`chiang.rs`, "Energy"), so the gather's units are those
/// of the shader's (radiance = S cos θi × irradiance).
#[test]
fn isotropic_records_light_a_white_fiber_by_a_quarter_pi() {
    let fiber = chiang([0.0; 3]);
    let (p, u, l) = slab(10, 0.001, 0.004, 0.004, 1);
    let cells = Cells::build(&points(&p, &u, &l), 0.004).expect("cells");
    let k = 200_000;
    let phi = 3.0f32;
    let mut rng = SplitMix64::new(4);
    let from: Vec<Vec3> = (0..k)
        .map(|_| {
            let z = 2.0 * rng.unit() - 1.0;
            let a = std::f32::consts::TAU * rng.unit();
            let s = (1.0 - z * z).max(0.0).sqrt();
            Vec3::new(s * a.cos(), s * a.sin(), z)
        })
        .collect();
    let count = cells.slots;
    // Every slot holds the same records.
    let mut starts = vec![0u32; count + 1];
    let mut all_from = Vec::new();
    for c in 0..count {
        all_from.extend_from_slice(&from);
        starts[c + 1] = ((c + 1) * k) as u32;
    }
    let paths = LightPaths {
        fluence: vec![Vec3::splat(phi / k as f32); all_from.len()],
        from: all_from,
        starts,
        cell_m: cells.cell_m,
        cells,
        moments: Vec::new(),
        scatterings: 0,
    };
    let centre = paths.cells.origin + paths.cells.dims.as_vec3() * (0.5 * paths.cells.cell_m);
    for (tangent, view) in [
        (Vec3::X, Vec3::Z),
        (Vec3::X, Vec3::new(0.6, 0.0, 0.8)),
        (
            Vec3::new(0.0, 0.6, 0.8),
            Vec3::new(-0.8, 0.36, -0.48).normalize(),
        ),
    ] {
        let got = paths.indirect(&fiber, None, centre, tangent, view, Vec3::splat(0.5));
        let want = phi / (4.0 * std::f32::consts::PI);
        for ch in got.to_array() {
            assert!(
                (ch / want - 1.0).abs() < 0.02,
                "tangent {tangent}, view {view}: {got} against φ/4π = {want}"
            );
        }
    }
}

/// The same records, bit for bit, on one thread and on two.
#[test]
fn the_same_records_for_any_thread_count() {
    let fiber = chiang([0.3, 0.5, 0.9]);
    let (p, u, l) = slab(3_000, 0.002, 0.01, 0.006, 2);
    let params = LightPathParams {
        cell_m: 0.002,
        paths: 5_000,
        seed: 77,
        ..Default::default()
    };
    let overhead = Light::directional(-Vec3::Y, Vec3::ONE).expect("light");
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool")
            .install(|| {
                LightPaths::build(&fiber, &points(&p, &u, &l), &overhead, &params, NO_SOLIDS)
                    .expect("light paths")
            })
    };
    let (a, b) = (run(1), run(2));
    assert!(a.records() > 1_000, "{} records", a.records());
    assert_eq!(a.starts, b.starts);
    let bits = |v: &[Vec3]| {
        v.iter()
            .flat_map(|x| x.to_array().map(f32::to_bits))
            .collect::<Vec<_>>()
    };
    assert_eq!(bits(&a.from), bits(&b.from));
    assert_eq!(bits(&a.fluence), bits(&b.fluence));
    assert_eq!(a.scatterings, b.scatterings);
}

/// A point light far away lights the hair as a directional light of irradiance I/d² along the
/// same line: the cone's power I·Ω/N per path against the plane's E·A/N. The records' summed
/// light agrees within the paths' noise.
#[test]
fn a_distant_point_light_is_a_directional_light_of_irradiance_i_over_d_squared() {
    let fiber = chiang([0.2, 0.3, 0.5]);
    let (p, u, l) = slab(4_000, 0.002, 0.01, 0.006, 8);
    let params = LightPathParams {
        cell_m: 0.002,
        paths: 40_000,
        seed: 3,
        ..Default::default()
    };
    let cells = Cells::build(&points(&p, &u, &l), params.cell_m).expect("cells");
    let centre = cells.origin + cells.dims.as_vec3() * (0.5 * cells.cell_m);
    let distance = 20.0;
    let point = Light::Point {
        position_m: centre + Vec3::Y * distance,
        intensity: Vec3::splat(400.0),
    };
    let sun =
        Light::directional(-Vec3::Y, Vec3::splat(400.0 / (distance * distance))).expect("light");
    let total = |light: &Light| {
        let v = LightPaths::build(&fiber, &points(&p, &u, &l), light, &params, NO_SOLIDS)
            .expect("light paths");
        v.fluence.iter().copied().sum::<Vec3>()
    };
    let (a, b) = (total(&point), total(&sun));
    println!("point {a}, directional {b}");
    assert!(a.min_element() > 0.0);
    for (x, y) in a.to_array().into_iter().zip(b.to_array()) {
        assert!(
            (x / y - 1.0).abs() < 0.04,
            "point {a} against directional {b}"
        );
    }
}

/// A solid between the light and the hair takes all its light: a layer over the hair's top
/// (every cell above it), lit from straight above, leaves no record; without it the same paths
/// leave thousands. Cells only partly inside a solid let light pass (the depth must exceed
/// half a cell's diagonal), and only the cells in the solids' boxes are asked.
#[test]
fn solids_absorb_the_light_that_enters_them() {
    let fiber = chiang([0.2, 0.3, 0.5]);
    let (p, u, l) = slab(2_000, 0.002, 0.01, 0.006, 4);
    let params = LightPathParams {
        cell_m: 0.002,
        paths: 10_000,
        seed: 1,
        ..Default::default()
    };
    let overhead = Light::directional(-Vec3::Y, Vec3::ONE).expect("light");
    let roof = |q: Vec3| if q.y > 0.0065 { 1.0 } else { 0.0 };
    let shallow = |q: Vec3| if q.y > 0.0065 { 1e-4 } else { 0.0 };
    // The roof's box, and one beside the slab that holds none of it.
    let over = [(Vec3::new(-1.0, 0.0065, -1.0), Vec3::splat(1.0))];
    let beside = [(Vec3::new(0.5, 0.0, 0.5), Vec3::splat(1.0))];
    let build = |depth: Option<&(dyn Fn(Vec3) -> f32 + Sync)>, within: &[(Vec3, Vec3)]| {
        LightPaths::build(
            &fiber,
            &points(&p, &u, &l),
            &overhead,
            &params,
            depth.map(|f| Solids {
                depth_m: move |q: Vec3| f(q),
                within_m: within,
            }),
        )
        .expect("light paths")
        .records()
    };
    let open = build(None, &EVERYWHERE);
    assert!(open > 1_000, "{open} records with no solid");
    assert_eq!(build(Some(&roof), &EVERYWHERE), 0, "light passed the roof");
    assert_eq!(
        build(Some(&roof), &over),
        0,
        "light passed the roof in its box"
    );
    assert_eq!(
        build(Some(&roof), &beside),
        open,
        "a solid's cells were asked outside its boxes"
    );
    assert_eq!(
        build(Some(&shallow), &EVERYWHERE),
        open,
        "a solid shallower than half a cell's diagonal stops nothing"
    );
}

/// Merging a cell's flights by direction keeps its light to rounding, gives one record per
/// bin reached with the light-weighted mean of its directions, and keeps slots apart: every
/// channel's sum per slot is what its flights held, and a flight alone in its bin keeps its
/// own direction.
#[test]
fn merging_by_direction_keeps_each_cells_light() {
    let mut rng = SplitMix64::new(12);
    let n = 8;
    // Three slots: 500 flights, 1 flight, none.
    let counts = [500usize, 1, 0];
    let mut bins = super::bins::Bins::new(3, n);
    let mut sums = [Vec3::ZERO; 3];
    let mut lone = Vec3::ZERO;
    for (slot, &k) in counts.iter().enumerate() {
        for _ in 0..k {
            let z = 2.0 * rng.unit() - 1.0;
            let a = std::f32::consts::TAU * rng.unit();
            let s = (1.0 - z * z).max(0.0).sqrt();
            let d = Vec3::new(s * a.cos(), s * a.sin(), z);
            let e = Vec3::new(rng.unit(), rng.unit(), rng.unit());
            bins.add(slot, d, e);
            sums[slot] += e;
            lone = d;
        }
    }
    let super::bins::Finished {
        starts,
        from,
        light,
        rest,
    } = bins.finish(None);
    assert!(rest.is_empty(), "every bin kept: no moments");
    assert_eq!(starts.len(), 4);
    let first = (starts[1] - starts[0]) as usize;
    assert!(
        first <= n * n && first > 40,
        "{first} bins reached by 500 flights"
    );
    assert_eq!(starts[2] - starts[1], 1);
    assert_eq!(starts[3], starts[2]);
    for (slot, want) in sums.iter().enumerate() {
        let got: Vec3 = light[starts[slot] as usize..starts[slot + 1] as usize]
            .iter()
            .copied()
            .sum();
        assert!(
            (got - *want).abs().max_element() <= 1e-4 * (1.0 + want.max_element()),
            "slot {slot}: {want} → {got}"
        );
    }
    assert!((from[starts[1] as usize] - lone).length() < 1e-6);
    for d in &from {
        assert!((d.length() - 1.0).abs() < 1e-5);
    }
    let reached: std::collections::BTreeSet<usize> = from[..first]
        .iter()
        .map(|d| super::bins::octahedral_bin(*d, n))
        .collect();
    assert_eq!(reached.len(), first, "one merged record per bin");
}

/// The octahedral map sends every direction to a bin, the six axes to six different bins, and
/// opposite directions to different bins.
#[test]
fn octahedral_bins_cover_the_sphere() {
    let n = 8;
    let axes = [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z];
    let bins: std::collections::BTreeSet<usize> = axes
        .iter()
        .map(|d| super::bins::octahedral_bin(*d, n))
        .collect();
    assert_eq!(bins.len(), 6);
    let mut rng = SplitMix64::new(2);
    let mut hit = vec![0u32; n * n];
    for _ in 0..100_000 {
        let d = Vec3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5).normalize();
        let k = super::bins::octahedral_bin(d, n);
        hit[k] += 1;
        assert_ne!(k, super::bins::octahedral_bin(-d, n), "{d}");
    }
    assert!(hit.iter().all(|&h| h > 0), "every bin is reached: {hit:?}");
}

/// Bins over their memory cap enlarge the cells until they fit, rather than exceed it.
#[test]
fn cells_grow_until_the_bins_fit_their_cap() {
    let fiber = chiang([0.2, 0.3, 0.5]);
    let (p, u, l) = slab(4_000, 0.002, 0.02, 0.01, 6);
    let overhead = Light::directional(-Vec3::Y, Vec3::ONE).expect("light");
    let build = |max_bins_bytes: u64| {
        let params = LightPathParams {
            cell_m: 0.001,
            paths: 2_000,
            max_bins_bytes,
            ..Default::default()
        };
        LightPaths::build(&fiber, &points(&p, &u, &l), &overhead, &params, NO_SOLIDS)
            .expect("light paths")
    };
    let (free, capped) = (build(u64::MAX), build(2_000_000));
    let bytes = |v: &LightPaths| super::bins::Bins::estimated_bytes(v.cells.slots as u64, 8);
    assert_eq!(free.cell_m, 0.001);
    assert!(
        bytes(&free) > 2_000_000,
        "the test needs a cap that binds: {}",
        bytes(&free)
    );
    assert!(capped.cell_m > 0.001, "cells of {} m", capped.cell_m);
    assert!(
        bytes(&capped) <= 2_000_000,
        "{} B over the cap",
        bytes(&capped)
    );
}

/// A block's records filed by the merge's ranges of slots keep, within each range, the order
/// the paths left them (what makes the merged sums the same bits as adding them one by one),
/// and every record is in exactly one range: its own.
#[test]
fn filed_records_keep_their_order_within_each_range() {
    let mut rng = SplitMix64::new(31);
    let records: Vec<Record> = (0..2_000)
        .map(|i| Record {
            slot: (rng.next_u64() % 37) as u32,
            from: Vec3::X,
            power_m: Vec3::splat(i as f32),
        })
        .collect();
    let (span, ranges) = (10, 4);
    let filed = super::records::BlockRecords::new(records.clone(), span, ranges);
    let mut seen = 0;
    for j in 0..ranges {
        let want: Vec<f32> = records
            .iter()
            .filter(|r| r.slot as usize / span == j)
            .map(|r| r.power_m.x)
            .collect();
        let got: Vec<f32> = filed.range(j).iter().map(|r| r.power_m.x).collect();
        assert_eq!(got, want, "range {j}");
        seen += got.len();
    }
    assert_eq!(seen, records.len());
    assert!(filed.range(ranges).is_empty());
}

/// A white fibre (σa = 0) conserves energy, so its response to isotropic light,
/// A₀ = ∫ S cos θi dωi, is 1 at every inclination (what the gather's white furnace pins for the
/// bins); the tables' quadrature must give it within 1%.
#[test]
fn a_white_fibres_response_to_isotropic_light_is_one() {
    let response = super::response::AngularResponse::new(&chiang([0.0; 3]));
    for deg in [-85.0f32, -60.0, -30.0, 0.0, 20.0, 45.0, 80.0] {
        let a0 = response.at(deg.to_radians()).a0;
        assert!(
            (a0 - Vec3::ONE).abs().max_element() < 0.01,
            "θo = {deg}°: A₀ = {a0}"
        );
    }
}

/// Light kept as moments to the second order and gathered through the tabulated integrals
/// against the BCSDF evaluated flight by flight (200,000 directions): isotropic light is
/// exact but for the quadrature (within 2%), light over a cap of 1 − cos = 0.5 (60°) reads
/// within 20% (the truncation of what lies past the second order), and a cap of 0.2 (37°)
/// reads 1.5–1.7× too bright: why a cell keeps its strongest bins as they are.
#[test]
fn moments_gather_as_the_flights_do_where_light_is_spread() {
    let fiber = chiang([0.126, 0.209, 0.411]);
    let response = super::response::AngularResponse::new(&fiber);
    let mut rng = SplitMix64::new(77);
    let u = Vec3::new(0.3, 0.9, 0.1).normalize();
    let wo = Vec3::new(-0.2, 0.1, 1.0).normalize();
    let unshadowed = crate::fiber::LightAtPoint::UNSHADOWED;
    let axis = Vec3::new(0.5, -0.3, 0.8).normalize();
    let (b1, b2) = axis.any_orthonormal_pair();
    for (spread, lo, hi) in [(2.0f32, 0.98, 1.02), (0.5, 1.0, 1.2), (0.2, 1.4, 1.8)] {
        let mut m = super::moments::Moment::default();
        let mut exact = Vec3::ZERO;
        let n = 200_000;
        for _ in 0..n {
            // Uniform over the cap of 1 − cos θ ≤ spread about the axis (2: the sphere).
            let z = 1.0 - spread * rng.unit();
            let a = std::f32::consts::TAU * rng.unit();
            let s = (1.0 - z * z).max(0.0).sqrt();
            let d = axis * z + b1 * (s * a.cos()) + b2 * (s * a.sin());
            let e = Vec3::splat(1.0 / n as f32);
            m.add(d, e);
            exact += fiber.shade(
                crate::fiber::ShadingMode::SingleScattering,
                u,
                d,
                wo,
                &unshadowed,
            ) * e;
        }
        let got = super::gather::rest_of(&m, &response, u, wo);
        let ratio = got / exact;
        assert!(
            ratio.min_element() >= lo && ratio.max_element() <= hi,
            "cap {spread}: moments ÷ flights = {ratio}, want [{lo}, {hi}]"
        );
    }
}

/// Keeping a cell's strongest bins and the rest as moments keeps all its light: the records
/// and the moments' M₀ add up to the bins' sums, the records are the strongest, and with
/// room for every bin nothing goes to the moments.
#[test]
fn the_strongest_bins_and_the_moments_keep_all_the_light() {
    let n = 8;
    let fill = || {
        let mut rng = SplitMix64::new(5);
        let mut bins = super::bins::Bins::new(2, n);
        let mut sums = [Vec3::ZERO; 2];
        for (slot, sum) in sums.iter_mut().enumerate() {
            for _ in 0..400 {
                let d = Vec3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5);
                let e = Vec3::new(rng.unit(), rng.unit(), rng.unit()) * rng.unit().powi(4);
                bins.add(slot, d.normalize(), e);
                *sum += e;
            }
        }
        (bins, sums)
    };
    let (all, _) = fill();
    let all = all.finish(None);
    assert!(all.rest.is_empty(), "every bin kept: no moments");
    let (bins, sums) = fill();
    let f = bins.finish(Some(4));
    assert_eq!(f.rest.len(), 2);
    for (slot, sum) in sums.iter().enumerate() {
        let range = f.starts[slot] as usize..f.starts[slot + 1] as usize;
        assert_eq!(range.len(), 4);
        let total = f.light[range.clone()].iter().copied().sum::<Vec3>() + f.rest[slot].m0;
        assert!(
            (total - *sum).abs().max_element() < 1e-4 * sum.max_element(),
            "slot {slot}: {total} of {sum}"
        );
        let mut every: Vec<f32> = all.light
            [all.starts[slot] as usize..all.starts[slot + 1] as usize]
            .iter()
            .map(|l| l.element_sum())
            .collect();
        every.sort_by(|a, b| b.total_cmp(a));
        let kept: Vec<f32> = f.light[range].iter().map(|l| l.element_sum()).collect();
        assert_eq!(
            kept,
            every[..4],
            "slot {slot}: the records are the 4 strongest bins"
        );
    }
}
