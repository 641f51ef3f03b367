//! Groom import: clustering alone and the whole build (placement, resampling, clustering,
//! guides, rest offsets, rest-distance report) for synthetic grooms of 5,000 and 50,000
//! strands of 24 vertices (`wisp::groom::synthetic_strands`), in the default rayon pool.
//! Run: `cargo bench --bench groom` (or `-- --quick`).

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use wisp::groom::{GroomOptions, build_groom, synthetic_strands};
use wisp::hairstyle::Hairstyle;

fn import(c: &mut Criterion) {
    let base = Hairstyle::default_smooth();
    let mut group = c.benchmark_group("groom_import");
    group.sample_size(10);
    for count in [5_000usize, 50_000] {
        let files = [("synthetic".to_string(), synthetic_strands(count, 24))];
        let groom = build_groom(&files, &base, &GroomOptions::default()).expect("builds");
        // Clustering alone, on features of the same form as the build's (root, half the
        // vectors to the middle and the tip; here in the file's centimetres).
        let features: Vec<_> = files[0]
            .1
            .strands()
            .map(|pts| {
                let mut f = [0.0f32; 9];
                f[..3].copy_from_slice(&pts[0].to_array());
                f[3..6].copy_from_slice(&((pts[12] - pts[0]) * 0.5).to_array());
                f[6..].copy_from_slice(&((pts[23] - pts[0]) * 0.5).to_array());
                f
            })
            .collect();
        let k = groom.report.wisps;
        group.bench_function(BenchmarkId::new("cluster", count), |b| {
            b.iter(|| black_box(wisp::groom::cluster::cluster(black_box(&features), k)))
        });
        group.bench_function(BenchmarkId::new("build", count), |b| {
            b.iter(|| {
                black_box(build_groom(
                    black_box(&files),
                    &base,
                    &GroomOptions::default(),
                ))
            })
        });
    }
    group.finish();
}

criterion_group!(benches, import);
criterion_main!(benches);
