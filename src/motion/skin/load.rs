//! Reading a glTF file's meshes into a [`Character`]: its bones (a skin's joints, or the node
//! of a rigid mesh), its materials and textures, and every triangle primitive (read by
//! [`super::primitive`]).
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
//! Bones, materials and textures are made once, on first use, however many nodes and
//! primitives refer to them; primitives that share their vertex accessors and bones (one per
//! material, as exporters split a mesh) share their vertices too ([`VertexKey`]).
//!
//! [`MAX_VERTICES`]: super::MAX_VERTICES
//! [`MAX_TRIANGLES`]: super::MAX_TRIANGLES

use std::collections::BTreeMap;

use glam::{Affine3A, Mat4, Vec3};
use gltf::Semantic;

use super::primitive::{PrimitiveInput, read_primitive};
use super::{Bone, Character, Material, blend};
use crate::motion::error::{MotionError, invalid};
use crate::motion::gltf_io::{Loaded, read_accessor};
use crate::motion::skeleton::Skeleton;
use crate::motion::texture;

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
    let mut b = Builder::new(loaded, skel, in_head, file, slot_of);
    for node in loaded.doc.nodes() {
        let Some(mesh) = node.mesh() else { continue };
        let bones = b.bones_of(&node)?;
        if bones.is_empty() {
            continue;
        }
        for prim in mesh.primitives() {
            b.add_primitive(&node, &mesh, &prim, &bones)?;
        }
    }
    b.finish(skel)
}

/// What makes two primitives' vertices the same: the bones they follow (a skin, or a rigid
/// node) and their attribute accessors.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
struct VertexKey {
    bones: (bool, usize),
    accessors: [Option<usize>; 5],
}

/// A character being read, with what has been made of the file so far.
struct Builder<'a> {
    loaded: &'a Loaded,
    file: &'a str,
    in_head: &'a [bool],
    slot_of: &'a mut dyn FnMut(usize) -> usize,
    ch: Character,
    /// Bones of each skin's joints, once made.
    skin_bones: Vec<Option<Vec<u16>>>,
    /// Bone of each rigid mesh node, once made.
    node_bone: Vec<Option<u16>>,
    /// Index in `ch.materials` of each glTF material, once read.
    material_of: Vec<Option<u16>>,
    /// The material of primitives without one (white, one-sided), once made.
    default_material: Option<u16>,
    textures: texture::Cache,
    /// Where the vertices of each vertex set are (first index, count).
    vertex_sets: BTreeMap<VertexKey, (u32, usize)>,
}

impl<'a> Builder<'a> {
    fn new(
        loaded: &'a Loaded,
        skel: &Skeleton,
        in_head: &'a [bool],
        file: &'a str,
        slot_of: &'a mut dyn FnMut(usize) -> usize,
    ) -> Self {
        let doc = &loaded.doc;
        Self {
            loaded,
            file,
            in_head,
            slot_of,
            ch: Character {
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
                unread_textures: 0,
            },
            skin_bones: vec![None; doc.skins().len()],
            node_bone: vec![None; skel.names.len()],
            material_of: vec![None; doc.materials().len()],
            default_material: None,
            textures: texture::Cache::new(doc.textures().len()),
            vertex_sets: BTreeMap::new(),
        }
    }

    /// A new bone following glTF node `node` with bind matrix `bind`.
    fn new_bone(&mut self, node: usize, bind: Affine3A) -> Result<u16, MotionError> {
        if self.ch.bones.len() >= u16::MAX as usize {
            return Err(invalid(self.file, "the meshes use more than 65535 bones"));
        }
        self.ch.bones.push(Bone {
            slot: (self.slot_of)(node),
            node,
            bind,
        });
        self.ch.bone_in_head.push(self.in_head[node]);
        Ok((self.ch.bones.len() - 1) as u16)
    }

