//! The hairstyle of an imported groom: the base style's head, fibre and dynamics, with the
//! counts and lengths of the groom, so that the memory budget, the map's sizing and the camera
//! treat it as any hairstyle.
//!
//! The guides' rest shape comes from the file, so the generated shape's length jitter, wave
//! and curl are zeroed. The same number of real fibres is kept as the base style's: a captured
//! strand stands for `F_base · N_base / N` fibres, fewer when the file has more strands than
//! the base style renders, so the hair's optical density does not depend on the capture.

use std::path::Path;

use crate::hairstyle::{CurlSpec, Hairstyle};
use crate::input::strands::StrandFile;

/// The style of a groom of `count` strands in `wisps` wisps whose longest strand is
/// `longest_m` once placed, from the files `files` on `base` (see the module doc). The error
/// is the rule the style breaks.
pub(super) fn groom_style(
    base: &Hairstyle,
    files: &[(String, StrandFile)],
    wisps: usize,
    count: usize,
    longest_m: f32,
) -> Result<Hairstyle, String> {
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
    style.guides.length_m = longest_m;
    style.guides.length_jitter = 0.0;
    style.guides.wave_amplitude_m = 0.0;
    style.curl = CurlSpec::default();
    // The same number of real fibres as the base style (see the module doc).
    style.strands.fibers_per_strand = base.strands.fibers_per_strand * base_strands / count as f32;
    style
        .validate()
        .map_err(|(field, rule)| format!("the imported style's `{field}` {rule}"))?;
    Ok(style)
}
