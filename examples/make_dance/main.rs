//! Authors wisp's own dance motion: a glTF 2.0 binary (`.glb`) with a small human skeleton, a
//! low-poly skinned mannequin on it (`mannequin.rs`), and one 8-second clip named "Dance" that
//! loops seamlessly.
//!
//! ```text
//! cargo run --release --example make_dance -- animations/dance.glb
//! ```
//!
//! # Skeleton (metres, +Y up, facing +Z as glTF prescribes; a 1.75 m adult)
//! `Hips` (1.00 m) → `Spine` → `Chest` (1.27 m) → `Neck` (1.47 m) → `Head` (1.57 m, the skull
//! base) → `HeadTop_End` (1.75 m), and `Shoulder.L` / `Shoulder.R` (±0.18 m, 1.41 m) under
//! `Chest`, each with `UpperArm` → `LowerArm` (elbow, 1.12 m) → `Hand` (wrist, 0.87 m); under
//! `Hips`, `UpperLeg.L` / `.R` (±0.09 m, 0.92 m) → `LowerLeg` (knee, 0.50 m) → `Foot` (ankle,
//! 0.08 m). All are joints of one skin. The mannequin's head mesh makes the automatic fit
//! exactly a 0.09 m head centred 0.09 m above the `Head` joint (as `HeadTop_End` did before the
//! mesh), so hairstyles sit at scale 1.
//!
//! # The clip (120 beats per minute; every move is a smooth function of time)
//! | time (s)  | move |
//! |-----------|------|
//! | 0.0 – 2.0 | groove: hips bob 2.5 cm on the beat, sway ±4 cm side to side, chest and head roll with the sway |
//! | 2.0 – 3.6 | head turns left/right (±0.6 rad) while the neck nods on the beat |
//! | 3.6 – 4.8 | whips: the head snaps to +0.7 rad, then across to −0.7 rad, then back |
//! | 4.8 – 5.2 | one head-bang nod |
//! | 5.0 – 6.3 | a full turn of the body on the spot with a small crouch |
//! | 6.3 – 8.0 | calm: standing still so the hair settles |
//!
//! The arms swing with the groove (±0.25 rad, opposite phases), rise sideways during the whips
//! and the turn (0.5–0.6 rad), and keep a slight elbow bend; the knees bend with the bob and
//! the crouch.
//!
//! Every move is multiplied by an envelope that is 0 with zero slope at its ends, so the pose and
//! its velocity at 8 s equal those at 0 s: the loop is seamless. Channels are LINEAR, sampled at
//! 30 keys per second, except the neck rotation, which is CUBICSPLINE with 4 keys per second and
//! tangents from the analytic derivative (to exercise that sampler on real data).
//!
//! The output is the project's own work (MIT, like the crate). After writing, the example loads
//! the file with `wisp::motion` and prints peak head speeds.

use std::f32::consts::TAU;
use std::path::PathBuf;

mod mannequin;

use glam::{Quat, Vec3};
use serde_json::{Value, json};
use wisp::motion::{Motion, MotionOptions};

const DURATION_S: f32 = 8.0;
const LINEAR_KEYS_PER_S: f32 = 30.0;
const CUBIC_KEYS_PER_S: f32 = 4.0;
const BEAT_HZ: f32 = 2.0;

/// Quintic smoothstep (zero first and second derivatives at both ends), x clamped to [0, 1].
fn smooth(x: f32) -> f32 {
    let x = x.clamp(0.0, 1.0);
    x * x * x * (x * (6.0 * x - 15.0) + 10.0)
}

/// 1 inside [a + ramp, b − ramp], 0 outside [a, b], smooth in between.
fn envelope(t: f32, a: f32, b: f32, ramp: f32) -> f32 {
    smooth((t - a) / ramp) * smooth((b - t) / ramp)
}

/// Piecewise quintic through (time, value) holds: the value moves smoothly between keys.
fn moves(t: f32, keys: &[(f32, f32)]) -> f32 {
    let mut v = keys.first().map_or(0.0, |k| k.1);
    for w in keys.windows(2) {
        let ((t0, v0), (t1, v1)) = (w[0], w[1]);
        if t >= t0 {
            v = v0 + (v1 - v0) * smooth((t - t0) / (t1 - t0));
        }
    }
    v
}

