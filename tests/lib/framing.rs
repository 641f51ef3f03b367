//! The engine's framings of a character (`wisp::scene::Framing`) and `--still` with one
//! (`Motion::held_still`): the camera shows the body, not a head alone.

use glam::{Vec3, Vec3Swizzles};
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;
use wisp::raster::Framebuffer;
use wisp::scene::{CameraSetup, Framing};

/// A small frame of the smooth hairstyle on `motion` at time `t_s`, the camera `camera`; the
/// hair rides rigidly (no simulation: the framing and the solids are what is tested).
fn frame(motion: Motion, camera: CameraSetup, t_s: f64) -> (Framebuffer, Engine) {
    let mut config = EngineConfig::sized(96, 54);
    config.simulation.simulate = false;
    config.hair_map.map_res = Some(32);
    config.scene.camera = camera;
    let mut engine = Engine::new(Hairstyle::default_smooth(), motion, config);
    let fb = engine.frame(t_s).clone();
    (fb, engine)
}

/// Pixels of the lower half (rows 27..54) whose coverage is above a half.
fn covered_in_lower_half(fb: &Framebuffer) -> usize {
    let w = fb.width as usize;
    fb.coverage[27 * w..].iter().filter(|a| **a > 0.5).count()
}

/// The fraction of the character's posed vertices 0.6–0.75 m below the head centre and within
/// 0.18 m of it across (the hips, not the hands: on the dance's
/// 1.75 m figure the hip joint is 0.66 m below the head centre and the hips 0.17 m to a side,
/// `examples/make_dance`) that project inside the engine's image.
fn hips_in_view(e: &Engine) -> f32 {
    let head = Vec3::from(e.pose().head.translation);
    let cam = e.camera();
    let band: Vec<Vec3> = (e.character_pose().positions.iter())
        .filter(|p| (head.y - 0.75..=head.y - 0.6).contains(&p.y))
        .filter(|p| (p.xz() - head.xz()).length() < 0.18)
        .copied()
        .collect();
    assert!(band.len() > 10, "{} vertices at the hips", band.len());
    let inside = band.iter().filter(|p| {
        cam.project(**p).is_some_and(|q| {
            (0.0..cam.width as f32).contains(&q.x) && (0.0..cam.height as f32).contains(&q.y)
        })
    });
    inside.count() as f32 / band.len() as f32
}

/// At 4.2 s, mid-whip: the upper framing (the default with the dance's body) has the hips in
/// the picture (every vertex of the hips band projects inside it, as the framing's
/// boxes hold every vertex of the top half of the figure) and the drawn trunk covers the lower
/// half: over 300 of its 2,592 pixels (the trunk, about 0.35 m wide in a frame about 1.4 m
/// wide, fills about a quarter of the width over the lower half, 650 pixels). The head
/// framing, the close-up, has none of the hips in the picture: it is cropped above them.
#[test]
fn the_upper_framing_shows_the_body_down_to_the_hips_and_is_the_default() {
    let dance = Motion::default_dance();
    assert!(dance.has_body());
    let (upper, e) = frame(
        dance.clone(),
        CameraSetup::Framed(Some(Framing::Upper)),
        4.2,
    );
    assert!(!e.camera.follows_head());
    assert_eq!(hips_in_view(&e), 1.0);
    let u = covered_in_lower_half(&upper);
    assert!(u > 300, "upper: {u} covered lower pixels");
    let (_, e) = frame(dance.clone(), CameraSetup::Framed(Some(Framing::Head)), 4.2);
    assert!(e.camera.follows_head());
    assert_eq!(hips_in_view(&e), 0.0);
    let (default, _) = frame(dance, CameraSetup::Framed(None), 4.2);
    assert_eq!(default.color, upper.color);
}

/// `Motion::held_still` keeps the dance's character, standing in the clip's first pose with
/// its head centre at the origin (the head alone's place) to within a micrometre; drawn, its
/// body covers the lower half of the default framing's picture below the head.
#[test]
fn the_still_dance_keeps_its_character_with_the_head_at_the_origin() {
    let still = Motion::default_dance().held_still();
    assert!(still.character().is_some() && still.has_body());
    assert_eq!(still.duration_s(), 0.0);
    let (a, b) = (still.sample(0.0), still.sample(3.0));
    assert!(Vec3::from(a.head.translation).length() < 1e-6);
    assert_eq!(a, b);
    assert!(!a.capsules.is_empty() || !a.spheres.is_empty());
    let (fb, _) = frame(still, CameraSetup::default(), 0.0);
    assert!(covered_in_lower_half(&fb) > 300);
}
