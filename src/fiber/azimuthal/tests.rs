use super::*;

#[test]
fn erf_reference_values() {
    // erf(0.5) = 0.5204998778, erf(1) = 0.8427007929, erf(2) = 0.9953222650 (tables).
    assert!((erf(0.5) - 0.520_499_877_8).abs() < 2e-7);
    assert!((erf(1.0) - 0.842_700_792_9).abs() < 2e-7);
    assert!((erf(-2.0) + 0.995_322_265_0).abs() < 2e-7);
}
