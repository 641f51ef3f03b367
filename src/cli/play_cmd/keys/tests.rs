use super::*;

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