fn hips_translation(t: f32) -> Vec3 {
    let groove = envelope(t, 0.0, 3.8, 0.5);
    let bob = -0.025 * groove * (0.5 - 0.5 * (TAU * BEAT_HZ * t).cos());
    let sway = 0.04 * envelope(t, 0.0, 2.4, 0.5) * (TAU * 0.5 * t).sin();
    let crouch = -0.06 * envelope(t, 5.0, 6.3, 0.4);
    Vec3::new(sway, 1.0 + bob + crouch, 0.0)
}

fn hips_rotation(t: f32) -> Quat {
    // One full turn, 5.0 s -> 6.3 s (peak 1.875·2π/1.3 ≈ 9.1 rad/s).
    Quat::from_rotation_y(TAU * smooth((t - 5.0) / 1.3))
}

fn chest_rotation(t: f32) -> Quat {
    let roll = -0.08 * envelope(t, 0.0, 2.4, 0.5) * (TAU * 0.5 * t).sin();
    let twist = 0.25 * envelope(t, 2.0, 3.6, 0.4) * (TAU * t / 1.6).sin();
    Quat::from_rotation_y(twist) * Quat::from_rotation_z(roll)
}

/// Neck pitch in radians (positive tips the head forward): nods on the beat, one head-bang.
fn neck_pitch(t: f32) -> f32 {
    let nods = 0.15 * envelope(t, 2.0, 3.6, 0.3) * (TAU * BEAT_HZ * t).sin();
    let bang = moves(t, &[(4.8, 0.0), (4.95, 0.45), (5.2, 0.0)]);
    nods + bang
}

fn neck_rotation(t: f32) -> Quat {
    Quat::from_rotation_x(neck_pitch(t))
}

fn head_rotation(t: f32) -> Quat {
    let roll = 0.2 * envelope(t, 0.0, 2.4, 0.5) * (TAU * 0.5 * t).sin();
    let turns = 0.6 * envelope(t, 2.0, 3.6, 0.3) * (TAU * t / 1.6).sin();
    let whips = moves(
        t,
        &[
            (3.6, 0.0),
            (3.8, 0.7),
            (4.1, 0.7),
            (4.35, -0.7),
            (4.6, -0.7),
            (4.8, 0.0),
        ],
    );
    Quat::from_rotation_y(turns + whips) * Quat::from_rotation_z(roll)
}

/// Sideways lift of the arms in radians (0: hanging), and their forward swing.
fn arm_lift(t: f32) -> f32 {
    0.12 + 0.38 * envelope(t, 3.5, 4.9, 0.3) + 0.48 * envelope(t, 4.9, 6.5, 0.4)
}

fn arm_swing(t: f32) -> f32 {
    0.25 * envelope(t, 0.0, 2.4, 0.5) * (TAU * 0.5 * t).sin()
}

/// Upper arm rotation; `side` is +1 for the left arm (+X), −1 for the right.
fn upper_arm_rotation(t: f32, side: f32) -> Quat {
    Quat::from_rotation_z(side * arm_lift(t)) * Quat::from_rotation_x(side * arm_swing(t))
}

/// Elbow bend (the forearm forward).
fn lower_arm_rotation(t: f32) -> Quat {
    Quat::from_rotation_x(-0.3 - 0.25 * envelope(t, 2.0, 4.9, 0.4))
}

/// Knee bend in radians: with the bob on the beat and with the crouch.
fn knee_bend(t: f32) -> f32 {
    let groove = envelope(t, 0.0, 3.8, 0.5);
    0.1 * groove * (0.5 - 0.5 * (TAU * BEAT_HZ * t).cos()) + 0.35 * envelope(t, 5.0, 6.3, 0.4)
}

fn upper_leg_rotation(t: f32) -> Quat {
    Quat::from_rotation_x(-knee_bend(t))
}

fn lower_leg_rotation(t: f32) -> Quat {
    Quat::from_rotation_x(2.0 * knee_bend(t))
}

fn foot_rotation(t: f32) -> Quat {
    Quat::from_rotation_x(-knee_bend(t))
}

/// Binary data and JSON pieces of the file being built.
#[derive(Default)]
struct Builder {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
    samplers: Vec<Value>,
    channels: Vec<Value>,
}

