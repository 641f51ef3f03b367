//! Synthetic fur authored on a character: short straight strands rooted on the vertices of
//! the character's rest-pose mesh, in the character's own frame and metres, for the groom
//! kept as authored on its character (`--groom-as-authored --animation FILE`,
//! `motion::carriers`) in tests and in `examples/fur_on_character.rs`.

use crate::input::strands::StrandFile;
use glam::Vec3;

/// Points per fur strand.
pub const FUR_POINTS: usize = 4;

/// One strand of [`FUR_POINTS`] points and `length_m` metres rooted at every `every`-th point
/// of `surface` (≥ 1), growing straight away from the surface's centroid (outward on a
/// body, roughly along the skin's normal). Empty for an empty surface.
pub fn synthetic_fur(surface: &[Vec3], every: usize, length_m: f32) -> StrandFile {
    let mut fur = StrandFile::default();
    if surface.is_empty() {
        return fur;
    }
    let centre = surface.iter().copied().sum::<Vec3>() / surface.len() as f32;
    for v in surface.iter().step_by(every.max(1)) {
        let out = (*v - centre).normalize_or(Vec3::Y);
        for k in 0..FUR_POINTS {
            let along = length_m * k as f32 / (FUR_POINTS - 1) as f32;
            fur.points.push(*v + out * along);
        }
        fur.strand_points.push(FUR_POINTS as u32);
    }
    fur
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fur_grows_away_from_the_centre_from_every_nth_vertex() {
        let surface = [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z];
        let fur = synthetic_fur(&surface, 2, 0.03);
        // Vertices 0, 2 and 4; the centroid is (0, 0, 0.2).
        assert_eq!(fur.strand_points, vec![4, 4, 4]);
        assert_eq!(fur.points[0], Vec3::X);
        let tip = fur.points[3];
        assert!((tip.distance(Vec3::X) - 0.03).abs() < 1e-6);
        let out = (Vec3::X - Vec3::new(0.0, 0.0, 0.2)).normalize();
        assert!((tip - Vec3::X).normalize().distance(out) < 1e-6);
        assert!(synthetic_fur(&[], 3, 0.01).points.is_empty());
    }
}
