//! Building a [`Motion`] from the bytes of a glTF file, in order: the container and its
//! buffers ([`super::gltf_io`]), the node hierarchy at rest ([`super::skeleton`]), the clip
//! ([`super::clip`]) and the head joint ([`super::joints`]), the character's meshes
//! ([`super::skin`]), the fit of the hairstyle's head ([`super::fit`]), the body colliders
//! ([`super::colliders`]), and last the check that the clip stays within reach
//! ([`super::reach`]).
//!
//! The meshes are read before the fit so that the fit measures the head on the character's own
//! vertices (a file's meshes are decoded once). The nodes every frame evaluates are gathered
//! along the way ([`ChainSet`]): the character's bones first, then the head, the spheres and
//! the capsules.

use std::path::Path;

use glam::{Quat, Vec3};

use super::chain::ChainSet;
use super::chain::JointChain;
use super::clip::{choose_clip, read_clip};
use super::colliders::{character_capsules, sphere_specs};
use super::error::MotionError;
use super::fit::{self, FitMethod};
use super::gltf_io::{Loaded, MAX_FILE_BYTES, parse};
use super::joints::{default_head, resolve_joint};
use super::options::{Fit, MotionOptions};
use super::playback::Motion;
use super::skeleton::{Skeleton, build_skeleton};
use super::skin::{Character, load_character};
use super::up_axis::{standing_turn, topmost_head};

impl Motion {
    /// Loads a glTF 2.0 motion from a `.glb` or `.gltf` file (recognised by content). Relative
    /// buffer URIs are resolved next to the file; `data:` base64 URIs are decoded.
    pub fn load(path: &Path, opts: &MotionOptions) -> Result<Motion, MotionError> {
        let name = path.display().to_string();
        let bytes =
            crate::input::read_capped(path, MAX_FILE_BYTES, "a glTF file").map_err(|error| {
                MotionError::Io {
                    file: name.clone(),
                    error,
                }
            })?;
        from_bytes(&bytes, &name, path.parent(), opts)
    }

    /// Loads a motion from the bytes of a `.glb` (or a self-contained `.gltf` whose buffers
    /// are `data:` URIs). `name_for_errors` is the file name used in error messages.
    pub fn from_glb_bytes(
        bytes: &[u8],
        name_for_errors: &str,
        opts: &MotionOptions,
    ) -> Result<Motion, MotionError> {
        from_bytes(bytes, name_for_errors, None, opts)
    }
}

/// The head mesh's bounding box at rest (model metres, rest world axes) and its vertex count.
type HeadBox = (Vec3, Vec3, usize);

/// Full load: container, clip, joints, character, fit, colliders (see the module doc).
pub(crate) fn from_bytes(
    bytes: &[u8],
    file: &str,
    base_dir: Option<&Path>,
    opts: &MotionOptions,
) -> Result<Motion, MotionError> {
    if !opts.speed.is_finite() {
        return Err(MotionError::BadOption {
            file: file.to_string(),
            reason: format!("speed {} is not finite", opts.speed),
        });
    }
    let loaded = parse(bytes, file, base_dir)?;
    let doc = &loaded.doc;
    let mut skel = build_skeleton(doc, file)?;
    let anim = choose_clip(doc, &loaded, opts.clip.as_deref(), file)?;
    let clip_name = anim
        .name()
        .map_or_else(|| format!("#{}", anim.index()), str::to_string);
    let (head, head_is_topmost) = match &opts.head_joint {
        Some(r) => (resolve_joint(&skel, r, file, "head joint")?, false),
        None => match default_head(&skel, file) {
            Ok(head) => (head, false),
            Err(e) => (topmost_head(&skel).ok_or(e)?, true),
        },
    };
    let (turn, file_up) = if opts.keep_axes {
        (Quat::IDENTITY, Vec3::Y)
    } else {
        standing_turn(&skel, head)
    };
    skel.turn_world(turn);
    let skel = skel;
    let clip = read_clip(&anim, &loaded, file, &clip_name)?;
    let mut chains = ChainSet::new(doc, &skel, clip.tracks).turned(turn);

    let character = if opts.meshes {
        let in_head = skel.subtree(head);
        load_character(&loaded, &skel, &in_head, file, &mut |node| {
            chains.slot(node)
        })?
    } else {
        None
    };
    let head_box = character.as_ref().and_then(head_box);
    let (fit, fit_method) = choose_fit(
        opts,
        head_box,
        character.is_some(),
        &loaded,
        &skel,
        head,
        file,
    )?;
    let head_half_extents_m = head_box.map(|(lo, hi, _)| (hi - lo) * 0.5 / fit.scale);

    let sphere_specs = sphere_specs(opts, character.is_some(), &skel, head, &fit, file)?;
    let head_chain = chains.chain(head);
    let spheres: Vec<(JointChain, Vec3, f32)> = sphere_specs
        .into_iter()
        .map(|(j, off, r)| (chains.chain(j), off, r))
        .collect();
    let capsules = match &character {
        Some(ch) if opts.body_capsules => {
            character_capsules(ch, &skel, head, &fit, head_half_extents_m, &mut chains)
        }
        _ => Vec::new(),
    };

    let motion = Motion {
        clip_name,
        start_s: clip.start_s,
        duration_s: (clip.end_s - clip.start_s).max(0.0),
        speed: opts.speed,
        fit,
        fit_method,
        nodes: chains.into_nodes(),
        head: head_chain,
        spheres,
        capsules,
        character,
        head_half_extents_m,
        head_joint_name: skel.names[head].clone(),
        head_joint_index: head,
        file_up,
        carriers: Vec::new(),
        head_is_topmost,
    };
    motion
        .check_reach()
        .map_err(|reason| MotionError::BadClip {
            file: file.to_string(),
            clip: motion.clip_name.clone(),
            reason,
        })?;
    Ok(motion)
}

/// The head mesh's box at rest: the character's vertices whose strongest bone is in the head's
/// subtree (`None` with fewer than 4).
fn head_box(ch: &Character) -> Option<HeadBox> {
    let (mut lo, mut hi, mut n) = (
        Vec3::splat(f32::INFINITY),
        Vec3::splat(f32::NEG_INFINITY),
        0,
    );
    for v in (0..ch.vertex_count()).filter(|&v| ch.is_head_vertex(v)) {
        lo = lo.min(ch.rest_model[v]);
        hi = hi.max(ch.rest_model[v]);
        n += 1;
    }
    (n >= 4).then_some((lo, hi, n))
}

/// The fit given in `opts` (checked), or estimated: from the head mesh's box, else from the
/// skeleton (without decoding meshes again when a character was read and has no head), else
/// from the file's meshes (see [`fit`]).
fn choose_fit(
    opts: &MotionOptions,
    head_box: Option<HeadBox>,
    has_character: bool,
    loaded: &Loaded,
    skel: &Skeleton,
    head: usize,
    file: &str,
) -> Result<(Fit, FitMethod), MotionError> {
    Ok(match opts.fit {
        Some(f) => {
            if !(f.scale.is_finite() && f.scale > 0.0 && f.offset_m.is_finite()) {
                return Err(MotionError::BadOption {
                    file: file.to_string(),
                    reason: format!("fit {f:?}: scale must be finite and > 0"),
                });
            }
            (f, FitMethod::Given)
        }
        None => match head_box {
            Some((lo, hi, n)) => fit::from_box(lo, hi, n, skel, head),
            // Meshes read above had no head: the fit must not decode them again.
            None if has_character => fit::estimate_without_mesh(skel, head),
            None => fit::estimate(loaded, skel, head),
        },
    })
}