impl Builder {
    /// Appends raw bytes as a buffer view (4-byte aligned) and an accessor over them; returns
    /// the accessor index.
    fn typed(&mut self, bytes: &[u8], accessor: Value, target: Option<u32>) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        let mut view = json!({"buffer": 0, "byteOffset": offset, "byteLength": bytes.len()});
        if let Some(t) = target {
            view["target"] = json!(t);
        }
        self.views.push(view);
        let mut acc = accessor;
        acc["bufferView"] = json!(self.views.len() - 1);
        self.accessors.push(acc);
        self.accessors.len() - 1
    }

    /// Appends f32 data as a buffer view + accessor; returns the accessor index.
    fn accessor(&mut self, data: &[f32], kind: &str, min_max: bool) -> usize {
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
        let mut acc = json!({
            "bufferView": self.views.len() - 1, "componentType": 5126,
            "count": data.len() / comps, "type": kind,
        });
        if min_max {
            let min = data.iter().copied().fold(f32::INFINITY, f32::min);
            let max = data.iter().copied().fold(f32::NEG_INFINITY, f32::max);
            acc["min"] = json!([min]);
            acc["max"] = json!([max]);
        }
        self.accessors.push(acc);
        self.accessors.len() - 1
    }

    fn channel(&mut self, node: usize, path: &str, interp: &str, times: &[f32], values: &[f32]) {
        let kind = if path == "rotation" { "VEC4" } else { "VEC3" };
        let input = self.accessor(times, "SCALAR", true);
        let output = self.accessor(values, kind, false);
        self.samplers
            .push(json!({"input": input, "output": output, "interpolation": interp}));
        let sampler = self.samplers.len() - 1;
        self.channels
            .push(json!({"sampler": sampler, "target": {"node": node, "path": path}}));
    }
}

fn key_times(per_s: f32) -> Vec<f32> {
    let n = (DURATION_S * per_s).round() as usize;
    (0..=n).map(|i| i as f32 / per_s).collect()
}

fn flat_quats(times: &[f32], f: fn(f32) -> Quat) -> Vec<f32> {
    let mut prev = Quat::IDENTITY;
    let mut out = Vec::new();
    for &t in times {
        // Keep consecutive keys in the same hemisphere, as exporters do.
        let mut q = f(t);
        if q.dot(prev) < 0.0 {
            q = -q;
        }
        prev = q;
        out.extend_from_slice(&q.to_array());
    }
    out
}

