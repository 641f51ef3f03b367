//! Skinned characters: the glTF's meshes posed by the clip every frame (glTF 2.0 §3.7.3
//! "Skins": linear blend skinning).
//!
//! # What
//! [`Character`] holds every triangle primitive of the file's meshes in bind space, with up to
//! four bone influences per vertex, and the base colour of its material (factor and, when the
//! material has one, a PNG texture). [`super::Motion::pose_character`] evaluates the clip's node
//! hierarchy once per frame (parent-first, each node once) and skins every vertex:
//!
//! `p = Σₖ wₖ · (Jₖ · IBMₖ) · v / Σₖ wₖ`, the normal by the cofactor of the blended matrix
//! (its inverse transpose up to a positive factor, so non-uniform node scales keep normals
//! perpendicular),
//!
//! with `Jₖ` the world matrix of joint k at the frame's time and `IBMₖ` its inverse bind
//! matrix. Weights are divided by their sum (real files have sums of 0.98–1.02). A mesh on a
//! node without a skin is rigid: one bone, the node itself, with an identity bind matrix
//! (RobotExpressive is built that way: 12 rigid parts and two skinned hands). Positions end in
//! the pose world (model metres divided by the fit's scale, as every other pose quantity).
//!
//! # Rules (a broken file is refused with the mesh, primitive and rule)
//! Only TRIANGLES primitives are drawn (points and lines are skipped and counted); positions must
//! be finite; indices must be below the primitive's vertex count; joint indices below the
//! skin's joint count; an inverse-bind-matrix accessor must hold one finite matrix per joint.
//! Missing normals are computed (area-weighted face normals); missing weights on a skinned
//! primitive make it follow the skin's first joint. At most [`MAX_VERTICES`] vertices and
//! [`MAX_TRIANGLES`] triangles are kept per file (the decode budget of the load bounds them
//! first). Morph targets are ignored (RobotExpressive's face weights are animated; its posed
//! shape is the base mesh).
//!
//! # Why this design
//! Skinning per vertex with a blended matrix costs about 50 flops; a few thousand vertices take
//! well under a millisecond. The node evaluation walks each node once per frame (the head and
//! collider chains walk theirs on their own, as they are also sampled at the simulation's
//! 240 Hz, where the mesh is not needed).

use glam::{Affine3A, Mat3A, Mat4, Vec2, Vec3, Vec3A};
use gltf::Semantic;
use rayon::prelude::*;

use super::MotionError;
use super::gltf_io::{Loaded, invalid, read_accessor};
use super::skeleton::Skeleton;
use super::texture::{self, Texture};

/// Most vertices a character may have.
pub const MAX_VERTICES: usize = 1 << 20;
/// Most triangles a character may have.
pub const MAX_TRIANGLES: usize = 2 << 20;

/// A bone: the evaluated node it follows and its bind matrix (the inverse bind matrix of a skin
/// joint, identity for a rigid mesh's node).
#[derive(Clone, Debug)]
pub(crate) struct Bone {
    /// Index into `Motion::nodes`.
    pub(crate) slot: usize,
    /// glTF node index (for messages and the head test).
    pub(crate) node: usize,
    pub(crate) bind: Affine3A,
}

/// A material's base colour.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Linear RGB base colour factor (glTF `baseColorFactor`, alpha dropped).
    pub base_color: Vec3,
    /// Index into [`Character::textures`] of the base colour texture, if any.
    pub texture: Option<usize>,
    /// Both faces are drawn (glTF `doubleSided`); otherwise back faces are culled.
    pub double_sided: bool,
}

