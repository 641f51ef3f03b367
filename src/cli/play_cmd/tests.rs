use super::*;
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;

#[test]
fn a_tap_within_one_frame_counts_once_and_repeats_do_not() {
    let mut p = Presses::default();
    // A tap: down and up before the frame reads them.
    p.set(Key::P, true);
    p.set(Key::P, false);
    // A held key: the X server's detectable auto-repeat sends presses without releases.
    p.set(Key::Space, true);
    p.set(Key::Space, true);
    p.set(Key::Space, true);
    p.set(Key::P, true);
    assert_eq!(std::mem::take(&mut p.pressed), [Key::P, Key::Space, Key::P]);
    p.set(Key::Space, false);
    p.set(Key::Space, true);
    assert_eq!(p.pressed, [Key::Space]);
    assert_eq!(p.down, [Key::P, Key::Space]);
}

#[test]
fn screenshot_names_never_clobber() {
    let dir = Path::new("shots");
    assert_eq!(
        free_shot_path(dir, |_| false),
        Some(dir.join("wisp-shot-0001.png"))
    );
    // Taken names are skipped, including a gap's later neighbours.
    let taken = |p: &Path| {
        [
            "wisp-shot-0001.png",
            "wisp-shot-0002.png",
            "wisp-shot-0004.png",
        ]
        .iter()
        .any(|n| p.ends_with(n))
    };
    assert_eq!(
        free_shot_path(dir, taken),
        Some(dir.join("wisp-shot-0003.png"))
    );
    assert_eq!(free_shot_path(dir, |_| true), None);
}

/// `Engine::set_camera` takes effect at once and survives a render (the head-following
/// rig no longer overrides it); setting the head-following camera again frames the same
/// still hair as the engine first did.
#[test]
fn the_mouse_camera_replaces_and_restores_the_engines() {
    let config = {
        let mut config = wisp::engine::EngineConfig::sized(48, 32);
        config.simulation.simulate = false;
        config.hair_map.map_res = Some(16);
        config
    };
    let style = Hairstyle::default_smooth();
    let motion = Motion::still(glam::Affine3A::IDENTITY);
    let mut engine = Engine::new(style, motion, config);
    let first = *engine.camera();
    let mut orbit = Orbit::from_camera(&first, Vec3::ZERO);
    orbit.orbit(40.0, -25.0);
    orbit.zoom(2.0);
    let spec = orbit.spec(Vec3::ZERO).unwrap();
    engine.set_camera(CameraSetup::Fixed(spec));
    engine.frame(0.1);
    assert_eq!(*engine.camera(), spec.camera(48, 32));
    assert_ne!(engine.camera().eye, first.eye);
    engine.set_camera(CameraSetup::HeadFollowing);
    engine.frame(0.2);
    let back = engine.camera();
    assert!(
        (back.eye - first.eye).length() < 1e-5,
        "{} vs {}",
        back.eye,
        first.eye
    );
    assert_eq!(back.target, first.target);
}
