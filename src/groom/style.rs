//! The hairstyle of an imported groom: the base style's head, fibre and dynamics, with the
//! counts and lengths of the groom, so that the memory budget, the map's sizing and the camera
//! treat it as any hairstyle.
//!
//! The guides' rest shape comes from the file, so the generated shape's length jitter, wave
//! and curl are zeroed. The same number of real fibres is kept as the base style's: a captured
//! strand stands for `F_base · N_base / N` fibres, fewer when the file has more strands than
//! the base style renders, so the hair's optical density does not depend on the capture. A
//! sparse groom's N render strands (its own and those interpolated among them, `densify.rs`)
//! stand for the base style's fibres on the share of the scalp the groom covers:
//! `F_base · N_base · share / N` each.
//!
//! The style's `guides.reach_m` is the groom's own reach from the head's centre, so the light
//! map holds hair whose roots lie off the head ellipsoid.

use std::path::Path;

use crate::hairstyle::{CurlSpec, Hairstyle};
use crate::input::strands::StrandFile;

/// What of a groom its style follows.
pub(super) struct GroomShape {
    pub(super) wisps: usize,
    /// Render strands: the file's, plus those a sparse groom is densified with.
    pub(super) render_strands: usize,
    /// A sparse groom's share of the base style's scalp (`densify::Density`), `None` for a
    /// dense one.
    pub(super) scalp_share: Option<f32>,
    /// The longest strand once placed, metres.
    pub(super) longest_m: f32,
    /// The farthest a root plus its strand reaches from the head's centre, metres.
    pub(super) reach_m: f32,
}

/// The style of a groom of `shape`, from the files `files` on `base` (see the module doc).
/// The error is the rule the style breaks.
pub(super) fn groom_style(
    base: &Hairstyle,
    files: &[(String, StrandFile)],
    shape: &GroomShape,
) -> Result<Hairstyle, String> {
    let (wisps, count) = (shape.wisps, shape.render_strands);
    let mut style = base.clone();
    style.name = files
        .iter()
        .map(|(name, _)| {
            Path::new(name)
                .file_stem()
                .map_or(name.clone(), |s| s.to_string_lossy().into_owned())
        })
        .collect::<Vec<_>>()
        .join("+");
    let base_strands = base.wisps.count as f32 * base.wisps.strands_per_wisp as f32;
    style.wisps.count = wisps as u32;
    style.wisps.strands_per_wisp = count.div_ceil(wisps) as u32;
    style.guides.length_m = shape.longest_m;
    style.guides.reach_m = Some(shape.reach_m);
    style.guides.length_jitter = 0.0;
    style.guides.wave_amplitude_m = 0.0;
    style.curl = CurlSpec::default();
    // The same number of real fibres as the base style (see the module doc).
    style.strands.fibers_per_strand = match shape.scalp_share {
        None => base.strands.fibers_per_strand * base_strands / count as f32,
        Some(share) => base.strands.fibers_per_strand * base_strands * share / count as f32,
    };
    style
        .validate()
        .map_err(|(field, rule)| format!("the imported style's `{field}` {rule}"))?;
    Ok(style)
}
