//! The hair's shadow on the skin and clothes against exact ray shooting.
//!
//! What is measured: at every pixel where the camera sees a solid (the character's mesh, or
//! the head and body ellipsoids) fully, facing the key light, the T_f the skin shader reads
//! from the map ([`crate::map::LightMap::light_at_surface`], at the normal-offset point the
//! shader uses) against the exact reference's
//! ([`crate::accuracy::exact::ExactReference::light_at_point`]: rays toward the light through the
//! explicit fibres, from a disc across the light of half a pixel's width at the point's depth,
//! so the reference is the pixel's own average, what an ideal renderer shows at this
//! resolution). The solids' own shadow (the head on the body) is the map's occluder grid in
//! both, so only the hair's shadow differs.
//!
//! The reference shoots rays at every measured pixel; its cost grows with pixels × rays (the
//! smooth preset at 800 × 800 with 64 rays: about 2 s on 2 cores; `wisp accuracy --skin`,
//! ACCURACY.md §1).

use super::{exact_reference, key_light};
use crate::accuracy::comparison::Comparison;
use crate::engine::Engine;
use crate::fiber::LightAtPoint;
use crate::map::Shadow;
use crate::raster::Framebuffer;
use glam::Vec3;
use std::time::Instant;

/// The skin's T_f: map against exact rays, over the measured pixels.
#[derive(Clone, Debug)]
pub struct SkinReport {
    /// Pixels measured (fully covered by a solid, facing the key light).
    pub pixels: usize,
    /// Of those, pixels the hair shadows noticeably (reference T_f < 0.98).
    pub shadowed_pixels: usize,
    /// The comparison over all measured pixels (binned by the reference's and the map's T_f).
    pub comparison: Comparison,
    /// Over the shadowed pixels only.
    pub shadowed: Comparison,
    /// Per-pixel T_f (mean of R, G, B) images, row-major, `width × height`: the map's, the
    /// reference's; pixels not measured hold a negative value.
    pub map_tf: Vec<f32>,
    pub reference_tf: Vec<f32>,
    pub width: u32,
    pub height: u32,
    /// Time to build the reference and shoot its rays, ms.
    pub reference_ms: f64,
}

/// Measures the skin's shadow in the engine's current frame (after [`Engine::frame`] or
/// [`Engine::build_map`]) for the key light (the first), with `rays` rays per pixel.
pub fn measure_skin(engine: &mut Engine, rays: u32) -> SkinReport {
    let key = engine.scene.lights[0];
    let (width, height) = (engine.scene.width, engine.scene.height);
    // Which pixels a solid covers fully and that face the light.
    let facing = |p: Vec3, n: Vec3| n.dot(key.toward_and_irradiance(p).0) > 0.0;
    let mask = engine.solids_image(|p, n, _| Vec3::splat(f32::from(u8::from(facing(p, n)))));
    let measured: Vec<bool> = mask.color.iter().map(|c| c.x >= 0.999).collect();
    // The key light's shadows, copied: the engine is drawn into while they are read.
    let key_shadow = engine
        .shadows()
        .light(0)
        .expect("an engine has a map per light");
    let (hair, solids, skin) = (
        key_shadow.hair.clone(),
        key_shadow.solids.clone(),
        key_shadow.skin.cloned(),
    );
    let map = Shadow {
        hair: &hair,
        solids: &solids,
        skin: skin.as_ref(),
        earlier: None,
    };
    let offset_m = map.surface_offset_m();
    let map_img = engine.solids_image(|p, n, _| {
        if facing(p, n) {
            map.light_at_surface(p + n * offset_m)
        } else {
            Vec3::ZERO
        }
    });
    let map_tf = tf_image(map_img, &measured);
    let t0 = Instant::now();
    // The reference borrows the strands; the engine is drawn into meanwhile.
    let (style, strands, fiber) = (
        engine.style.clone(),
        engine.strands().clone(),
        engine.fiber.clone(),
    );
    let reference = exact_reference(&style, &strands, &fiber, key_light(engine));
    let camera = *engine.camera();
    let (eye, forward, focal_px) = (camera.eye(), camera.forward(), camera.focal_px());
    let ref_img = engine.solids_image(|p, n, _| {
        if !facing(p, n) {
            return Vec3::ZERO;
        }
        let q = p + n * offset_m;
        let half_pixel_m = 0.5 * (q - eye).dot(forward).max(1e-4) / focal_px;
        let hair = reference.light_at_point(q, half_pixel_m, rays);
        hair.tf * map.solid_visibility(q)
    });
    let reference_tf = tf_image(ref_img, &measured);
    let reference_ms = t0.elapsed().as_secs_f64() * 1e3;
    let (all, shadowed) = compare_pixels(&reference_tf, &map_tf);
    SkinReport {
        pixels: all.vertices,
        shadowed_pixels: shadowed.vertices,
        comparison: all,
        shadowed,
        map_tf,
        reference_tf,
        width,
        height,
        reference_ms,
    }
}