/// The character's meshes in bind space (see the module doc).
#[derive(Clone, Debug)]
pub struct Character {
    pub(crate) bones: Vec<Bone>,
    /// Bone is in the head joint's subtree (the head is the hairstyle's ellipsoid's job).
    pub(crate) bone_in_head: Vec<bool>,
    pub(crate) bind_pos: Vec<Vec3>,
    pub(crate) bind_nrm: Vec<Vec3>,
    /// Bone indices (into `bones`) of each vertex's four influences.
    pub(crate) joints: Vec<[u16; 4]>,
    /// Weights of the influences, summing to 1.
    pub(crate) weights: Vec<[f32; 4]>,
    /// Texture coordinates (0, 0 without a TEXCOORD_0).
    pub uv: Vec<Vec2>,
    /// Material of each triangle.
    pub triangle_material: Vec<u16>,
    /// Triangles (vertex indices, counter-clockwise front faces).
    pub triangles: Vec<[u32; 3]>,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    /// Rest-pose positions in model metres (the bind pose posed by the nodes' rest transforms).
    pub(crate) rest_model: Vec<Vec3>,
    /// Primitives skipped because they are not triangles.
    pub skipped_primitives: usize,
}

/// A posed character (reused every frame): positions and unit normals in the pose world.
#[derive(Clone, Debug, Default)]
pub struct CharacterPose {
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    /// Scratch: world matrix of every evaluated node, then each bone's skinning matrix.
    pub(crate) node_worlds: Vec<Affine3A>,
    pub(crate) bone_mats: Vec<Affine3A>,
}

impl Character {
    /// Vertices.
    pub fn vertex_count(&self) -> usize {
        self.bind_pos.len()
    }

    /// Whether vertex `v`'s strongest influence is a bone of the head (the head joint or below).
    pub fn is_head_vertex(&self, v: usize) -> bool {
        let k = dominant(&self.weights[v]);
        self.bone_in_head[self.joints[v][k] as usize]
    }

    /// Whether any vertex belongs to the head.
    pub fn has_head(&self) -> bool {
        (0..self.vertex_count()).any(|v| self.is_head_vertex(v))
    }

    /// Heap bytes held.
    pub fn held_bytes(&self) -> u64 {
        let per_vertex = 2 * size_of::<Vec3>()
            + size_of::<[u16; 4]>()
            + size_of::<[f32; 4]>()
            + size_of::<Vec2>()
            + size_of::<Vec3>();
        (self.bind_pos.len() * per_vertex
            + self.triangles.len() * (size_of::<[u32; 3]>() + size_of::<u16>())
            + self.bones.len() * size_of::<Bone>()) as u64
            + self.textures.iter().map(Texture::held_bytes).sum::<u64>()
    }

    /// Bytes a [`CharacterPose`] of this character holds (positions, normals, matrices).
    pub fn pose_bytes(&self, nodes: usize) -> u64 {
        (2 * self.bind_pos.len() * size_of::<Vec3>()
            + (nodes + self.bones.len()) * size_of::<Affine3A>()) as u64
    }

    /// Skins every vertex with the bone matrices in `pose.bone_mats` (pose world).
    pub(crate) fn skin(&self, pose: &mut CharacterPose) {
        const CHUNK: usize = 2048;
        let n = self.bind_pos.len();
        pose.positions.resize(n, Vec3::ZERO);
        pose.normals.resize(n, Vec3::Y);
        let mats = &pose.bone_mats;
        pose.positions
            .par_chunks_mut(CHUNK)
            .zip(pose.normals.par_chunks_mut(CHUNK))
            .enumerate()
            .for_each(|(c, (pos, nrm))| {
                for (k, (p, nn)) in pos.iter_mut().zip(nrm.iter_mut()).enumerate() {
                    let v = c * CHUNK + k;
                    let m = blend(mats, &self.joints[v], &self.weights[v]);
                    *p = m.transform_point3(self.bind_pos[v]);
                    *nn = normal_map(&m.matrix3, self.bind_nrm[v]);
                }
            });
    }
}

/// The blended matrix Σ wₖ Mₖ (weights sum to 1).
#[inline]
fn blend(mats: &[Affine3A], j: &[u16; 4], w: &[f32; 4]) -> Affine3A {
    let mut m = Affine3A {
        matrix3: Mat3A::ZERO,
        translation: Vec3A::ZERO,
    };
    for k in 0..4 {
        if w[k] != 0.0 {
            let b = &mats[j[k] as usize];
            m.matrix3 += b.matrix3 * w[k];
            m.translation += b.translation * w[k];
        }
    }
    m
}

