//! Generated scene files for what a field-by-field check does not see: colours that overflow
//! a 32-bit float only once exposed, colours that are finite but huge (the shading must
//! saturate, not overflow), point lights too far for their map, and unknown fields in every
//! tagged enum variant and struct of the scene file. Each generator returns the scene's JSON
//! and what must happen to it; `tests/lib/hostile_scene.rs` runs them in process and
//! `tests/cli/hostile_scene.rs` through the binary.

use super::Rng;
use serde_json::{Value, json};

/// A scene with every colour field and every tagged enum's variants in reach: a directional
/// and a point light, the engine's camera, 32 × 32 pixels.
pub fn base_scene() -> Value {
    json!({
        "image": {"width": 32, "height": 32},
        "camera": {"type": "follow_head"},
        "lights": [
            {"type": "directional", "direction": [-0.75, -0.55, -0.35], "irradiance": [6, 6, 6]},
            {"type": "point", "position_m": [0.6, 1.9, 0.8], "intensity": [2, 1.8, 1.5]}
        ],
        "ambient": [0.035, 0.04, 0.05],
        "background": [0.012, 0.014, 0.018],
        "exposure_stops": 0
    })
}

/// The colour fields of [`base_scene`], as errors name them.
pub const COLOUR_FIELDS: [&str; 4] = [
    "ambient",
    "background",
    "lights[0].irradiance",
    "lights[1].intensity",
];

/// The JSON value of colour field `field` of `scene`.
fn colour_slot<'a>(scene: &'a mut Value, field: &str) -> &'a mut Value {
    match field {
        "lights[0].irradiance" => &mut scene["lights"][0]["irradiance"],
        "lights[1].intensity" => &mut scene["lights"][1]["intensity"],
        f => &mut scene[f],
    }
}

/// `m · 2^e` as written in a file (exact in f32 for the mantissas used).
fn power_of_two_times(m: f64, e: i32) -> f64 {
    m * 2f64.powi(e)
}

/// A colour that overflows f32 only once exposed: one channel of a colour field set to
/// v = m·2^e (m in [1, 1.99], e in 109..=127, so v is finite) and `exposure_stops` s = 129 − e
/// (in [2, 20]), so v·2^s ≥ 2^129 > f32::MAX ≈ 2^128. Returns the scene and the field the
/// refusal must name.
pub fn overflowing_after_exposure(rng: &mut Rng) -> (Value, &'static str) {
    let mut scene = base_scene();
    let field = *rng.pick(&COLOUR_FIELDS);
    let e = 109 + rng.below(19) as i32;
    let m = *rng.pick(&[1.0, 1.5, 1.99]);
    let channel = rng.below(3);
    colour_slot(&mut scene, field)[channel] = json!(power_of_two_times(m, e));
    scene["exposure_stops"] = json!(129 - e);
    (scene, field)
}

/// Colours that are finite once exposed but huge: the ambient and the first light's
/// irradiance (and, by chance, the other colours) at v = m·2^e with e in 100..=126 and an
/// exposure of at most 126 − e stops, so v·2^s ≤ 2^127 < f32::MAX. The scene is valid; every
/// pixel must come out finite and not black (before the shading saturated, sums of such
/// radiances overflowed and the hair came out black).
pub fn huge_but_finite(rng: &mut Rng) -> Value {
    let mut scene = base_scene();
    let e = 100 + rng.below(27) as i32;
    let stops = (126 - e).min(20) - rng.below(4) as i32;
    for field in COLOUR_FIELDS {
        let essential = matches!(field, "ambient" | "lights[0].irradiance");
        if essential || rng.chance(0.5) {
            let m = *rng.pick(&[1.0, 1.5, 1.99]);
            let v = power_of_two_times(m, e);
            *colour_slot(&mut scene, field) = json!([v, v, v]);
        }
    }
    scene["exposure_stops"] = json!(stops);
    scene
}

/// Distances of a far point light, metres: past the far-light rule (2048 × the hair's reach,
/// about 1 km for the presets), the Sun's, past where d² overflows f32 (1.8e19 m), and near
/// the largest f32.
pub const FAR_DISTANCES_M: [f64; 5] = [5e3, 1.5e11, 1e18, 1e25, 3e38];