fn build() -> Vec<u8> {
    let names = [
        "Hips",
        "Spine",
        "Chest",
        "Neck",
        "Head",
        "HeadTop_End",
        "Shoulder.L",
        "Shoulder.R",
        "UpperArm.L",
        "LowerArm.L",
        "Hand.L",
        "UpperArm.R",
        "LowerArm.R",
        "Hand.R",
        "UpperLeg.L",
        "LowerLeg.L",
        "Foot.L",
        "UpperLeg.R",
        "LowerLeg.R",
        "Foot.R",
    ];
    let (hips, chest, neck, head) = (0, 2, 3, 4);
    // The first eight nodes keep the indices they had before the mannequin.
    let rest: [(Vec3, &[usize]); 20] = [
        (Vec3::new(0.0, 1.0, 0.0), &[1, 14, 17]),
        (Vec3::new(0.0, 0.12, 0.0), &[2]),
        (Vec3::new(0.0, 0.15, 0.0), &[3, 6, 7]),
        (Vec3::new(0.0, 0.20, 0.0), &[4]),
        (Vec3::new(0.0, 0.10, 0.0), &[5]),
        (Vec3::new(0.0, 0.18, 0.0), &[]),
        (Vec3::new(0.18, 0.14, 0.0), &[8]),
        (Vec3::new(-0.18, 0.14, 0.0), &[11]),
        (Vec3::new(0.03, -0.01, 0.0), &[9]),
        (Vec3::new(0.02, -0.28, 0.0), &[10]),
        (Vec3::new(0.01, -0.25, 0.0), &[]),
        (Vec3::new(-0.03, -0.01, 0.0), &[12]),
        (Vec3::new(-0.02, -0.28, 0.0), &[13]),
        (Vec3::new(-0.01, -0.25, 0.0), &[]),
        (Vec3::new(0.09, -0.08, 0.0), &[15]),
        (Vec3::new(0.005, -0.42, 0.01), &[16]),
        (Vec3::new(0.005, -0.42, -0.02), &[]),
        (Vec3::new(-0.09, -0.08, 0.0), &[18]),
        (Vec3::new(-0.005, -0.42, 0.01), &[19]),
        (Vec3::new(-0.005, -0.42, -0.02), &[]),
    ];
    // Rest world positions (no rest rotations): each node's translation plus its parent's.
    let mut world = [Vec3::ZERO; 20];
    let mut parent = [None; 20];
    for (i, (_, children)) in rest.iter().enumerate() {
        for &c in children.iter() {
            parent[c] = Some(i);
        }
    }
    for i in 0..names.len() {
        // Parents come before their children in this list except for the legs and arms,
        // whose parents are earlier too; a second pass is not needed.
        world[i] = rest[i].0 + parent[i].map_or(Vec3::ZERO, |p: usize| world[p]);
    }
    let index = |name: &str| names.iter().position(|n| *n == name).expect("joint name");
    let mut nodes: Vec<Value> = names
        .iter()
        .zip(rest)
        .map(|(name, (t, children))| {
            let mut n = json!({"name": name, "translation": t.to_array()});
            if !children.is_empty() {
                n["children"] = json!(children);
            }
            n
        })
        .collect();

    let mut b = Builder::default();
    let lin = key_times(LINEAR_KEYS_PER_S);
    let hips_t: Vec<f32> = lin
        .iter()
        .flat_map(|&t| hips_translation(t).to_array())
        .collect();
    b.channel(hips, "translation", "LINEAR", &lin, &hips_t);
    b.channel(
        hips,
        "rotation",
        "LINEAR",
        &lin,
        &flat_quats(&lin, hips_rotation),
    );
    b.channel(
        chest,
        "rotation",
        "LINEAR",
        &lin,
        &flat_quats(&lin, chest_rotation),
    );
    b.channel(
        head,
        "rotation",
        "LINEAR",
        &lin,
        &flat_quats(&lin, head_rotation),
    );

    // Neck: CUBICSPLINE (in-tangent, value, out-tangent) per key; for q = Rx(θ(t)),
    // dq/dt = θ'/2 · (cos θ/2, 0, 0, −sin θ/2). θ' by central difference (1 ms).
    let cub = key_times(CUBIC_KEYS_PER_S);
    let mut neck_v = Vec::new();
    for &t in &cub {
        let h = 1e-3;
        let dtheta = (neck_pitch(t + h) - neck_pitch(t - h)) / (2.0 * h);
        let th = neck_pitch(t);
        let tangent = [
            0.5 * dtheta * (th / 2.0).cos(),
            0.0,
            0.0,
            -0.5 * dtheta * (th / 2.0).sin(),
        ];
        neck_v.extend_from_slice(&tangent);
        neck_v.extend_from_slice(&neck_rotation(t).to_array());
        neck_v.extend_from_slice(&tangent);
    }
    b.channel(neck, "rotation", "CUBICSPLINE", &cub, &neck_v);

    // Limbs.
    for (side, sign) in [("L", 1.0f32), ("R", -1.0)] {
        let j = |n: &str| index(&format!("{n}.{side}"));
        let q: Vec<f32> = {
            let mut prev = Quat::IDENTITY;
            let mut out = Vec::new();
            for &t in &lin {
                let mut r = upper_arm_rotation(t, sign);
                if r.dot(prev) < 0.0 {
                    r = -r;
                }
                prev = r;
                out.extend_from_slice(&r.to_array());
            }
            out
        };
        b.channel(j("UpperArm"), "rotation", "LINEAR", &lin, &q);
        for (joint, f) in [
            ("LowerArm", lower_arm_rotation as fn(f32) -> Quat),
            ("UpperLeg", upper_leg_rotation),
            ("LowerLeg", lower_leg_rotation),
            ("Foot", foot_rotation),
        ] {
            b.channel(j(joint), "rotation", "LINEAR", &lin, &flat_quats(&lin, f));
        }
    }

    // The mannequin: one mesh, one primitive per material, skinned to every joint.
    let mesh = mannequin::build(|n| world[index(n)], index);
    let f32_bytes = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let flat = |v: &[Vec3]| v.iter().flat_map(|p| p.to_array()).collect::<Vec<f32>>();
    let (lo, hi) = mesh.positions.iter().fold(
        (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let count = mesh.positions.len();
    let position = b.typed(
        &f32_bytes(&flat(&mesh.positions)),
        json!({"componentType": 5126, "count": count, "type": "VEC3",
               "min": lo.to_array(), "max": hi.to_array()}),
        Some(34962),
    );
    let normal = b.typed(
        &f32_bytes(&flat(&mesh.normals)),
        json!({"componentType": 5126, "count": count, "type": "VEC3"}),
        Some(34962),
    );
    let joints = b.typed(
        &mesh.joints.concat(),
        json!({"componentType": 5121, "count": count, "type": "VEC4"}),
        Some(34962),
    );
    let weights = b.typed(
        &mesh.weights.concat(),
        json!({"componentType": 5121, "normalized": true, "count": count, "type": "VEC4"}),
        Some(34962),
    );
    let ibm: Vec<f32> = world
        .iter()
        .flat_map(|p| glam::Mat4::from_translation(-*p).to_cols_array())
        .collect();
    let ibm = b.typed(
        &f32_bytes(&ibm),
        json!({"componentType": 5126, "count": names.len(), "type": "MAT4"}),
        None,
    );
    let mut primitives = Vec::new();
    for (m, idx) in mesh.indices.iter().enumerate() {
        let bytes: Vec<u8> = idx.iter().flat_map(|i| i.to_le_bytes()).collect();
        let acc = b.typed(
            &bytes,
            json!({"componentType": 5123, "count": idx.len(), "type": "SCALAR"}),
            Some(34963),
        );
        primitives.push(json!({
            "attributes": {"POSITION": position, "NORMAL": normal, "JOINTS_0": joints, "WEIGHTS_0": weights},
            "indices": acc, "material": m,
        }));
    }
    let materials: Vec<Value> = mannequin::MATERIALS
        .iter()
        .map(|(name, c)| {
            json!({"name": name, "pbrMetallicRoughness": {
                "baseColorFactor": [c[0], c[1], c[2], 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.8}})
        })
        .collect();
    nodes.push(json!({"name": "Mannequin", "mesh": 0, "skin": 0}));
    let mannequin_node = nodes.len() - 1;

    while !b.bin.len().is_multiple_of(4) {
        b.bin.push(0);
    }
    let doc = json!({
        "asset": {"version": "2.0", "generator": "wisp examples/make_dance"},
        "scene": 0,
        "scenes": [{"name": "Dance", "nodes": [0, mannequin_node]}],
        "nodes": nodes,
        "meshes": [{"name": "Mannequin", "primitives": primitives}],
        "materials": materials,
        "skins": [{"name": "Dancer", "skeleton": 0, "joints": (0..names.len()).collect::<Vec<_>>(),
                   "inverseBindMatrices": ibm}],
        "animations": [{"name": "Dance", "samplers": b.samplers, "channels": b.channels}],
        "accessors": b.accessors,
        "bufferViews": b.views,
        "buffers": [{"byteLength": b.bin.len()}],
    });
    glb(&doc.to_string().into_bytes(), &b.bin)
}

/// GLB 2.0 container: 12-byte header, JSON chunk padded with spaces, BIN chunk padded with 0.
fn glb(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let mut json = json.to_vec();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
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
    out.extend_from_slice(bin);
    out
}

fn main() -> anyhow::Result<()> {
    let path = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "animations/dance.glb".to_string()),
    );
    let bytes = build();
    std::fs::write(&path, &bytes)?;
    let m = Motion::load(&path, &MotionOptions::default())?;
    // Peak speeds of the head frame, sampled at 1 kHz.
    let dt = 1e-3;
    let (mut w_max, mut v_max, mut w_at, mut v_at) = (0.0f32, 0.0f32, 0.0, 0.0);
    let mut prev = m.sample(0.0).head;
    for i in 1..=(m.duration_s() / dt).round() as usize {
        let t = i as f32 * dt;
        let h = m.sample(t).head;
        let dq = Quat::from_mat3a(&h.matrix3) * Quat::from_mat3a(&prev.matrix3).inverse();
        let w = dq.to_axis_angle().1.min(TAU - dq.to_axis_angle().1) / dt;
        let v = (h.translation - prev.translation).length() / dt;
        if w > w_max {
            (w_max, w_at) = (w, t);
        }
        if v > v_max {
            (v_max, v_at) = (v, t);
        }
        prev = h;
    }
    let ch = m.character().expect("the mannequin loads");
    println!(
        "wrote {} ({} bytes): clip {:?}, {:.2} s, fit {:?} ({:?}); mannequin {} vertices, {} \
         triangles, {} capsules; peak head angular speed {w_max:.2} rad/s at {w_at:.2} s, \
         linear speed {v_max:.2} m/s at {v_at:.2} s",
        path.display(),
        bytes.len(),
        m.clip_name(),
        m.duration_s(),
        m.fit(),
        m.fit_method(),
        ch.vertex_count(),
        ch.triangles.len(),
        m.sample(0.0).capsules.len(),
    );
    Ok(())
}
