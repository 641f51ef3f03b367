//! Copies of a glTF binary rig in other units and axes, made the way exporters make them, so
//! tests can check that wisp gives the same hair whatever convention a file was written in.
//!
//! Every copy re-expresses the whole file in a frame `M` (a uniform scale `s` and a rotation
//! `R`): node translations become `M·t`, rotations `R·q·R⁻¹` (also every keyframe), vertex
//! positions `M·p`, normals `R·n`, inverse bind matrices `M·B·M⁻¹`. Then either a new root
//! node carries `M⁻¹`, so the file's world is the original's (a Mixamo rig in centimetres under
//! a 0.01 scale node: `M` = ×100; a Z-up export with its −90° correcting root: `M` = +90° about
//! X), or no root is added and the model stands in the file's world as `M` put it (a Z-up file
//! without the correction, a rig in centimetres without the scale node).
//!
//! It edits only what the rigs made by `examples/make_dance` hold: tightly packed f32
//! accessors, one buffer in the GLB's BIN chunk, TRS nodes.

use glam::{Mat4, Quat, Vec3};
use serde_json::{Value, json};

/// How a copy is expressed.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    /// Uniform scale of the data (100 for centimetres).
    pub scale: f32,
    /// Rotation of the data (+90° about X turns a Y-up model Z-up).
    pub rotation: Quat,
    /// Add a root node that undoes the frame, so the world is unchanged.
    pub correcting_root: bool,
    /// Drop every node name (joints known by index only).
    pub unnamed: bool,
}

impl Frame {
    /// A Mixamo-like rig: centimetres under a 0.01 scale node.
    pub const CM_UNDER_SCALE_NODE: Frame = Frame {
        scale: 100.0,
        rotation: Quat::IDENTITY,
        correcting_root: true,
        unnamed: false,
    };

    /// A Z-up export whose root rotates it back to Y-up (as Blender's and 3ds Max's do).
    pub fn z_up_corrected() -> Frame {
        Frame {
            scale: 1.0,
            rotation: Quat::from_rotation_x(std::f32::consts::FRAC_PI_2),
            correcting_root: true,
            unnamed: false,
        }
    }

    /// A Z-up file with no correction: the model stands along +Z of the glTF world.
    pub fn z_up_raw() -> Frame {
        Frame {
            correcting_root: false,
            ..Frame::z_up_corrected()
        }
    }

    fn matrix(&self) -> Mat4 {
        Mat4::from_scale_rotation_translation(Vec3::splat(self.scale), self.rotation, Vec3::ZERO)
    }
}

/// The GLB `glb` re-expressed in `frame` (see the module doc).
pub fn re_expressed(glb: &[u8], frame: Frame) -> Vec<u8> {
    let (mut doc, mut bin) = split_glb(glb);
    let m = frame.matrix();
    let r = frame.rotation;
    for node in doc["nodes"].as_array_mut().expect("nodes") {
        if let Some(t) = node.get("translation") {
            let t = m.transform_point3(vec3(t));
            node["translation"] = json!(t.to_array());
        }
        if let Some(q) = node.get("rotation") {
            let q = r * quat(q) * r.inverse();
            node["rotation"] = json!(q.to_array());
        }
        if frame.unnamed {
            node.as_object_mut().expect("node").remove("name");
        }
    }
    let accessors = doc["accessors"].clone();
    let views = doc["bufferViews"].clone();
    let mut edit = |index: &Value, f: &dyn Fn(&mut [f32])| {
        let acc = &accessors[index.as_u64().expect("accessor") as usize];
        let view = &views[acc["bufferView"].as_u64().expect("view") as usize];
        let start = view["byteOffset"].as_u64().unwrap_or(0) as usize
            + acc["byteOffset"].as_u64().unwrap_or(0) as usize;
        let comps = match acc["type"].as_str().expect("type") {
            "SCALAR" => 1,
            "VEC3" => 3,
            "VEC4" => 4,
            "MAT4" => 16,
            other => panic!("unexpected accessor type {other}"),
        };
        let n = acc["count"].as_u64().expect("count") as usize * comps;
        let bytes = &mut bin[start..start + 4 * n];
        let mut values: Vec<f32> = bytes
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes(b.try_into().expect("4 bytes")))
            .collect();
        for chunk in values.chunks_exact_mut(comps) {
            f(chunk);
        }
        for (b, v) in bytes.chunks_exact_mut(4).zip(values) {
            b.copy_from_slice(&v.to_le_bytes());
        }
    };
    // Primitives share vertex accessors: each is edited once.
    let mut positions = std::collections::BTreeSet::new();
    let mut normals = std::collections::BTreeSet::new();
    for mesh in doc["meshes"].as_array().into_iter().flatten() {
        for prim in mesh["primitives"].as_array().expect("primitives") {
            let attrs = &prim["attributes"];
            if let Some(p) = attrs.get("POSITION") {
                positions.insert(p.as_u64().expect("index") as usize);
            }
            if let Some(n) = attrs.get("NORMAL") {
                normals.insert(n.as_u64().expect("index") as usize);
            }
        }
    }
    for &p in &positions {
        edit(&json!(p), &|v| {
            set3(v, m.transform_point3(Vec3::from_slice(v)))
        });
    }
    for &n in &normals {
        edit(&json!(n), &|v| set3(v, r * Vec3::from_slice(v)));
    }
    let inverse = m.inverse();
    for skin in doc["skins"].as_array().into_iter().flatten() {
        if let Some(b) = skin.get("inverseBindMatrices") {
            edit(b, &|v| {
                let b = m * Mat4::from_cols_slice(v) * inverse;
                v.copy_from_slice(&b.to_cols_array());
            });
        }
    }
    for anim in doc["animations"].as_array().into_iter().flatten() {
        for ch in anim["channels"].as_array().expect("channels") {
            let sampler = &anim["samplers"][ch["sampler"].as_u64().expect("sampler") as usize];
            match ch["target"]["path"].as_str().expect("path") {
                "translation" => edit(&sampler["output"], &|v| {
                    // Keys and cubic tangents alike are vectors in the parent's frame.
                    set3(v, m.transform_vector3(Vec3::from_slice(v)));
                }),
                "rotation" => edit(&sampler["output"], &|v| {
                    let q = r * Quat::from_slice(v) * r.inverse();
                    v.copy_from_slice(&q.to_array());
                }),
                _ => {}
            }
        }
    }
    for p in positions {
        bounds_from_data(&mut doc, &bin, p);
    }
    if frame.correcting_root {
        add_root(&mut doc, frame);
    }
    join_glb(&doc, &bin)
}

