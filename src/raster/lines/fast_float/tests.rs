use super::*;

#[test]
fn ceil_index_matches_ceil() {
    for v in [0.0_f32, 0.2, 1.0, 1.5, 7.999, 1e6, 1.5e9] {
        assert_eq!(ceil_index(v), v.ceil() as usize, "{v}");
    }
}