/// Unit normal under the linear map `m`: its cofactor matrix (det · m⁻ᵀ, columns c1×c2,
/// c2×c0, c0×c1) with the sign of the determinant, so mirrored nodes keep outward normals.
#[inline]
fn normal_map(m: &Mat3A, n: Vec3) -> Vec3 {
    let (c0, c1, c2) = (m.x_axis, m.y_axis, m.z_axis);
    let cof = Mat3A::from_cols(c1.cross(c2), c2.cross(c0), c0.cross(c1));
    let sign = if c0.dot(c1.cross(c2)) < 0.0 {
        -1.0
    } else {
        1.0
    };
    Vec3::from(cof * Vec3A::from(n) * sign).normalize_or(Vec3::Y)
}

/// Index of the largest of four weights (the first on ties).
#[inline]
pub(crate) fn dominant(w: &[f32; 4]) -> usize {
    let mut k = 0;
    for i in 1..4 {
        if w[i] > w[k] {
            k = i;
        }
    }
    k
}

/// Reads every triangle primitive of the file (see the module doc). `slot_of(node)` makes the
/// node evaluated every frame and returns its index in `Motion::nodes`; `in_head` marks the
/// head joint's subtree. `None` when the file has no mesh.
pub(crate) fn load_character(
    loaded: &Loaded,
    skel: &Skeleton,
    in_head: &[bool],
    file: &str,
    slot_of: &mut dyn FnMut(usize) -> usize,
) -> Result<Option<Character>, MotionError> {
    let doc = &loaded.doc;
    let mut ch = Character {
        bones: Vec::new(),
        bone_in_head: Vec::new(),
        bind_pos: Vec::new(),
        bind_nrm: Vec::new(),
        joints: Vec::new(),
        weights: Vec::new(),
        uv: Vec::new(),
        triangle_material: Vec::new(),
        triangles: Vec::new(),
        materials: Vec::new(),
        textures: Vec::new(),
        rest_model: Vec::new(),
        skipped_primitives: 0,
    };
    // Bone of (skin, joint slot) or of a rigid node, created on first use.
    let mut skin_bones: Vec<Option<Vec<u16>>> = vec![None; doc.skins().len()];
    let mut node_bone: Vec<Option<u16>> = vec![None; skel.names.len()];
    let mut material_of: Vec<Option<u16>> = vec![None; doc.materials().len()];
    let mut default_material: Option<u16> = None;
    let mut textures = texture::Cache::new(doc.textures().len());
    let mut vertex_sets: std::collections::BTreeMap<VertexKey, (u32, usize)> =
        std::collections::BTreeMap::new();
    let mut new_bone =
        |ch: &mut Character, node: usize, bind: Affine3A| -> Result<u16, MotionError> {
            if ch.bones.len() >= u16::MAX as usize {
                return Err(invalid(file, "the meshes use more than 65535 bones"));
            }
            ch.bones.push(Bone {
                slot: slot_of(node),
                node,
                bind,
            });
            ch.bone_in_head.push(in_head[node]);
            Ok((ch.bones.len() - 1) as u16)
        };
    for node in doc.nodes() {
        let Some(mesh) = node.mesh() else { continue };
        // The bones this node's vertices refer to: the skin's joints, or the node itself.
        let bones: Vec<u16> = match node.skin() {
            Some(skin) => {
                if skin_bones[skin.index()].is_none() {
                    let joints: Vec<usize> = skin.joints().map(|j| j.index()).collect();
                    let ibm = inverse_binds(&skin, joints.len(), loaded, file)?;
                    let mut list = Vec::with_capacity(joints.len());
                    for (j, b) in joints.iter().zip(ibm) {
                        list.push(new_bone(&mut ch, *j, b)?);
                    }
                    skin_bones[skin.index()] = Some(list);
                }
                skin_bones[skin.index()].clone().unwrap_or_default()
            }
            None => {
                let b = match node_bone[node.index()] {
                    Some(b) => b,
                    None => {
                        let b = new_bone(&mut ch, node.index(), Affine3A::IDENTITY)?;
                        node_bone[node.index()] = Some(b);
                        b
                    }
                };
                vec![b]
            }
        };
        if bones.is_empty() {
            continue;
        }
        for prim in mesh.primitives() {
            let at = format!("meshes[{}].primitives[{}]", mesh.index(), prim.index());
            if prim.mode() != gltf::mesh::Mode::Triangles {
                ch.skipped_primitives += 1;
                continue;
            }
            let material = match prim.material().index() {
                Some(i) => match material_of[i] {
                    Some(m) => m,
                    None => {
                        let m =
                            read_material(&mut ch, &prim.material(), &mut textures, loaded, file)?;
                        material_of[i] = Some(m);
                        m
                    }
                },
                None => *default_material.get_or_insert_with(|| {
                    ch.materials.push(Material {
                        base_color: Vec3::ONE,
                        texture: None,
                        double_sided: false,
                    });
                    (ch.materials.len() - 1) as u16
                }),
            };
            let uv_set = ch.materials[material as usize]
                .texture
                .and_then(|t| textures.tex_coord(t));
            // Primitives that share their vertex accessors (one per material, as exporters
            // split a mesh) and their bones share their vertices too.
            let acc = |s: Semantic| prim.get(&s).map(|a| a.index());
            let key = VertexKey {
                bones: node
                    .skin()
                    .map_or((false, node.index()), |k| (true, k.index())),
                accessors: [
                    acc(Semantic::Positions),
                    acc(Semantic::Normals),
                    acc(Semantic::Joints(0)),
                    acc(Semantic::Weights(0)),
                    uv_set.and_then(|u| acc(Semantic::TexCoords(u))),
                ],
            };
            let shared = vertex_sets.get(&key).copied();
            let base = read_primitive(
                &mut ch,
                &prim,
                &bones,
                node.skin().is_some(),
                material,
                uv_set,
                shared,
                loaded,
                file,
                &at,
            )?;
            vertex_sets.entry(key).or_insert(base);
        }
    }
    if ch.triangles.is_empty() {
        return Ok(None);
    }
    ch.textures = textures.into_textures();
    // Rest pose in model metres.
    let rest: Vec<Affine3A> = ch
        .bones
        .iter()
        .map(|b| skel.rest_world(b.node) * b.bind)
        .collect();
    ch.rest_model = (0..ch.bind_pos.len())
        .map(|v| blend(&rest, &ch.joints[v], &ch.weights[v]).transform_point3(ch.bind_pos[v]))
        .collect();
    if let Some(v) = ch.rest_model.iter().position(|p| !p.is_finite()) {
        return Err(invalid(
            file,
            format!(
                "the meshes' vertex {v} is not finite in the rest pose (a joint's rest transform or inverse bind matrix is degenerate)"
            ),
        ));
    }
    Ok(Some(ch))
}

