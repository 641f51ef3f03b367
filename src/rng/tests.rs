use super::SplitMix64;

/// The first 64 numbers of each of 4,096 streams of a small seed: no number is drawn
/// twice anywhere, as a stream that ran another's sequence shifted would. Seeding by
/// `new(seed ^ b · step)`, the scheme `stream` replaced, fails it (checked below), so the
/// test can fail.
#[test]
fn streams_do_not_repeat_each_other() {
    let draws = |make: &dyn Fn(u64) -> SplitMix64| {
        let mut seen = std::collections::HashSet::new();
        let mut repeats = 0;
        for b in 0..4096 {
            let mut rng = make(b);
            for _ in 0..64 {
                repeats += usize::from(!seen.insert(rng.next_u64()));
            }
        }
        repeats
    };
    assert_eq!(draws(&|b| SplitMix64::stream(3, b)), 0);
    let old = draws(&|b| SplitMix64::new(3 ^ b.wrapping_mul(super::GOLDEN)));
    assert!(old > 100_000, "{old} repeats under the old seeding");
}
