//! Setting up an engine's scene: the hairstyle fitted to a character's head, where the roots lie
//! on the head mesh, and the solids and colliders of a pose.

use crate::hairstyle::{GuideSet, Hairstyle, guide_roots};
use crate::map::Solid;
use crate::motion::{CarryError, Motion, Pose, RootsOnHead};
use crate::sim::{CapsuleCollider, Colliders, SphereCollider};
use glam::{Affine3A, Vec3};

/// The hairstyle an [`Engine`] grows on `motion`'s character: when the character has a head
/// mesh, the head ellipsoid takes the half extents of that mesh's box (pose metres, clamped to
/// the valid range), so generated roots lie on the drawn head instead of floating above a
/// flat one or hiding under a wide one (RobotExpressive's head is 0.10 × 0.07 × 0.10 m after
/// the fit against the presets' 0.076 × 0.098 × 0.094 m). Otherwise the style is unchanged.
pub fn fit_style_to_character(style: &Hairstyle, motion: &Motion) -> Hairstyle {
    let mut style = style.clone();
    if let Some(half) = motion.head_half_extents_m() {
        let lo = crate::hairstyle::MIN_HEAD_RADIUS_M;
        let r = half.clamp(Vec3::splat(lo), Vec3::ONE);
        if r.is_finite() {
            style.head.radii_m = r.to_array();
        }
    }
    style
}

/// How far the roots of `style`'s guides, grown on `motion`'s character as an [`Engine`] grows
/// them ([`fit_style_to_character`]), lie from the drawn head at t = 0
/// ([`Motion::roots_on_head`], for the fitted head's mean radius); `None` without a head mesh.
pub fn roots_on_head(style: &Hairstyle, motion: &Motion) -> Option<RootsOnHead> {
    motion.character()?;
    let style = fit_style_to_character(style, motion);
    roots_at(&guide_roots(&style), &style, motion)
}

/// [`roots_on_head`] for guides made elsewhere (an imported groom placed on `style`'s head,
/// which is used as given); `None` without a head mesh.
pub fn roots_of_guides_on_head(
    guides: &GuideSet,
    style: &Hairstyle,
    motion: &Motion,
) -> Option<RootsOnHead> {
    motion.character()?;
    let roots: Vec<Vec3> = (0..guides.count()).map(|g| guides.guide(g)[0]).collect();
    roots_at(&roots, style, motion)
}

/// How far `roots` lie from `motion`'s drawn head, for `style`'s head's mean radius.
fn roots_at(roots: &[Vec3], style: &Hairstyle, motion: &Motion) -> Option<RootsOnHead> {
    let [x, y, z] = style.head.radii_m;
    motion.roots_on_head(roots, (x * y * z).cbrt())
}

/// Pins the roots of `guides`, a groom kept as authored on `motion`'s character, each to the
/// nearest bone of the character (`motion::carriers`): the motion keeps the bones that carry
/// roots and each guide its carrier (`GuideSet::carrier`). Returns how many bones carry roots.
pub fn carry_roots_by_bones(
    guides: &mut GuideSet,
    motion: &mut Motion,
) -> Result<usize, CarryError> {
    let roots: Vec<Vec3> = (0..guides.count()).map(|g| guides.guide(g)[0]).collect();
    guides.carrier = motion.carry_by_nearest_bones(&roots)?;
    Ok(motion.carrier_count())
}

/// The opaque solids of a pose: the head ellipsoid first, then the body spheres.
pub(super) fn solids_of(pose: &Pose, head_radii_m: Vec3) -> impl Iterator<Item = Solid> + '_ {
    let head = Solid {
        unit_sphere_to_world: pose.head * Affine3A::from_scale(head_radii_m),
    };
    std::iter::once(head).chain(pose.spheres.iter().map(|s| Solid {
        unit_sphere_to_world: Affine3A::from_scale_rotation_translation(
            Vec3::splat(s.radius_m),
            glam::Quat::IDENTITY,
            s.center,
        ),
    }))
}

pub(super) fn colliders_of(pose: &Pose, radii: Vec3) -> Colliders {
    let mut c = Colliders::head_only(pose.head, radii);
    write_colliders(pose, radii, &mut c);
    c
}

/// Writes `pose`'s colliders (head ellipsoid of `radii`, body spheres and capsules) and the
/// bones that carry roots into `c`,
/// reusing its buffers: what the engine's simulation and interpolation are kept out of.
pub fn write_colliders(pose: &Pose, radii: Vec3, c: &mut Colliders) {
    c.head = pose.head;
    c.head_radii_m = radii;
    c.spheres.clear();
    c.spheres
        .extend(pose.spheres.iter().map(|s| SphereCollider {
            center: s.center,
            radius_m: s.radius_m,
        }));
    c.capsules.clear();
    c.capsules
        .extend(pose.capsules.iter().map(|k| CapsuleCollider {
            a: k.a,
            b: k.b,
            radius_m: k.radius_m,
        }));
    c.carriers.clone_from(&pose.carriers);
}