/// The map's T_f image against the reference's over the measured pixels (those where the
/// reference is not negative): all of them, and those the hair shadows noticeably (reference
/// T_f < 0.98).
fn compare_pixels(reference_tf: &[f32], map_tf: &[f32]) -> (Comparison, Comparison) {
    let as_light = |tf: f32| LightAtPoint {
        tf: Vec3::splat(tf),
        direct_fraction: tf,
        ..LightAtPoint::UNSHADOWED
    };
    let (mut truth, mut estimate, mut shadow_truth, mut shadow_estimate) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (&t, &e) in reference_tf.iter().zip(map_tf) {
        if t < 0.0 {
            continue;
        }
        truth.push(as_light(t));
        estimate.push(as_light(e));
        if t < 0.98 {
            shadow_truth.push(as_light(t));
            shadow_estimate.push(as_light(e));
        }
    }
    (
        Comparison::new(&truth, &estimate),
        Comparison::new(&shadow_truth, &shadow_estimate),
    )
}

/// The mean of R, G, B of each measured pixel; −1 elsewhere.
fn tf_image(fb: &Framebuffer, measured: &[bool]) -> Vec<f32> {
    fb.color
        .iter()
        .zip(measured)
        .map(|(c, &m)| if m { (c.x + c.y + c.z) / 3.0 } else { -1.0 })
        .collect()
}

impl SkinReport {
    /// Three grey images side by side, 8-bit RGB rows: the map's T_f, the reference's, and the
    /// difference (map − reference: red where the map is too light, blue where too dark, full
    /// at ±0.25); unmeasured pixels dark grey.
    pub fn side_by_side_rgb8(&self) -> (u32, u32, Vec<u8>) {
        let (w, h) = (self.width as usize, self.height as usize);
        let mut out = vec![0u8; 3 * w * 3 * h];
        let grey = |v: f32| (v.clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0).round() as u8;
        for y in 0..h {
            for x in 0..w {
                let i = y * w + x;
                let (m, r) = (self.map_tf[i], self.reference_tf[i]);
                let px = |panel: usize| (y * 3 * w + panel * w + x) * 3;
                if r < 0.0 {
                    for panel in 0..3 {
                        out[px(panel)..px(panel) + 3].copy_from_slice(&[40, 40, 40]);
                    }
                    continue;
                }
                out[px(0)..px(0) + 3].fill(grey(m));
                out[px(1)..px(1) + 3].fill(grey(r));
                let d = ((m - r) / 0.25).clamp(-1.0, 1.0);
                let fade = |s: f32| (255.0 * (1.0 - s)).round() as u8;
                let rgb = if d >= 0.0 {
                    [255, fade(d), fade(d)]
                } else {
                    [fade(-d), fade(-d), 255]
                };
                out[px(2)..px(2) + 3].copy_from_slice(&rgb);
            }
        }
        (3 * self.width, self.height, out)
    }
}