/// What makes two primitives' vertices the same: the bones they follow (a skin, or a rigid
/// node) and their attribute accessors.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
struct VertexKey {
    bones: (bool, usize),
    accessors: [Option<usize>; 5],
}

/// One finite inverse bind matrix per joint (identity when the skin has none).
fn inverse_binds(
    skin: &gltf::Skin,
    joints: usize,
    loaded: &Loaded,
    file: &str,
) -> Result<Vec<Affine3A>, MotionError> {
    let Some(acc) = skin.inverse_bind_matrices() else {
        return Ok(vec![Affine3A::IDENTITY; joints]);
    };
    let at = format!("skins[{}].inverseBindMatrices", skin.index());
    let (v, comps) =
        read_accessor(&acc, loaded).map_err(|e| invalid(file, format!("{at}: {e}")))?;
    if comps != 16 || v.len() < 16 * joints {
        return Err(invalid(
            file,
            format!(
                "{at}: {} matrices for {joints} joints (one MAT4 per joint is required)",
                v.len() / comps.max(1)
            ),
        ));
    }
    let mats: Vec<Affine3A> = v
        .chunks_exact(16)
        .take(joints)
        .map(|m| Affine3A::from_mat4(Mat4::from_cols_slice(m)))
        .collect();
    if let Some(k) = mats.iter().position(|m| !m.is_finite()) {
        return Err(invalid(file, format!("{at}: matrix {k} is not finite")));
    }
    Ok(mats)
}