    /// The bones a mesh node's vertices refer to: its skin's joints, or the node itself.
    fn bones_of(&mut self, node: &gltf::Node) -> Result<Vec<u16>, MotionError> {
        Ok(match node.skin() {
            Some(skin) => {
                if self.skin_bones[skin.index()].is_none() {
                    let joints: Vec<usize> = skin.joints().map(|j| j.index()).collect();
                    let ibm = inverse_binds(&skin, joints.len(), self.loaded, self.file)?;
                    let mut list = Vec::with_capacity(joints.len());
                    for (j, b) in joints.iter().zip(ibm) {
                        list.push(self.new_bone(*j, b)?);
                    }
                    self.skin_bones[skin.index()] = Some(list);
                }
                self.skin_bones[skin.index()].clone().unwrap_or_default()
            }
            None => {
                let b = match self.node_bone[node.index()] {
                    Some(b) => b,
                    None => {
                        let b = self.new_bone(node.index(), Affine3A::IDENTITY)?;
                        self.node_bone[node.index()] = Some(b);
                        b
                    }
                };
                vec![b]
            }
        })
    }

    /// Appends primitive `prim` of `mesh` on `node`, whose vertices follow `bones`; a
    /// primitive that is not TRIANGLES is counted and skipped.
    fn add_primitive(
        &mut self,
        node: &gltf::Node,
        mesh: &gltf::Mesh,
        prim: &gltf::Primitive,
        bones: &[u16],
    ) -> Result<(), MotionError> {
        let at = format!("meshes[{}].primitives[{}]", mesh.index(), prim.index());
        if prim.mode() != gltf::mesh::Mode::Triangles {
            self.ch.skipped_primitives += 1;
            return Ok(());
        }
        let material = self.material(prim)?;
        let uv_set = self.ch.materials[material as usize]
            .texture
            .and_then(|t| self.textures.tex_coord(t));
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
        let input = PrimitiveInput {
            prim,
            bones,
            skinned: node.skin().is_some(),
            material,
            uv_set,
            shared: self.vertex_sets.get(&key).copied(),
            at: &at,
        };
        let base = read_primitive(&mut self.ch, &input, self.loaded, self.file)?;
        self.vertex_sets.entry(key).or_insert(base);
        Ok(())
    }

    /// The index of `prim`'s material in `ch.materials`, read on first use (a primitive
    /// without one gets a white one-sided material).
    fn material(&mut self, prim: &gltf::Primitive) -> Result<u16, MotionError> {
        Ok(match prim.material().index() {
            Some(i) => match self.material_of[i] {
                Some(m) => m,
                None => {
                    let m = self.read_material(&prim.material())?;
                    self.material_of[i] = Some(m);
                    m
                }
            },
            None => *self.default_material.get_or_insert_with(|| {
                self.ch.materials.push(Material {
                    base_color: Vec3::ONE,
                    texture: None,
                    double_sided: false,
                });
                (self.ch.materials.len() - 1) as u16
            }),
        })
    }

    /// Appends material `m`: its base colour factor (clamped to [0, 1], white when not
    /// finite), its base colour texture (decoded once) and its sidedness.
    fn read_material(&mut self, m: &gltf::Material) -> Result<u16, MotionError> {
        let pbr = m.pbr_metallic_roughness();
        let f = pbr.base_color_factor();
        let base = Vec3::new(f[0], f[1], f[2]);
        let base_color = if base.is_finite() {
            base.clamp(Vec3::ZERO, Vec3::ONE)
        } else {
            Vec3::ONE
        };
        let texture = match pbr.base_color_texture() {
            Some(info) => self.textures.load(&info, self.loaded, self.file)?,
            None => None,
        };
        if self.ch.materials.len() >= u16::MAX as usize {
            return Err(invalid(self.file, "more than 65535 materials"));
        }
        self.ch.materials.push(Material {
            base_color,
            texture,
            double_sided: m.double_sided(),
        });
        Ok((self.ch.materials.len() - 1) as u16)
    }

    /// The character with its textures and its rest pose in model metres (`None` without
    /// triangles); a vertex that is not finite at rest is refused.
    fn finish(self, skel: &Skeleton) -> Result<Option<Character>, MotionError> {
        let mut ch = self.ch;
        if ch.triangles.is_empty() {
            return Ok(None);
        }
        ch.unread_textures = self.textures.unsupported;
        ch.textures = self.textures.into_textures();
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
                self.file,
                format!(
                    "the meshes' vertex {v} is not finite in the rest pose (a joint's rest transform or inverse bind matrix is degenerate)"
                ),
            ));
        }
        Ok(Some(ch))
    }
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
