use super::*;

/// The Vogel spiral fills the unit disc evenly: the share of points within radius ρ is ρ².
#[test]
fn vogel_spiral_is_area_uniform() {
    let n = 4096;
    for rho in [0.25f32, 0.5, 0.9] {
        let inside = (0..n).filter(|&i| vogel(i, n).length() < rho).count();
        let share = inside as f32 / n as f32;
        assert!(
            (share - rho * rho).abs() < 2.0 / n as f32 + 1e-3,
            "{rho}: {share}"
        );
    }
}
