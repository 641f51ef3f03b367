use super::*;

/// A fragment stays 24 bytes: a frame keeps millions of them between emission and
/// compositing.
#[test]
fn fragment_is_24_bytes() {
    assert_eq!(size_of::<Frag>(), 24);
}