/// Puts every scene's root nodes under a new node that undoes `frame`.
fn add_root(doc: &mut Value, frame: Frame) {
    let nodes = doc["nodes"].as_array_mut().expect("nodes");
    let root = nodes.len();
    let inv_scale = 1.0 / frame.scale;
    let mut node = json!({
        "scale": [inv_scale, inv_scale, inv_scale],
        "rotation": frame.rotation.inverse().to_array(),
    });
    if !frame.unnamed {
        node["name"] = json!("Armature");
    }
    let mut children = Vec::new();
    for scene in doc["scenes"].as_array_mut().expect("scenes") {
        children.extend(scene["nodes"].as_array().expect("roots").iter().cloned());
        scene["nodes"] = json!([root]);
    }
    node["children"] = json!(children);
    doc["nodes"].as_array_mut().expect("nodes").push(node);
}

/// Recomputes a POSITION accessor's `min`/`max` from its data (glTF requires them).
fn bounds_from_data(doc: &mut Value, bin: &[u8], accessor: usize) {
    let acc = &doc["accessors"][accessor];
    let view = &doc["bufferViews"][acc["bufferView"].as_u64().expect("view") as usize];
    let start = view["byteOffset"].as_u64().unwrap_or(0) as usize
        + acc["byteOffset"].as_u64().unwrap_or(0) as usize;
    let n = acc["count"].as_u64().expect("count") as usize;
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for p in bin[start..start + 12 * n].chunks_exact(12) {
        let f = |k: usize| f32::from_le_bytes(p[4 * k..4 * k + 4].try_into().expect("4"));
        let v = Vec3::new(f(0), f(1), f(2));
        lo = lo.min(v);
        hi = hi.max(v);
    }
    doc["accessors"][accessor]["min"] = json!(lo.to_array());
    doc["accessors"][accessor]["max"] = json!(hi.to_array());
}

fn set3(v: &mut [f32], p: Vec3) {
    v.copy_from_slice(&p.to_array());
}

fn vec3(v: &Value) -> Vec3 {
    let f = |k: usize| v[k].as_f64().expect("number") as f32;
    Vec3::new(f(0), f(1), f(2))
}

fn quat(v: &Value) -> Quat {
    let f = |k: usize| v[k].as_f64().expect("number") as f32;
    Quat::from_xyzw(f(0), f(1), f(2), f(3))
}

/// The JSON document and BIN chunk of a GLB.
fn split_glb(glb: &[u8]) -> (Value, Vec<u8>) {
    let u32_at = |i: usize| u32::from_le_bytes(glb[i..i + 4].try_into().expect("4 bytes")) as usize;
    assert_eq!(&glb[..4], b"glTF", "a GLB");
    let json_len = u32_at(12);
    let doc = serde_json::from_slice(&glb[20..20 + json_len]).expect("GLB JSON");
    let bin_at = 20 + json_len;
    let bin_len = u32_at(bin_at);
    (doc, glb[bin_at + 8..bin_at + 8 + bin_len].to_vec())
}

/// A GLB of `doc` and `bin` (JSON padded with spaces, BIN with zeros).
pub fn join_glb(doc: &Value, bin: &[u8]) -> Vec<u8> {
    let mut json = doc.to_string().into_bytes();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let mut bin = bin.to_vec();
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    for v in [2, total as u32, json.len() as u32, 0x4E4F_534A] {
        out.extend_from_slice(&u32::to_le_bytes(v));
    }
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(&0x004E_4942u32.to_le_bytes());
    out.extend_from_slice(&bin);
    out
}

/// The GLB `glb` with the rest rotations of the named nodes replaced (a T-pose rest for a
/// rig whose clip animates those nodes: the motion is the same, only the pose the loader
/// measures the character in changes).
pub fn with_rest_rotations(glb: &[u8], rotations: &[(&str, Quat)]) -> Vec<u8> {
    let (mut doc, bin) = split_glb(glb);
    for node in doc["nodes"].as_array_mut().expect("nodes") {
        let name = node.get("name").and_then(Value::as_str).map(str::to_string);
        if let Some((_, q)) = rotations.iter().find(|(n, _)| Some(*n) == name.as_deref()) {
            node["rotation"] = json!(q.to_array());
        }
    }
    join_glb(&doc, &bin)
}