fn read_material(
    ch: &mut Character,
    m: &gltf::Material,
    textures: &mut texture::Cache,
    loaded: &Loaded,
    file: &str,
) -> Result<u16, MotionError> {
    let pbr = m.pbr_metallic_roughness();
    let f = pbr.base_color_factor();
    let base = Vec3::new(f[0], f[1], f[2]);
    let base_color = if base.is_finite() {
        base.clamp(Vec3::ZERO, Vec3::ONE)
    } else {
        Vec3::ONE
    };
    let texture = match pbr.base_color_texture() {
        Some(info) => textures.load(&info, loaded, file)?,
        None => None,
    };
    if ch.materials.len() >= u16::MAX as usize {
        return Err(invalid(file, "more than 65535 materials"));
    }
    ch.materials.push(Material {
        base_color,
        texture,
        double_sided: m.double_sided(),
    });
    Ok((ch.materials.len() - 1) as u16)
}

/// Appends one triangle primitive (see the module doc for the rules); its vertices are
/// appended too unless `shared` gives those of an earlier primitive (first index, count).
/// Returns where its vertices are.
#[allow(clippy::too_many_arguments)]
fn read_primitive(
    ch: &mut Character,
    prim: &gltf::Primitive,
    bones: &[u16],
    skinned: bool,
    material: u16,
    uv_set: Option<u32>,
    shared: Option<(u32, usize)>,
    loaded: &Loaded,
    file: &str,
    at: &str,
) -> Result<(u32, usize), MotionError> {
    let fail = |rule: String| invalid(file, format!("{at}: {rule}"));
    if let Some((base, n)) = shared {
        let tris = read_triangles(prim, n, loaded, &fail)?;
        if ch.triangles.len() + tris.len() > MAX_TRIANGLES {
            return Err(fail(format!(
                "the meshes have more than {MAX_TRIANGLES} triangles"
            )));
        }
        ch.triangles
            .extend(tris.iter().map(|t| t.map(|i| i + base)));
        ch.triangle_material
            .extend(std::iter::repeat_n(material, tris.len()));
        return Ok((base, n));
    }
    let read = |s: Semantic| -> Result<Option<(Vec<f32>, usize)>, MotionError> {
        match prim.get(&s) {
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
    let tris = read_triangles(prim, n, loaded, &fail)?;
    if ch.triangles.len() + tris.len() > MAX_TRIANGLES {
        return Err(fail(format!(
            "the meshes have more than {MAX_TRIANGLES} triangles"
        )));
    }
    let normals: Vec<Vec3> = match read(Semantic::Normals)? {
        Some((v, 3)) if v.len() == 3 * n => v
            .chunks_exact(3)
            .map(|c| Vec3::from_slice(c).normalize_or(Vec3::Y))
            .collect(),
        _ => face_normals(&positions, &tris),
    };
    let uvs: Vec<Vec2> = match uv_set.map(|s| read(Semantic::TexCoords(s))).transpose()? {
        Some(Some((v, 2))) if v.len() == 2 * n => v
            .chunks_exact(2)
            .map(|c| {
                let uv = Vec2::new(c[0], c[1]);
                if uv.is_finite() { uv } else { Vec2::ZERO }
            })
            .collect(),
        _ => vec![Vec2::ZERO; n],
    };
    let (joints, weights): (Vec<[u16; 4]>, Vec<[f32; 4]>) = if skinned {
        match (read(Semantic::Joints(0))?, read(Semantic::Weights(0))?) {
            (Some((j, 4)), Some((w, 4))) if j.len() == 4 * n && w.len() == 4 * n => {
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
                (js, ws)
            }
            _ => (vec![[bones[0]; 4]; n], vec![[1.0, 0.0, 0.0, 0.0]; n]),
        }
    } else {
        (vec![[bones[0]; 4]; n], vec![[1.0, 0.0, 0.0, 0.0]; n])
    };
    ch.bind_pos.extend(positions);
    ch.bind_nrm.extend(normals);
    ch.uv.extend(uvs);
    ch.joints.extend(joints);
    ch.weights.extend(weights);
    ch.triangles
        .extend(tris.iter().map(|t| t.map(|i| i + base as u32)));
    ch.triangle_material
        .extend(std::iter::repeat_n(material, tris.len()));
    Ok((base as u32, n))
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
