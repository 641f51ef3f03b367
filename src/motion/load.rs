//! Building a [`super::Motion`] from a parsed glTF: node hierarchy at rest, clip and joint
//! choice, the clip's tracks, and the evaluated chains (root to joint) that `sample_into`
//! walks. Container and accessor reading live in [`super::gltf_io`].

use std::path::Path;

use glam::{Affine3A, Quat, Vec3, Vec4};
use gltf::animation::{Interpolation as GltfInterpolation, Property};

use super::capsules;
use super::fit::{self, FitMethod};
use super::gltf_io::{Loaded, parse, read_accessor};
use super::sampler::{Interpolation, Track};
use super::skeleton::{Skeleton, build_skeleton, rest_trs};
use super::skin::load_character;
use super::{CapsuleSpec, ChainNode, JointChain, JointRef, Motion, MotionError, MotionOptions};

/// Resolves a [`JointRef`]: exact name, then case-insensitive; joints before other nodes.
fn resolve_joint(
    skel: &Skeleton,
    r: &JointRef,
    file: &str,
    role: &str,
) -> Result<usize, MotionError> {
    let found = match r {
        JointRef::Index(i) => (*i < skel.names.len()).then_some(*i),
        JointRef::Name(name) => {
            let by = |pred: &dyn Fn(usize) -> bool| (0..skel.names.len()).find(|&i| pred(i));
            by(&|i| skel.is_joint[i] && skel.names[i] == *name)
                .or_else(|| by(&|i| skel.names[i] == *name))
                .or_else(|| by(&|i| skel.is_joint[i] && skel.names[i].eq_ignore_ascii_case(name)))
                .or_else(|| by(&|i| skel.names[i].eq_ignore_ascii_case(name)))
        }
    };
    found.ok_or_else(|| MotionError::UnknownJoint {
        file: file.to_string(),
        role: role.to_string(),
        requested: match r {
            JointRef::Index(i) => format!(
                "with node index {i} (the file has {} nodes)",
                skel.names.len()
            ),
            JointRef::Name(n) => format!("named {n:?}"),
        },
        available: skel.joint_list(),
    })
}

/// Default head: a joint named "head" (any case), else the shortest joint name containing
/// "head" but neither "end" nor "top" (skips `Head_end`, `HeadTop_End`).
fn default_head(skel: &Skeleton, file: &str) -> Result<usize, MotionError> {
    let lower: Vec<String> = skel.names.iter().map(|n| n.to_lowercase()).collect();
    let joints = || (0..skel.names.len()).filter(|&i| skel.is_joint[i]);
    joints()
        .find(|&i| lower[i] == "head")
        .or_else(|| {
            joints()
                .filter(|&i| {
                    lower[i].contains("head")
                        && !lower[i].contains("end")
                        && !lower[i].contains("top")
                })
                .min_by_key(|&i| (lower[i].len(), i))
        })
        .ok_or_else(|| MotionError::UnknownJoint {
            file: file.to_string(),
            role: "head joint".to_string(),
            requested: "named like \"head\"".to_string(),
            available: skel.joint_list(),
        })
}

/// Picks the clip: requested name (exact, then any case), else "Dance", else the first.
fn choose_clip<'a>(
    doc: &'a gltf::Document,
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
        None => Ok(find("Dance").unwrap_or_else(|| anims[0].clone())),
    }
}

/// The clip's tracks of the animated nodes: `[translation, rotation, scale]` by node index.
type NodeTracks = std::collections::BTreeMap<usize, [Option<Track>; 3]>;

/// Shortest and longest length accepted for a rotation key (glTF rotations are unit
/// quaternions; integer-encoded ones are slightly off, and sampling normalises).
const ROTATION_KEY_LENGTH: (f32, f32) = (0.1, 10.0);

