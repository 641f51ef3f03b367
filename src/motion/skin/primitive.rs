//! One triangle primitive of a character: its vertices (positions, normals, texture
//! coordinates, bone influences) and triangles appended to the [`Character`], each attribute
//! checked (see [`super::load`] for the rules).
//!
//! Influences are read from `JOINTS_0` and `WEIGHTS_0`: a weight that is not finite or not
//! positive is dropped, the rest divided by their sum (`wₖ / Σ w`); a vertex left without
//! weight follows the skin's first joint with weight 1, as does every vertex of a skinned
//! primitive without both attributes. A rigid mesh's vertices follow its node's one bone.

use glam::{Vec2, Vec3};
use gltf::Semantic;

use super::{Character, MAX_TRIANGLES, MAX_VERTICES};
use crate::motion::error::{MotionError, invalid};
use crate::motion::gltf_io::{Loaded, read_accessor};

/// A triangle primitive to append, with what its vertices follow.
pub(super) struct PrimitiveInput<'a> {
    pub(super) prim: &'a gltf::Primitive<'a>,
    /// Bones (indices into `Character::bones`) of the skin's joints, or the rigid node's one.
    pub(super) bones: &'a [u16],
    /// The vertices follow a skin (read `JOINTS_0` and `WEIGHTS_0`).
    pub(super) skinned: bool,
    /// Index of the primitive's material in `Character::materials`.
    pub(super) material: u16,
    /// The `TEXCOORD_n` set its material's texture reads, if any.
    pub(super) uv_set: Option<u32>,
    /// The vertices of an earlier primitive with the same accessors and bones (first index,
    /// count), which this one shares.
    pub(super) shared: Option<(u32, usize)>,
    /// "meshes[m].primitives[p]", for messages.
    pub(super) at: &'a str,
}

/// Bone influences of each vertex: bone indices and weights (summing to 1).
type Influences = (Vec<[u16; 4]>, Vec<[f32; 4]>);

/// Appends one triangle primitive (see the module doc for the rules); its vertices are
/// appended too unless `p.shared` gives those of an earlier primitive. Returns where its
/// vertices are (first index, count).
pub(super) fn read_primitive(
    ch: &mut Character,
    p: &PrimitiveInput,
    loaded: &Loaded,
    file: &str,
) -> Result<(u32, usize), MotionError> {
    let fail = |rule: String| invalid(file, format!("{}: {rule}", p.at));
    if let Some((base, n)) = p.shared {
        let tris = read_triangles(p.prim, n, loaded, &fail)?;
        check_triangle_count(ch, tris.len(), &fail)?;
        push_triangles(ch, &tris, base, p.material);
        return Ok((base, n));
    }
    let read = |s: Semantic| -> Result<Option<(Vec<f32>, usize)>, MotionError> {
        match p.prim.get(&s) {
            None => Ok(None),
            Some(a) => read_accessor(&a, loaded)
                .map(Some)
                .map_err(|e| fail(format!("{s:?}: {e}"))),
        }
    };
    let Some((pos, 3)) = read(Semantic::Positions)? else {
        return Err(fail("POSITION is missing or not VEC3".into()));
    };
    let n = pos.len() / 3;
    let base = ch.bind_pos.len();
    if base + n > MAX_VERTICES {
        return Err(fail(format!(
            "the meshes have more than {MAX_VERTICES} vertices"
        )));
    }
    let positions: Vec<Vec3> = pos.chunks_exact(3).map(Vec3::from_slice).collect();
    if let Some(v) = positions.iter().position(|p| !p.is_finite()) {
        return Err(fail(format!("POSITION: vertex {v} is not finite")));
    }
    let tris = read_triangles(p.prim, n, loaded, &fail)?;
    check_triangle_count(ch, tris.len(), &fail)?;
    let normals: Vec<Vec3> = match read(Semantic::Normals)? {
        Some((v, 3)) if v.len() == 3 * n => v
            .chunks_exact(3)
            .map(|c| Vec3::from_slice(c).normalize_or(Vec3::Y))
            .collect(),
        _ => face_normals(&positions, &tris),
    };
    let uvs: Vec<Vec2> = match p.uv_set.map(|s| read(Semantic::TexCoords(s))).transpose()? {
        Some(Some((v, 2))) if v.len() == 2 * n => v
            .chunks_exact(2)
            .map(|c| {
                let uv = Vec2::new(c[0], c[1]);
                if uv.is_finite() { uv } else { Vec2::ZERO }
            })
            .collect(),
        _ => vec![Vec2::ZERO; n],
    };
    let rigid = || (vec![[p.bones[0]; 4]; n], vec![[1.0, 0.0, 0.0, 0.0]; n]);
    let (joints, weights) = if p.skinned {
        match (read(Semantic::Joints(0))?, read(Semantic::Weights(0))?) {
            (Some((j, 4)), Some((w, 4))) if j.len() == 4 * n && w.len() == 4 * n => {
                influences(&j, &w, p.bones, &fail)?
            }
            _ => rigid(),
        }
    } else {
        rigid()
    };
    ch.bind_pos.extend(positions);
    ch.bind_nrm.extend(normals);
    ch.uv.extend(uvs);
    ch.joints.extend(joints);
    ch.weights.extend(weights);
    push_triangles(ch, &tris, base as u32, p.material);
    Ok((base as u32, n))
}

