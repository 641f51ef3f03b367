//! Generated scene files (`support::hostile::scene`), in process: colours that overflow once
//! exposed are refused naming the field, colours that are huge but finite render with no
//! black or non-finite pixel, point lights too far for their map are drawn as directional
//! lights with every hair sample in the map, and an unknown field in any struct or tagged enum
//! variant of the scene file is refused naming the file, the object, the field and the fields
//! allowed. Issue 60, items 2–4.

use crate::support::hostile::Rng;
use crate::support::hostile::scene::{
    self, far_point_light, huge_but_finite, overflowing_after_exposure, unknown_field,
};
use glam::{Affine3A, Vec3};
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::light::Light;
use wisp::motion::Motion;
use wisp::scene::far_light::FAR_LIGHT_REACH_RATIO;
use wisp::scene::{Scene, SceneFile};

const FILE: &str = "hostile_scene.json";

fn refusal(text: &str) -> String {
    match SceneFile::from_json(text, FILE) {
        Ok(_) => panic!("accepted: {text}"),
        Err(e) => e.to_string(),
    }
}

/// Cases of each generated class (`WISP_HOSTILE_CASES` overrides).
fn cases(default: u64) -> u64 {
    std::env::var("WISP_HOSTILE_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

#[test]
fn colours_that_overflow_once_exposed_are_refused_naming_the_field() {
    for i in 0..cases(64) {
        let seed = 0x5CE0_0200 + i;
        let (scene, field) = overflowing_after_exposure(&mut Rng::new(seed));
        let text = scene.to_string();
        let msg = refusal(&text);
        assert!(
            msg.starts_with(&format!("{FILE}: {field}: ")),
            "seed {seed}: {msg}"
        );
        assert!(
            msg.contains("exposure_stops") && msg.contains("must be finite"),
            "seed {seed}: {msg}"
        );
    }
}

/// A still head alone at the origin, the smooth hairstyle, the settle shortened.
fn engine(scene: Scene) -> Engine {
    let mut config = EngineConfig::sized(scene.width, scene.height).with_scene(&scene);
    config.simulation.settle_s = 0.2;
    Engine::new(
        Hairstyle::default_smooth(),
        Motion::still(Affine3A::IDENTITY),
        config,
    )
}

/// Before the shading saturated, the ambient and irradiance sums of such scenes overflowed to
/// infinity and the hair came out black (538 of 4,096 pixels at `--ambient 3e38 --irradiance
/// 3e38`); the background is never black, so no pixel may be.
#[test]
fn huge_but_finite_colours_saturate_instead_of_turning_black() {
    for i in 0..cases(3) {
        let seed = 0x5CE0_0300 + i;
        let text = huge_but_finite(&mut Rng::new(seed)).to_string();
        let (_, scene) = SceneFile::from_json(&text, FILE).expect("a valid scene");
        let mut e = engine(scene);
        e.frame(0.0);
        let fb = e.framebuffer();
        let bad = fb
            .color
            .iter()
            .filter(|c| !c.is_finite() || **c == Vec3::ZERO)
            .count();
        assert_eq!(
            bad, 0,
            "seed {seed}: {bad} black or non-finite pixels: {text}"
        );
    }
}

/// The frame lit by `light` alone, 48 × 48, and every map's skipped sample count.
fn lit_by(light: Light) -> (Vec<Vec3>, Vec<usize>) {
    let scene = Scene {
        width: 48,
        height: 48,
        lights: vec![light],
        ..Scene::default()
    };
    let mut e = engine(scene);
    e.frame(0.0);
    let skipped = e.maps().iter().map(|m| m.stats().skipped).collect();
    (e.framebuffer().color.clone(), skipped)
}

/// Before: every sample of the map of a point light at 1.5e11 m or more fell out of it (the
/// hair unshadowed); now it is drawn as the directional light it is. At distances where
/// I = 6·d² is a finite f32 the frame is the one of a directional light of irradiance 6 along
/// the same direction, up to the rounding of that direction (one f32 ulp in its components:
/// at most 2 of 255 in any pixel, measured 0).
#[test]
fn far_point_lights_are_drawn_as_directional_lights() {
    let head = [0.0, 0.0, 0.0];
    for i in 0..cases(4) {
        let seed = 0x5CE0_0400 + i;
        let (pos, intensity, travel) = far_point_light(&mut Rng::new(seed), head);
        let point = Light::point(
            Vec3::new(pos[0] as f32, pos[1] as f32, pos[2] as f32),
            Vec3::splat(intensity as f32),
        )
        .expect("a valid point light");
        let (image, skipped) = lit_by(point);
        assert_eq!(skipped, vec![0], "seed {seed}: samples out of the map");
        assert!(image.iter().all(|c| c.is_finite()), "seed {seed}");
        let d = (pos[0].powi(2) + pos[1].powi(2) + pos[2].powi(2)).sqrt();
        if 6.0 * d * d > f64::from(f32::MAX) {
            continue;
        }
        let travel = Vec3::new(travel[0] as f32, travel[1] as f32, travel[2] as f32);
        let (want, _) = lit_by(Light::directional(travel, Vec3::splat(6.0)).unwrap());
        let worst = image
            .iter()
            .zip(&want)
            .map(|(a, b)| (a - b).abs().max_element())
            .fold(0.0f32, f32::max);
        println!("seed {seed}: d = {d:e} m, worst {worst:e}");
        assert!(
            worst <= 2.0 / 255.0,
            "seed {seed}: d = {d:e} m, a pixel differs by {worst}"
        );
    }
}

/// The rule's threshold, 2048 × the reach: a point light just inside it keeps its central map,
/// whose rays differ from parallel by at most half a cell of the finest map, so its frame is
/// close to the directional light's (the inverse-square law across the hair, ±2R/d ≈ ±0.1%, and
/// the lean of the rays are what differ); one just past it is the directional light. Mean
/// absolute difference per pixel channel, linear radiance.
#[test]
fn the_far_light_threshold_separates_two_nearly_equal_frames() {
    let reach = Hairstyle::default_smooth().reach_m() as f64;
    let travel = Vec3::new(-0.6, -0.64, -0.48);
    let at = |ratio: f64| {
        let d = ratio * reach;
        let p = -travel.as_dvec3() * d;
        Light::point(p.as_vec3(), Vec3::splat((6.0 * d * d) as f32)).unwrap()
    };
    let (directional, _) = lit_by(Light::directional(travel, Vec3::splat(6.0)).unwrap());
    let (past, _) = lit_by(at(FAR_LIGHT_REACH_RATIO * 1.01));
    let (inside, skipped) = lit_by(at(FAR_LIGHT_REACH_RATIO * 0.99));
    assert_eq!(skipped, vec![0]);
    let mean_abs = |a: &[Vec3]| {
        a.iter()
            .zip(&directional)
            .map(|(x, y)| f64::from((*x - *y).abs().element_sum()) / 3.0)
            .sum::<f64>()
            / a.len() as f64
    };
    // Measured: 9.2e-10 past (the f64 direction rounded to f32) and 5.0e-5 inside (0.013 of
    // an 8-bit step); the bounds are about 10× and 4× those.
    assert!(mean_abs(&past) < 1e-8, "{}", mean_abs(&past));
    let inside_err = mean_abs(&inside);
    assert!(inside_err < 2e-4, "{inside_err}");
}

#[test]
fn an_unknown_field_in_every_struct_and_tagged_variant_is_refused() {
    let slots = scene::slots();
    for (k, slot) in slots.iter().enumerate() {
        for i in 0..cases(6) {
            let seed = 0x5CE0_0500 + 100 * k as u64 + i;
            let (value, name) = unknown_field(&mut Rng::new(seed), slot);
            let text = value.to_string();
            let msg = refusal(&text);
            // A struct's error names the unknown field's path, a tagged enum's the variant's.
            let at = if slot.path.is_empty() {
                vec![name.clone()]
            } else {
                vec![slot.path.to_string(), format!("{}.{name}", slot.path)]
            };
            assert!(
                at.iter()
                    .any(|a| msg.starts_with(&format!("{FILE}: {a}: "))),
                "{} seed {seed}: {msg}",
                slot.what
            );
            assert!(
                msg.contains(&format!("unknown field `{name}`")) && msg.contains("expected"),
                "{} seed {seed}: {msg}",
                slot.what
            );
            // The fields allowed are named (the tag is the variant's, not listed by serde).
            for field in slot.allowed.iter().filter(|f| **f != "type") {
                assert!(
                    msg.contains(&format!("`{field}`")),
                    "{} seed {seed}: `{field}` not named: {msg}",
                    slot.what
                );
            }
        }
    }
}