fn read_clip(
    anim: &gltf::Animation,
    loaded: &Loaded,
    file: &str,
    clip: &str,
) -> Result<(NodeTracks, f32, f32), MotionError> {
    let bad = |reason: String| MotionError::BadClip {
        file: file.to_string(),
        clip: clip.to_string(),
        reason,
    };
    let mut tracks = NodeTracks::new();
    let (mut start_s, mut end_s) = (f32::INFINITY, f32::NEG_INFINITY);
    for (ci, ch) in anim.channels().enumerate() {
        let sampler = ch.sampler();
        let (times, _) = read_accessor(&sampler.input(), loaded)
            .map_err(|e| bad(format!("channel {ci} input: {e}")))?;
        // Every channel's times set the clip's range, so check them all (weights too).
        if let Some(k) =
            (0..times.len()).find(|&k| !times[k].is_finite() || (k > 0 && times[k] <= times[k - 1]))
        {
            return Err(bad(format!(
                "channel {ci} input: key time {k} ({} s) is not finite or not after the previous key",
                times[k]
            )));
        }
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
        let (vals, comps) = read_accessor(&sampler.output(), loaded)
            .map_err(|e| bad(format!("channel {ci} output: {e}")))?;
        let want = if slot == 1 { 4 } else { 3 };
        if comps != want {
            return Err(bad(format!(
                "channel {ci}: output has {comps} components, expected {want}"
            )));
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
                return Err(bad(format!(
                    "channel {ci} (node {node}): rotation key {k} has length {} (glTF rotations are unit quaternions)",
                    q.length()
                )));
            }
        }
        let track = Track::new(times, values, interp)
            .map_err(|e| bad(format!("channel {ci} (node {node}): {e}")))?;
        tracks.entry(node).or_default()[slot] = Some(track);
    }
    if !start_s.is_finite() || !end_s.is_finite() {
        return Err(bad("the clip has no keys".to_string()));
    }
    Ok((tracks, start_s, end_s))
}

