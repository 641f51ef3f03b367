use super::*;

/// The table reproduces `linear_to_srgb8` exactly: at every level change and one ulp
/// either side, at every bucket boundary, on 2M bit patterns spread over [0, 1], and on
/// out-of-range and non-finite values.
#[test]
fn srgb_table_matches_transfer_function() {
    let t = Srgb8Table::get();
    let check = |v: f32| assert_eq!(t.srgb8(v), linear_to_srgb8(v), "v = {v:e}");
    let mut changes = 0;
    for b in 0..=BUCKETS {
        let lo = b as f32 / BUCKETS as f32;
        check(lo);
        check(f32::from_bits(lo.to_bits().saturating_sub(1)));
        let th = t.threshold[b];
        if th.is_finite() {
            changes += 1;
            check(th);
            check(f32::from_bits(th.to_bits() - 1));
            check(f32::from_bits(th.to_bits() + 1));
        }
    }
    // Every level 1..=255 starts somewhere, each in its own bucket.
    assert_eq!(changes, 255);
    let one = 1.0_f32.to_bits();
    for i in 0..2_000_000_u32 {
        check(f32::from_bits(
            (u64::from(i) * u64::from(one) / 2_000_000) as u32,
        ));
    }
    for v in [
        -0.0,
        -1e-30,
        -5.0,
        1.0,
        1.000_001,
        7.0,
        f32::NAN,
        -f32::NAN,
        f32::INFINITY,
    ] {
        check(v);
    }
    check(f32::NEG_INFINITY);
}
