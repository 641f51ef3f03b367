//! The animation clip: which one is played, and its channels read into [`Track`]s by node.
//!
//! The clip asked for is matched by name (exactly, then in any case); without a request the
//! clip named "Dance" plays, else the first whose name contains "dance", else "idle" (in any
//! case), else the longest (the first of the longest): a rig's clips are often in
//! alphabetical order, and its first ("Agree", "Attack") is rarely the one to watch hair on. Every channel's key times must be finite and
//! strictly increasing (weights channels too: every channel sets the clip's range
//! `[first key, last key]`); translation and scale outputs must be VEC3 and rotation outputs
//! VEC4 quaternions of length in [`ROTATION_KEY_LENGTH`]. Morph-target weights are not read
//! further. A refusal names the clip, the channel (and its node) and the rule.

use glam::Vec4;
use gltf::animation::{Interpolation as GltfInterpolation, Property};

use super::error::MotionError;
use super::gltf_io::{Loaded, read_accessor};
use super::sampler::{Interpolation, Track};

/// Picks the clip: requested name (exact, then any case), else the module doc's default.
pub(super) fn choose_clip<'a>(
    doc: &'a gltf::Document,
    loaded: &Loaded,
    requested: Option<&str>,
    file: &str,
) -> Result<gltf::Animation<'a>, MotionError> {
    let anims: Vec<gltf::Animation> = doc.animations().collect();
    if anims.is_empty() {
        return Err(MotionError::NoAnimations {
            file: file.to_string(),
        });
    }
    let name = |a: &gltf::Animation| {
        a.name()
            .map_or_else(|| format!("#{}", a.index()), str::to_string)
    };
    let find = |want: &str| {
        anims
            .iter()
            .find(|a| name(a) == want)
            .or_else(|| anims.iter().find(|a| name(a).eq_ignore_ascii_case(want)))
            .cloned()
    };
    match requested {
        Some(want) => find(want).ok_or_else(|| MotionError::UnknownClip {
            file: file.to_string(),
            requested: want.to_string(),
            available: anims.iter().map(name).collect(),
        }),
        None => Ok(find("Dance")
            .or_else(|| named_like(&anims, "dance"))
            .or_else(|| named_like(&anims, "idle"))
            .unwrap_or_else(|| longest(&anims, loaded))),
    }
}

/// The first clip whose name contains `word` in any case.
fn named_like<'a>(anims: &[gltf::Animation<'a>], word: &str) -> Option<gltf::Animation<'a>> {
    anims
        .iter()
        .find(|a| a.name().is_some_and(|n| n.to_lowercase().contains(word)))
        .cloned()
}

/// The longest clip by its key times (a clip whose times cannot be read counts as 0 s; the
/// first of equals). `anims` is not empty.
fn longest<'a>(anims: &[gltf::Animation<'a>], loaded: &Loaded) -> gltf::Animation<'a> {
    let duration_s = |a: &gltf::Animation| {
        let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
        for (ci, ch) in a.channels().enumerate() {
            if let Ok(times) = read_key_times(&ch.sampler(), loaded, ci)
                && let (Some(&first), Some(&last)) = (times.first(), times.last())
            {
                (lo, hi) = (lo.min(first), hi.max(last));
            }
        }
        if hi >= lo { hi - lo } else { 0.0 }
    };
    let mut best = (0, f32::NEG_INFINITY);
    for (k, a) in anims.iter().enumerate() {
        let d = duration_s(a);
        if d > best.1 {
            best = (k, d);
        }
    }
    anims[best.0].clone()
}

/// The clip's tracks of the animated nodes: `[translation, rotation, scale]` by node index.
pub(super) type NodeTracks = std::collections::BTreeMap<usize, [Option<Track>; 3]>;

/// Shortest and longest length accepted for a rotation key (glTF rotations are unit
/// quaternions; integer-encoded ones are slightly off, and sampling normalises).
const ROTATION_KEY_LENGTH: (f32, f32) = (0.1, 10.0);

/// A clip read: the tracks by node and the key range over all channels, seconds.
pub(super) struct ClipTracks {
    pub(super) tracks: NodeTracks,
    pub(super) start_s: f32,
    pub(super) end_s: f32,
}

