use super::*;
use crate::budget::{DEFAULT_MEMORY_BYTES, DEFAULT_WORK_CPU_S};

#[test]
fn presets_fit_the_default_budget_with_room() {
    let est = estimate(
        &Hairstyle::default_smooth(),
        &Motion::still(glam::Affine3A::IDENTITY),
        &EngineConfig::default(),
        &RunPlan::default(),
    );
    est.check(&Budget::default()).unwrap();
    // About 470 MB: the hair line raster (227 MB at 800 × 800, most of it the fragments
    // kept from the seen pass to the composite, bounded by all it could emit) and the
    // light map's per-frame entries (136 MB; each sample piece is splatted to 4
    // columns): under an eighth of the default budget.
    assert!(est.memory_bytes() < DEFAULT_MEMORY_BYTES / 8, "{est:#?}");
    assert!(est.work_cpu_s() < DEFAULT_WORK_CPU_S / 100.0, "{est:#?}");
}

#[test]
fn a_cache_adds_its_record_buffer_and_reading_one_skips_the_settle() {
    let style = Hairstyle::default_smooth();
    let motion = Motion::still(glam::Affine3A::IDENTITY);
    let config = EngineConfig::default();
    let plan = |cache| RunPlan {
        warm_up_s: 3.0,
        cache,
        ..RunPlan::default()
    };
    let none = estimate(&style, &motion, &config, &plan(CacheUse::None));
    let read = estimate(&style, &motion, &config, &plan(CacheUse::Read));
    let write = estimate(&style, &motion, &config, &plan(CacheUse::Write));
    let part = |e: &Estimate| {
        e.memory
            .iter()
            .find(|p| p.what == "simulation cache")
            .map(|p| p.bytes)
    };
    assert_eq!(part(&none), None);
    // 6,432 particles: a record of 8 + 12·6,432 + 4 bytes, and the positions (12 B each).
    assert_eq!(part(&read), Some(77_196 + 77_184));
    assert_eq!(part(&write), Some(77_196 + 8_192));
    // Reading a cache simulates nothing: no settle, no warm-up.
    assert_eq!(read.work[0].cpu_s, 0.0);
    assert_eq!(read.work[1].cpu_s, 0.0);
    assert!(none.work[0].cpu_s > 0.0 && none.work[1].cpu_s > 0.0);
    assert_eq!(write.work[0].cpu_s, none.work[0].cpu_s);
}

#[test]
fn over_budget_names_the_largest_part() {
    let est = estimate(
        &Hairstyle::default_smooth(),
        &Motion::still(glam::Affine3A::IDENTITY),
        &EngineConfig::default(),
        &RunPlan::default(),
    );
    let tight = Budget {
        memory_bytes: 1_000,
        ..Budget::default()
    };
    let e = est.check(&tight).unwrap_err().to_string();
    assert!(e.contains("over the budget of 1.0 KB"), "{e}");
    let slow = Budget {
        work_cpu_s: 1e-6,
        ..Budget::default()
    };
    let e = est.check(&slow).unwrap_err().to_string();
    assert!(e.contains("CPU-seconds before its first frame"), "{e}");
}
