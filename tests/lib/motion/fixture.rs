//! Shared helpers of the motion tests: a tiny glTF writer (serde_json + `data:` base64 buffer)
//! and geometric assertions.

use std::path::PathBuf;

use glam::{Affine3A, Quat};
use serde_json::{Value, json};
use wisp::motion::{Fit, Motion, MotionError, MotionOptions};

/// A glTF under construction: nodes, one clip, f32 data in one buffer.
#[derive(Default)]
pub struct Fx {
    pub nodes: Vec<Value>,
    pub bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
    samplers: Vec<Value>,
    channels: Vec<Value>,
}

pub fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in bytes.chunks(3) {
        let n = (c[0] as u32) << 16
            | (*c.get(1).unwrap_or(&0) as u32) << 8
            | *c.get(2).unwrap_or(&0) as u32;
        for k in 0..4 {
            if k <= c.len() {
                s.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

impl Fx {
    /// Adds a node; returns its index.
    pub fn node(&mut self, n: Value) -> usize {
        self.nodes.push(n);
        self.nodes.len() - 1
    }

    pub fn accessor(&mut self, data: &[f32], kind: &str) -> usize {
        let comps = match kind {
            "SCALAR" => 1,
            "VEC3" => 3,
            _ => 4,
        };
        let offset = self.bin.len();
        for v in data {
            self.bin.extend_from_slice(&v.to_le_bytes());
        }
        self.views
            .push(json!({"buffer": 0, "byteOffset": offset, "byteLength": data.len() * 4}));
        self.accessors.push(json!({
            "bufferView": self.views.len() - 1, "componentType": 5126,
            "count": data.len() / comps, "type": kind,
        }));
        self.accessors.len() - 1
    }

    pub fn channel(
        &mut self,
        node: usize,
        path: &str,
        interp: &str,
        times: &[f32],
        values: &[f32],
    ) {
        let kind = if path == "rotation" { "VEC4" } else { "VEC3" };
        let input = self.accessor(times, "SCALAR");
        let output = self.accessor(values, kind);
        self.samplers
            .push(json!({"input": input, "output": output, "interpolation": interp}));
        self.channels.push(
            json!({"sampler": self.samplers.len() - 1, "target": {"node": node, "path": path}}),
        );
    }

    /// The glTF JSON; `clips` names the copies of the clip (none = no animations).
    pub fn json(&self, clips: &[&str]) -> Value {
        let anims: Vec<Value> = clips
            .iter()
            .map(|n| json!({"name": n, "samplers": self.samplers, "channels": self.channels}))
            .collect();
        let mut doc = json!({
            "asset": {"version": "2.0"},
            "scenes": [{"nodes": [0]}],
            "nodes": self.nodes,
            "accessors": self.accessors,
            "bufferViews": self.views,
            "buffers": [{
                "byteLength": self.bin.len(),
                "uri": format!("data:application/octet-stream;base64,{}", base64(&self.bin)),
            }],
        });
        if !anims.is_empty() {
            doc["animations"] = json!(anims);
        }
        doc
    }

    /// The glTF with one clip per `(name, channel)`: each clip holds that channel alone.
    pub fn bytes_one_channel_each(&self, clips: &[(&str, usize)]) -> Vec<u8> {
        let mut doc = self.json(&[]);
        doc["animations"] = clips
            .iter()
            .map(|&(name, k)| {
                let mut channel = self.channels[k].clone();
                channel["sampler"] = json!(0);
                json!({"name": name, "samplers": [self.samplers[k]], "channels": [channel]})
            })
            .collect();
        doc.to_string().into_bytes()
    }

    pub fn bytes(&self, clips: &[&str]) -> Vec<u8> {
        self.json(clips).to_string().into_bytes()
    }
}

pub fn load(bytes: &[u8], opts: &MotionOptions) -> Result<Motion, MotionError> {
    Motion::from_glb_bytes(bytes, "fixture.gltf", opts)
}

pub fn fixed_fit() -> MotionOptions {
    MotionOptions {
        fit: Some(Fit::IDENTITY),
        body_spheres: Some(vec![]),
        ..Default::default()
    }
}

/// A single "Head" node with one animated property.
pub fn one_channel(path: &str, interp: &str, times: &[f32], values: &[f32]) -> Vec<u8> {
    let mut fx = Fx::default();
    let head = fx.node(json!({"name": "Head"}));
    fx.channel(head, path, interp, times, values);
    fx.bytes(&["Dance"])
}

pub fn angle_between(a: &Affine3A, b: &Affine3A) -> f32 {
    let qa = Quat::from_mat3a(&a.matrix3);
    let qb = Quat::from_mat3a(&b.matrix3);
    qa.angle_between(qb)
}

pub fn temp_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("wisp-motion-{}-{tag}", std::process::id()));
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

pub fn assert_rigid(h: &Affine3A, what: &str) {
    let m = h.matrix3;
    let mtm = m.transpose() * m;
    let err = (mtm - glam::Mat3A::IDENTITY)
        .to_cols_array()
        .iter()
        .map(|v| v.abs())
        .fold(0.0, f32::max);
    assert!(err < 1e-4, "{what}: MᵀM differs from I by {err}");
    assert!(
        (m.determinant() - 1.0).abs() < 1e-4,
        "{what}: det {}",
        m.determinant()
    );
}
