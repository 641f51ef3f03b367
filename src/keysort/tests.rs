use super::*;

#[test]
fn radix_sort_matches_comparison_sort() {
    let mut state = 0x1234_5678_9ABC_DEF1_u64;
    for n in [0, 5, 63, 64, 1000, 5000] {
        let mut keys: Vec<u64> = (0..n)
            .map(|pos| {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                // Depth-like keys: one exponent, few distinct values (ties by position).
                let depth = 1.0 + (state % 97) as f32 * 0.01;
                (u64::from(depth.to_bits()) << 32) | pos
            })
            .collect();
        let mut expected = keys.clone();
        expected.sort_unstable();
        sort_keys(&mut keys, &mut Vec::new());
        assert_eq!(keys, expected, "n {n}");
    }
}

proptest::proptest! {
    /// The bits' order is `total_cmp`'s for any two floats, NaNs, infinities and signed
    /// zeros included.
    #[test]
    fn total_order_bits_keep_total_order(
        a in proptest::num::f32::ANY,
        b in proptest::num::f32::ANY,
    ) {
        proptest::prop_assert_eq!(total_order_bits(a).cmp(&total_order_bits(b)), a.total_cmp(&b));
    }
}
