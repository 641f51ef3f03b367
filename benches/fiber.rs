//! Fibre model costs, for both models (Marschner 2003, Chiang 2016): building every table
//! (`Fiber::new`, runs at program start), one shade call per mode (runs per render-strand vertex
//! per frame), and `forward_scatter` (per map sample per frame). Inputs are 1024 fixed
//! pseudo-random direction pairs, so results compare across runs. Names without a model suffix
//! are Marschner's (as before); Chiang's end in `_chiang`.

use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec3;
use std::hint::black_box;
use wisp::fiber::{Fiber, FiberModel, FiberParams, LightAtPoint, ShadingMode};

fn directions(n: usize) -> Vec<(Vec3, Vec3)> {
    let mut s: u64 = 1;
    let mut next = move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 40) as f32 / (1u64 << 24) as f32
    };
    let mut dir = move || {
        let z = 2.0 * next() - 1.0;
        let a = std::f32::consts::TAU * next();
        let r = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(r * a.cos(), z, r * a.sin())
    };
    (0..n).map(|_| (dir(), dir())).collect()
}

fn bench(c: &mut Criterion) {
    for (suffix, model) in [("", FiberModel::Marschner), ("_chiang", FiberModel::Chiang)] {
        bench_model(c, suffix, model);
    }
}

fn bench_model(c: &mut Criterion, suffix: &str, model: FiberModel) {
    let params = FiberParams {
        model,
        ..Default::default()
    };
    c.bench_function(&format!("fiber_new{suffix}"), |b| {
        b.iter(|| Fiber::new(black_box(&params)))
    });
    let fiber = Fiber::new(&params);
    let pairs = directions(1024);
    let u = Vec3::new(0.2, 0.9, 0.1).normalize();
    let light = LightAtPoint {
        direct_fraction: 0.3,
        tf: Vec3::new(0.6, 0.4, 0.2),
        sigma_f2: Vec3::splat(0.02),
        crossings_behind: LightAtPoint::DENSE,
    };
    for (name, mode) in [
        ("shade_dual_x1024", ShadingMode::DualScattering),
        ("shade_single_x1024", ShadingMode::SingleScattering),
        ("shade_kajiya_kay_x1024", ShadingMode::KajiyaKay),
    ] {
        c.bench_function(&format!("{name}{suffix}"), |b| {
            b.iter(|| {
                let mut acc = Vec3::ZERO;
                for (wi, wo) in &pairs {
                    acc += fiber.shade(mode, u, *wi, *wo, black_box(&light));
                }
                acc
            })
        });
    }
    // The local-density truncation of Ā_b (a finite `crossings_behind`).
    let sparse = LightAtPoint {
        crossings_behind: 2.0,
        ..light
    };
    c.bench_function(&format!("shade_dual_density_x1024{suffix}"), |b| {
        b.iter(|| {
            let mut acc = Vec3::ZERO;
            for (wi, wo) in &pairs {
                acc += fiber.shade(ShadingMode::DualScattering, u, *wi, *wo, black_box(&sparse));
            }
            acc
        })
    });
    // Coherent input, as along a strand: the view sweeps slowly across 1024 vertices.
    let sweep: Vec<(Vec3, Vec3)> = (0..1024)
        .map(|k| {
            let t = k as f32 / 1024.0;
            let wi = Vec3::new(0.7, 0.3, 0.648).normalize();
            let wo = Vec3::new((3.0 * t).cos(), 0.2 - 0.4 * t, (3.0 * t).sin()).normalize();
            (wi, wo)
        })
        .collect();
    c.bench_function(&format!("shade_dual_coherent_x1024{suffix}"), |b| {
        b.iter(|| {
            let mut acc = Vec3::ZERO;
            for (wi, wo) in &sweep {
                acc += fiber.shade(ShadingMode::DualScattering, u, *wi, *wo, black_box(&light));
            }
            acc
        })
    });
    c.bench_function(&format!("forward_scatter_x1024{suffix}"), |b| {
        b.iter(|| {
            let mut acc = Vec3::ZERO;
            for (wi, _) in &pairs {
                acc += fiber.forward_scatter(black_box(wi.y)).a_f;
            }
            acc
        })
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
