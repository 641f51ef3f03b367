//! Writing and reading a simulation cache of the smooth preset (6,432 guide particles, 77.2 KB
//! a frame): one iteration writes a 30-frame cache (create, header, 31 records, flush, fsync,
//! rename) or opens one and reads its 31 records (checksums, times, finite positions within
//! reach of the head). Per frame = iteration / 31. Files go to the system's temporary folder.
//! Run: `cargo bench --bench cache` (or `-- --quick`).

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use wisp::cache::{CacheHeader, CacheReader, CacheWriter, Expected};
use wisp::hairstyle::{Hairstyle, generate};
use wisp::motion::Motion;

const FRAMES: u32 = 30;

fn cache(c: &mut Criterion) {
    let style = Hairstyle::default_smooth();
    let motion = Motion::default_dance();
    let expected = Expected::new(&style, &motion, "the embedded dance");
    let (guides, _) = generate(&style);
    // The rest pose carried by the head at time 0: positions a real frame could hold.
    let head = motion.sample(0.0).head;
    let positions: Vec<_> = guides
        .rest
        .iter()
        .map(|p| head.transform_point3(*p))
        .collect();
    let header = CacheHeader {
        frames: FRAMES,
        particles: expected.particles,
        points_per_guide: expected.points_per_guide,
        fps: 30.0,
        start_s: 0.0,
        settle_s: 2.0,
        hairstyle_digest: expected.hairstyle_digest,
        motion_digest: expected.motion_digest,
        light_dir: glam::Vec3::NEG_Y,
        map_res: 172,
        simulated: false,
        self_collision: false,
        draw_solids: true,
        hairstyle_name: style.name.clone(),
        motion_label: "the embedded dance".into(),
    };
    let dir = std::env::temp_dir().join(format!("wisp-bench-cache-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("bench dir");
    let path = dir.join("bench.wcache");
    let write = || {
        let mut w = CacheWriter::create(&path, header.clone()).expect("create");
        w.write_positions(0.0, &positions).expect("settled");
        for i in 0..FRAMES {
            w.write_positions(header.frame_time_s(i), &positions)
                .expect("frame");
        }
        w.finish().expect("finish");
    };
    let mut group = c.benchmark_group("cache_smooth_30_frames");
    group.sample_size(20);
    group.bench_function("write", |b| b.iter(write));
    write();
    group.bench_function("read", |b| {
        b.iter(|| {
            let mut r = CacheReader::open(&path, &expected).expect("open");
            black_box(r.read_settled(&motion).expect("settled").len());
            for i in 0..FRAMES {
                black_box(r.read_frame(i, &motion).expect("frame")[0]);
            }
        })
    });
    group.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(benches, cache);
criterion_main!(benches);
