use super::*;

#[test]
fn start_wraps_into_one_loop() {
    assert_eq!(wrapped_start_s(4.0, 8.0, 1.0), (4.0, false));
    assert_eq!(wrapped_start_s(1e12, 8.0, 1.0), (0.0, true));
    assert_eq!(wrapped_start_s(-1.0, 8.0, 1.0), (7.0, true));
    // At speed 2 one loop of an 8 s clip lasts 4 s.
    assert_eq!(wrapped_start_s(5.0, 8.0, 2.0), (1.0, true));
    // A still motion has no loop: it starts at 0.
    assert_eq!(wrapped_start_s(3.0, 0.0, 1.0), (0.0, true));
    let (t, _) = wrapped_start_s(-1e-300, 8.0, 1.0);
    assert!((0.0..8.0).contains(&t));
}
