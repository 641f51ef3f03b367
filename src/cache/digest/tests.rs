use super::*;
use crate::motion::MotionOptions;

#[test]
fn hairstyle_digest_ignores_spelling_and_sees_every_value() {
    let a = Hairstyle::default_smooth();
    // The same hairstyle through another spelling of its JSON.
    let text = serde_json::to_string_pretty(&a).unwrap();
    let b = Hairstyle::from_json(&text, "b.json").unwrap();
    assert_eq!(hairstyle_digest(&a), hairstyle_digest(&b));
    let mut c = a.clone();
    c.fiber.eta += 1e-6;
    assert_ne!(hairstyle_digest(&a), hairstyle_digest(&c));
    let mut d = a.clone();
    d.seed += 1;
    assert_ne!(hairstyle_digest(&a), hairstyle_digest(&d));
    assert_ne!(
        hairstyle_digest(&a),
        hairstyle_digest(&Hairstyle::default_curly())
    );
}

#[test]
fn motion_digest_tells_speed_and_stillness_apart() {
    let dance = Motion::default_dance();
    assert_eq!(motion_digest(&dance), motion_digest(&dance.clone()));
    let faster = crate::motion::dance::try_dance(&MotionOptions {
        speed: 1.5,
        ..MotionOptions::default()
    })
    .unwrap();
    assert_ne!(motion_digest(&dance), motion_digest(&faster));
    let still = Motion::still(glam::Affine3A::IDENTITY);
    assert_ne!(motion_digest(&dance), motion_digest(&still));
    let moved = Motion::still(glam::Affine3A::from_translation(glam::Vec3::X * 1e-3));
    assert_ne!(motion_digest(&still), motion_digest(&moved));
}

#[test]
fn digests_print_as_hex() {
    let d = Digest([0xab; 32]);
    assert_eq!(d.short(), "abababababab");
    assert_eq!(d.to_string().len(), 64);
}