/// Refuses `added` more triangles when the character would have more than [`MAX_TRIANGLES`].
fn check_triangle_count(
    ch: &Character,
    added: usize,
    fail: &dyn Fn(String) -> MotionError,
) -> Result<(), MotionError> {
    if ch.triangles.len() + added > MAX_TRIANGLES {
        return Err(fail(format!(
            "the meshes have more than {MAX_TRIANGLES} triangles"
        )));
    }
    Ok(())
}

/// Appends triangles whose vertex indices count from `base`, all of `material`.
fn push_triangles(ch: &mut Character, tris: &[[u32; 3]], base: u32, material: u16) {
    ch.triangles
        .extend(tris.iter().map(|t| t.map(|i| i + base)));
    ch.triangle_material
        .extend(std::iter::repeat_n(material, tris.len()));
}

/// Each vertex's four influences from `JOINTS_0` (`j`) and `WEIGHTS_0` (`w`), 4 values per
/// vertex: joint slots mapped to `bones`, weights normalised (see the module doc).
fn influences(
    j: &[f32],
    w: &[f32],
    bones: &[u16],
    fail: &dyn Fn(String) -> MotionError,
) -> Result<Influences, MotionError> {
    let n = j.len() / 4;
    let mut js = Vec::with_capacity(n);
    let mut ws = Vec::with_capacity(n);
    for (v, (jj, ww)) in j.chunks_exact(4).zip(w.chunks_exact(4)).enumerate() {
        let mut out_j = [bones[0]; 4];
        let mut out_w = [0.0f32; 4];
        for k in 0..4 {
            let wk = if ww[k].is_finite() {
                ww[k].max(0.0)
            } else {
                0.0
            };
            if wk == 0.0 {
                continue;
            }
            let ji = jj[k];
            if !(ji >= 0.0 && (ji as usize) < bones.len()) {
                return Err(fail(format!(
                    "JOINTS_0: vertex {v} uses joint {ji}, the skin has {} joints",
                    bones.len()
                )));
            }
            out_j[k] = bones[ji as usize];
            out_w[k] = wk;
        }
        let sum: f32 = out_w.iter().sum();
        if sum > 0.0 && sum.is_finite() {
            out_w.iter_mut().for_each(|x| *x /= sum);
        } else {
            out_w = [1.0, 0.0, 0.0, 0.0];
        }
        js.push(out_j);
        ws.push(out_w);
    }
    Ok((js, ws))
}

/// A primitive's triangles (its indices, or consecutive vertices without them), every index
/// below the vertex count `n`.
fn read_triangles(
    prim: &gltf::Primitive,
    n: usize,
    loaded: &Loaded,
    fail: &dyn Fn(String) -> MotionError,
) -> Result<Vec<[u32; 3]>, MotionError> {
    Ok(match prim.indices() {
        Some(acc) => {
            let (idx, _) =
                read_accessor(&acc, loaded).map_err(|e| fail(format!("indices: {e}")))?;
            if let Some(k) = idx.iter().position(|&i| !(i >= 0.0 && (i as usize) < n)) {
                return Err(fail(format!(
                    "indices: index {k} is {}, the primitive has {n} vertices",
                    idx[k]
                )));
            }
            idx.chunks_exact(3)
                .map(|t| [t[0] as u32, t[1] as u32, t[2] as u32])
                .collect()
        }
        None => (0..n as u32 / 3)
            .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
            .collect(),
    })
}

/// Area-weighted vertex normals of a triangle list (for primitives without NORMAL).
fn face_normals(positions: &[Vec3], tris: &[[u32; 3]]) -> Vec<Vec3> {
    let mut acc = vec![Vec3::ZERO; positions.len()];
    for t in tris {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        let n = (b - a).cross(c - a);
        for &i in t {
            acc[i as usize] += n;
        }
    }
    acc.into_iter().map(|n| n.normalize_or(Vec3::Y)).collect()
}