/// A point light far from `head` along a random direction from above (y > 0.3, so the hair
/// shadows itself and the skin), of intensity E·d² for irradiance E = 6 at the head (capped at
/// f32::MAX: past about 7.5e18 m it lights the hair less). Returns (position, intensity, the
/// unit direction its light travels).
pub fn far_point_light(rng: &mut Rng, head: [f64; 3]) -> ([f64; 3], f64, [f64; 3]) {
    let d = *rng.pick(&FAR_DISTANCES_M);
    let dir = loop {
        let v = [
            rng.below(2001) as f64 / 1000.0 - 1.0,
            0.3 + rng.below(701) as f64 / 1000.0,
            rng.below(2001) as f64 / 1000.0 - 1.0,
        ];
        let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if len > 0.5 && len <= 1.0 {
            break [v[0] / len, v[1] / len, v[2] / len];
        }
    };
    let position = [
        head[0] + dir[0] * d,
        head[1] + dir[1] * d,
        head[2] + dir[2] * d,
    ];
    let intensity = (6.0 * d * d).min(f64::from(f32::MAX));
    (position, intensity, [-dir[0], -dir[1], -dir[2]])
}

/// Where an unknown field goes: the JSON pointer of an object of the scene, the path an error
/// names it by (empty at the top level, where the error names the unknown field itself), and
/// the scene edited so that the object is the variant meant.
pub struct Slot {
    pub pointer: &'static str,
    pub path: &'static str,
    pub what: &'static str,
    /// The fields the object has, as the scene file's doc lists them.
    pub allowed: &'static [&'static str],
    edit: fn(&mut Value),
}

/// Every struct and every tagged enum variant of the scene file.
pub fn slots() -> Vec<Slot> {
    vec![
        Slot {
            pointer: "",
            path: "",
            what: "the scene",
            allowed: &[
                "image",
                "camera",
                "lights",
                "ambient",
                "background",
                "exposure_stops",
                "draw_solids",
                "quality",
            ],
            edit: |_| {},
        },
        Slot {
            pointer: "/image",
            path: "image",
            what: "image",
            allowed: &["width", "height"],
            edit: |_| {},
        },
        Slot {
            pointer: "/camera",
            path: "camera",
            what: "camera follow_head",
            allowed: &["type", "framing"],
            edit: |_| {},
        },
        Slot {
            pointer: "/camera",
            path: "camera",
            what: "camera follow_head with a framing",
            allowed: &["type", "framing"],
            edit: |s| s["camera"]["framing"] = json!("head"),
        },
        Slot {
            pointer: "/camera",
            path: "camera",
            what: "camera fixed",
            allowed: &["type", "position_m", "target_m", "up", "fov_y_deg"],
            edit: |s| {
                s["camera"] =
                    json!({"type": "fixed", "position_m": [0, 1.6, 2], "target_m": [0, 1.6, 0]})
            },
        },
        Slot {
            pointer: "/lights/0",
            path: "lights[0]",
            what: "light directional",
            allowed: &["type", "direction", "irradiance"],
            edit: |_| {},
        },
        Slot {
            pointer: "/lights/1",
            path: "lights[1]",
            what: "light point",
            allowed: &["type", "position_m", "intensity"],
            edit: |_| {},
        },
    ]
}

/// Names an unknown field takes: nonsense, a field of another variant or struct, the tag's
/// own spelling in another case.
const UNKNOWN_NAMES: [&str; 8] = [
    "zzz",
    "position_m",
    "intensity",
    "irradiance",
    "framing",
    "Type",
    "width ",
    "é",
];

/// Values an unknown field holds (never `null`: an absent option may be written as `null`).
fn unknown_value(rng: &mut Rng) -> Value {
    match rng.below(5) {
        0 => json!("garbage"),
        1 => json!([1, 2]),
        2 => json!({"a": 1}),
        3 => json!(1e30),
        _ => json!(true),
    }
}

/// `slot`'s object in a scene with one field it does not have: (scene, the field's name).
pub fn unknown_field(rng: &mut Rng, slot: &Slot) -> (Value, String) {
    let mut scene = base_scene();
    (slot.edit)(&mut scene);
    let object = scene
        .pointer_mut(slot.pointer)
        .and_then(Value::as_object_mut)
        .expect("the slot is an object");
    let name = loop {
        let n = *rng.pick(&UNKNOWN_NAMES);
        if !object.contains_key(n) && !slot.allowed.contains(&n) {
            break n;
        }
    };
    object.insert(name.to_string(), unknown_value(rng));
    (scene, name.to_string())
}