/// Full load: container, clip, joints, fit, spheres.
pub(crate) fn from_bytes(
    bytes: &[u8],
    file: &str,
    base_dir: Option<&Path>,
    opts: &MotionOptions,
) -> Result<Motion, MotionError> {
    let bad_option = |reason: String| MotionError::BadOption {
        file: file.to_string(),
        reason,
    };
    if !opts.speed.is_finite() {
        return Err(bad_option(format!("speed {} is not finite", opts.speed)));
    }
    let loaded = parse(bytes, file, base_dir)?;
    let doc = &loaded.doc;
    let skel = build_skeleton(doc, file)?;
    let anim = choose_clip(doc, opts.clip.as_deref(), file)?;
    let clip_name = anim
        .name()
        .map_or_else(|| format!("#{}", anim.index()), str::to_string);
    let head = match &opts.head_joint {
        Some(r) => resolve_joint(&skel, r, file, "head joint")?,
        None => default_head(&skel, file)?,
    };
    let (mut tracks, start_s, end_s) = read_clip(&anim, &loaded, file, &clip_name)?;

    // Evaluated nodes: the union of the chains, each node once, parents first.
    let mut nodes: Vec<ChainNode> = Vec::new();
    let mut slot_of: Vec<Option<usize>> = vec![None; skel.names.len()];
    let mut make_chain = |joint: usize| -> JointChain {
        let chain = skel.chain(joint);
        let mut idx: Vec<usize> = Vec::with_capacity(chain.len());
        for &n in &chain {
            let parent = idx.last().copied();
            let slot = *slot_of[n].get_or_insert_with(|| {
                let [t, r, s] = tracks.remove(&n).unwrap_or_default();
                let nd = doc.nodes().nth(n);
                let (rt, rr, rs, m) = nd.as_ref().map_or(
                    (Vec3::ZERO, Quat::IDENTITY, Vec3::ONE, Affine3A::IDENTITY),
                    rest_trs,
                );
                let is_matrix = nd.is_some_and(|nd| {
                    matches!(nd.transform(), gltf::scene::Transform::Matrix { .. })
                });
                let animated = t.is_some() || r.is_some() || s.is_some();
                nodes.push(ChainNode {
                    parent,
                    rest_matrix: (is_matrix && !animated).then_some(m),
                    rest_t: rt,
                    rest_r: rr,
                    rest_s: rs,
                    translation: t,
                    rotation: r,
                    scale: s,
                });
                nodes.len() - 1
            });
            idx.push(slot);
        }
        JointChain {
            chain: idx,
            rest_align: super::rigid_rotation(&skel.rest_world(joint)).inverse(),
        }
    };

    let in_head = skel.subtree(head);
    let character = if opts.meshes {
        let mut bone_slot = |node: usize| make_chain(node).chain.last().copied().unwrap_or(0);
        load_character(&loaded, &skel, &in_head, file, &mut bone_slot)?
    } else {
        None
    };
    // The head mesh's box at rest (model metres, rest world axes): the character's vertices
    // whose strongest bone is in the head's subtree.
    let head_box = character.as_ref().and_then(|ch| {
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
    });

    let (fit, fit_method) = match opts.fit {
        Some(f) => {
            if !(f.scale.is_finite() && f.scale > 0.0 && f.offset_m.is_finite()) {
                return Err(bad_option(format!(
                    "fit {f:?}: scale must be finite and > 0"
                )));
            }
            (f, FitMethod::Given)
        }
        None => match head_box {
            Some((lo, hi, n)) => fit::from_box(lo, hi, n, &skel, head),
            // Meshes read above had no head: the fit must not decode them again.
            None if character.is_some() => fit::estimate_without_mesh(&skel, head),
            None => fit::estimate(&loaded, &skel, head),
        },
    };
    let head_half_extents_m = head_box.map(|(lo, hi, _)| (hi - lo) * 0.5 / fit.scale);

    let sphere_specs: Vec<(usize, Vec3, f32)> = match &opts.body_spheres {
        None if character.is_some() && opts.body_capsules => Vec::new(),
        None => fit::default_spheres(&skel, head, &fit),
        Some(specs) => {
            let mut out = Vec::with_capacity(specs.len());
            for s in specs {
                if !(s.radius_m.is_finite() && s.radius_m > 0.0 && s.offset_m.is_finite()) {
                    return Err(bad_option(format!(
                        "body sphere {s:?}: radius must be > 0, values finite"
                    )));
                }
                out.push((
                    resolve_joint(&skel, &s.joint, file, "body sphere joint")?,
                    s.offset_m,
                    s.radius_m,
                ));
            }
            out
        }
    };

    let head_chain = make_chain(head);
    let spheres: Vec<(JointChain, Vec3, f32)> = sphere_specs
        .into_iter()
        .map(|(j, off, r)| (make_chain(j), off, r))
        .collect();
    let capsules: Vec<CapsuleSpec> = match &character {
        Some(ch) if opts.body_capsules => {
            // The head ellipsoid at rest in model space: the mesh's box, or the fitted
            // 0.09 m head.
            let centre = Vec3::from(skel.rest_world(head).translation) + fit.offset_m;
            let radii = head_half_extents_m
                .map_or(Vec3::splat(super::HAIRSTYLE_HEAD_RADIUS_M), |h| h)
                * fit.scale;
            let head_ellipsoid =
                Affine3A::from_scale_rotation_translation(radii, Quat::IDENTITY, centre);
            let bone_of: Vec<usize> = (0..ch.vertex_count())
                .map(|v| ch.joints[v][super::skin::dominant(&ch.weights[v])] as usize)
                .collect();
            // Each bone's direction at rest: from its node to the mean of its children.
            let mut child_sum = vec![(Vec3::ZERO, 0u32); skel.names.len()];
            for (i, p) in skel.parents.iter().enumerate() {
                if let Some(p) = *p {
                    child_sum[p].0 += Vec3::from(skel.rest_world(i).translation);
                    child_sum[p].1 += 1;
                }
            }
            let bone_dir: Vec<Vec3> = ch
                .bones
                .iter()
                .map(|b| {
                    let (sum, n) = child_sum[b.node];
                    if n == 0 {
                        return Vec3::ZERO;
                    }
                    let d = sum / n as f32 - Vec3::from(skel.rest_world(b.node).translation);
                    // Shorter than a millimetre at the fitted scale: no direction.
                    if d.length() > 1e-3 * fit.scale {
                        d
                    } else {
                        Vec3::ZERO
                    }
                })
                .collect();
            capsules::fit(
                &ch.rest_model,
                &bone_of,
                &ch.bone_in_head,
                &bone_dir,
                head_ellipsoid,
                capsules::HEAD_DEPTH_M * fit.scale,
                capsules::MIN_RADIUS_M * fit.scale,
            )
            .into_iter()
            .map(|c| {
                let bone = &ch.bones[c.bone];
                let to_bind = (skel.rest_world(bone.node) * bone.bind).inverse();
                CapsuleSpec {
                    chain: make_chain(bone.node),
                    bind: bone.bind,
                    a: to_bind.transform_point3(c.a),
                    b: to_bind.transform_point3(c.b),
                    radius_m: c.radius / fit.scale,
                }
            })
            .collect()
        }
        _ => Vec::new(),
    };

    let motion = Motion {
        clip_name,
        start_s,
        duration_s: (end_s - start_s).max(0.0),
        speed: opts.speed,
        fit,
        fit_method,
        nodes,
        head: head_chain,
        spheres,
        capsules,
        character,
        head_half_extents_m,
        head_joint_name: skel.names[head].clone(),
        head_joint_index: head,
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
