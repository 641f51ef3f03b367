//! Why a groom could not be imported ([`GroomError`]): a strand file that cannot be read, a
//! rule the strands break (naming the files, and the strand where there is one), or roots that
//! do not lie on the head once the groom is fitted to it (naming the worst strand, its
//! distance and the fit, so a user can tell a wrong orientation from a wrong head).

use crate::input::strands::StrandFileError;

/// Why a groom could not be imported.
#[derive(Debug, thiserror::Error)]
pub enum GroomError {
    #[error(transparent)]
    File(#[from] StrandFileError),
    #[error("{files}: {rule}")]
    Invalid { files: String, rule: String },
    /// Neither the fit onto the head nor the sphere through the roots places the groom (its
    /// roots are not a scalp's: fur, or roots in one point or on a line).
    #[error(
        "{files}: the groom cannot be placed on the head: fitted to the head it shrinks under {min_mm:.0} mm, and no sphere passes through its roots (are they a scalp's?)"
    )]
    NotOnAHead { files: String, min_mm: f32 },
    #[error(
        "{file}: strand {strand}: its root is {distance_mm:.0} mm from the head surface after fitting the groom to the head (scale {scale:.4}, turn {yaw_deg:.0}°), and {share:.0}% of all roots are over {tolerance_mm:.0} mm: the groom's roots do not lie on a head (is it Y-up?)"
    )]
    RootsOffHead {
        file: String,
        strand: usize,
        distance_mm: f32,
        tolerance_mm: f32,
        share: f32,
        scale: f32,
        yaw_deg: f32,
    },
}
