//! A groom kept where it was authored: not fitted onto wisp's head, only converted from the
//! file's units to metres, its roots pinned where they are (the fur of an animal, a groom made
//! for a head that is not there).
//!
//! The units are given (`GroomOptions::unit_m`) or guessed from the groom's size, the diagonal
//! `D` of its points' bounding box in file units: `D ≤ 5` is metres (a head of hair is about
//! 0.5 m across, a horse's coat 3 m), `5 < D ≤ 300` centimetres, larger millimetres. The
//! guess is said in the import's line, so a wrong one is one flag away.

use glam::{Quat, Vec3};

use super::fit::Placement;
use super::place::OnHead;
use super::strands::Kept;

/// Largest groom diagonal (file units) taken as metres.
pub const METRES_UP_TO: f32 = 5.0;
/// Largest groom diagonal (file units) taken as centimetres; above it, millimetres.
pub const CENTIMETRES_UP_TO: f32 = 300.0;

/// Metres per file unit for a groom whose points span a box of diagonal `diagonal`.
pub fn guess_unit_m(diagonal: f32) -> f32 {
    if diagonal <= METRES_UP_TO {
        1.0
    } else if diagonal <= CENTIMETRES_UP_TO {
        0.01
    } else {
        0.001
    }
}

/// Where a groom kept as authored on its own character lies in the head frame: the file's
/// coordinates are the character's, so they are turned as the model was to stand upright
/// (`Motion::file_turn`) and moved so that the head centre at rest (`Motion::head_at_rest`,
/// pose metres) is the origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AuthoredFrame {
    pub upright: Quat,
    pub head_at_rest_m: Vec3,
}

/// The placement of the `kept` strands as authored: scaled by `unit_m` (guessed when `None`)
/// and, on a character, put in its head frame (`frame`); not fitted, so their roots are where
/// the file has them and none is off a head. Also returns the unit used and whether it was
/// guessed.
pub(super) fn as_authored(
    kept: &[Kept],
    unit_m: Option<f32>,
    frame: Option<AuthoredFrame>,
) -> (OnHead, f32, bool) {
    let (lo, hi) = kept.iter().flat_map(|k| k.points.iter()).fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let diagonal = (hi - lo).length();
    let unit = unit_m.unwrap_or_else(|| guess_unit_m(diagonal));
    let on_head = OnHead {
        placement: Placement {
            scale: unit,
            yaw_rad: 0.0,
            offset_m: frame.map_or(Vec3::ZERO, |f| -f.head_at_rest_m),
            upright: frame.map_or(Quat::IDENTITY, |f| f.upright),
        },
        root_distance_m: vec![0.0; kept.len()],
        worst_m: 0.0,
        from_root_sphere: false,
    };
    (on_head, unit, unit_m.is_none())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_are_guessed_from_the_size() {
        // A head of hair 0.5 m across in metres, 50 cm in centimetres, 500 mm in millimetres.
        assert_eq!(guess_unit_m(0.5), 1.0);
        assert_eq!(guess_unit_m(50.0), 0.01);
        assert_eq!(guess_unit_m(500.0), 0.001);
        // A horse's coat, 3 m in metres and 300 cm in centimetres.
        assert_eq!(guess_unit_m(3.0), 1.0);
        assert_eq!(guess_unit_m(300.0), 0.01);
    }
}