/// Reads every channel of `anim` (named `clip` in messages) into tracks by node.
pub(super) fn read_clip(
    anim: &gltf::Animation,
    loaded: &Loaded,
    file: &str,
    clip: &str,
) -> Result<ClipTracks, MotionError> {
    let bad = |reason: String| MotionError::BadClip {
        file: file.to_string(),
        clip: clip.to_string(),
        reason,
    };
    let mut tracks = NodeTracks::new();
    let (mut start_s, mut end_s) = (f32::INFINITY, f32::NEG_INFINITY);
    for (ci, ch) in anim.channels().enumerate() {
        let times = read_key_times(&ch.sampler(), loaded, ci).map_err(bad)?;
        if let (Some(&a), Some(&b)) = (times.first(), times.last()) {
            start_s = start_s.min(a);
            end_s = end_s.max(b);
        }
        let slot = match ch.target().property() {
            Property::Translation => 0,
            Property::Rotation => 1,
            Property::Scale => 2,
            Property::MorphTargetWeights => continue,
        };
        let (node, track) = read_track(&ch, slot, times, loaded, ci).map_err(bad)?;
        tracks.entry(node).or_default()[slot] = Some(track);
    }
    if !start_s.is_finite() || !end_s.is_finite() {
        return Err(bad("the clip has no keys".to_string()));
    }
    Ok(ClipTracks {
        tracks,
        start_s,
        end_s,
    })
}

/// The key times of channel `ci`'s sampler, each finite and after the previous one.
fn read_key_times(
    sampler: &gltf::animation::Sampler,
    loaded: &Loaded,
    ci: usize,
) -> Result<Vec<f32>, String> {
    let (times, _) =
        read_accessor(&sampler.input(), loaded).map_err(|e| format!("channel {ci} input: {e}"))?;
    // Every channel's times set the clip's range, so check them all (weights too).
    if let Some(k) =
        (0..times.len()).find(|&k| !times[k].is_finite() || (k > 0 && times[k] <= times[k - 1]))
    {
        return Err(format!(
            "channel {ci} input: key time {k} ({} s) is not finite or not after the previous key",
            times[k]
        ));
    }
    Ok(times)
}

/// The track of channel `ci` (property `slot`: 0 translation, 1 rotation, 2 scale) with its
/// key `times`, and the node it animates.
fn read_track(
    ch: &gltf::animation::Channel,
    slot: usize,
    times: Vec<f32>,
    loaded: &Loaded,
    ci: usize,
) -> Result<(usize, Track), String> {
    let sampler = ch.sampler();
    let (vals, comps) = read_accessor(&sampler.output(), loaded)
        .map_err(|e| format!("channel {ci} output: {e}"))?;
    let want = if slot == 1 { 4 } else { 3 };
    if comps != want {
        return Err(format!(
            "channel {ci}: output has {comps} components, expected {want}"
        ));
    }
    let values: Vec<Vec4> = vals
        .chunks_exact(comps)
        .map(|c| {
            if comps == 4 {
                Vec4::new(c[0], c[1], c[2], c[3])
            } else {
                Vec4::new(c[0], c[1], c[2], 0.0)
            }
        })
        .collect();
    let interp = match sampler.interpolation() {
        GltfInterpolation::Linear => Interpolation::Linear,
        GltfInterpolation::Step => Interpolation::Step,
        GltfInterpolation::CubicSpline => Interpolation::CubicSpline,
    };
    let node = ch.target().node().index();
    if slot == 1 {
        check_rotation_keys(&values, interp, ci, node)?;
    }
    let track = Track::new(times, values, interp)
        .map_err(|e| format!("channel {ci} (node {node}): {e}"))?;
    Ok((node, track))
}

/// Refuses a rotation key whose length is outside [`ROTATION_KEY_LENGTH`] (a CUBICSPLINE key
/// is the middle of its in-tangent, value, out-tangent triple).
fn check_rotation_keys(
    values: &[Vec4],
    interp: Interpolation,
    ci: usize,
    node: usize,
) -> Result<(), String> {
    let per_key = if interp == Interpolation::CubicSpline {
        3
    } else {
        1
    };
    let middle = per_key / 2;
    let (lo, hi) = ROTATION_KEY_LENGTH;
    if let Some((k, q)) = values
        .iter()
        .skip(middle)
        .step_by(per_key)
        .enumerate()
        .find(|(_, q)| !(lo..=hi).contains(&q.length()))
    {
        return Err(format!(
            "channel {ci} (node {node}): rotation key {k} has length {} (glTF rotations are unit quaternions)",
            q.length()
        ));
    }
    Ok(())
}
