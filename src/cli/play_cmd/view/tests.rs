use super::*;
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;

/// `Engine::set_camera` takes effect at once and survives a render (the head-following
/// rig does not override it); setting the head-following camera again frames the same
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
    engine.set_camera(CameraSetup::default());
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
