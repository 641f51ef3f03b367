//! `wisp::export`: the cyHair file reads back as the frame's strands, the scene description
//! reads back and the EXR holds the framebuffer (the command, `wisp export`, in
//! `tests/cli/export.rs`).

use glam::{Affine3A, Vec3};
use std::path::Path;
use wisp::engine::{Engine, EngineConfig};
use wisp::export::{ReferenceScene, cyhair, write_reference_scene};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;
use wisp::output::read_exr_rgba_f32;

fn tmp(name: &str) -> std::path::PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn exported_scene_reads_back() {
    let dir = tmp("export-roundtrip");
    let config = {
        let mut config = EngineConfig::sized(96, 64);
        config.scene.background = Vec3::ZERO;
        config.scene.draw_solids = false;
        config
    };
    let mut e = Engine::new(
        Hairstyle::default_smooth(),
        Motion::still(Affine3A::IDENTITY),
        config,
    );
    e.frame(0.0);
    e.shade();
    let scene = write_reference_scene(&e, &dir, 0.0).unwrap();
    for f in [
        "hair.hair",
        "scene.json",
        "wisp.exr",
        "wisp.png",
        "vertex_rgb.f32",
    ] {
        assert!(dir.join(f).exists(), "{f}");
        assert!(
            !dir.join(format!("{f}.tmp")).exists(),
            "{f}.tmp left behind"
        );
    }

    // cyHair: every strand, root first, bit for bit; thickness = fibre diameter.
    let hair = cyhair::read_hair(&dir.join("hair.hair")).unwrap();
    let n = e.strands().points_per_strand;
    assert_eq!(hair.segments.len(), e.strands().strand_count());
    assert!(hair.segments.iter().all(|s| usize::from(*s) == n - 1));
    assert_eq!(hair.points, e.strands().positions);
    let d = 2.0 * e.style.fiber.radius_m;
    assert!(hair.thickness.iter().all(|t| *t == d));
    assert!(hair.info.contains("metres"));
    // Root first: each strand's first point is on the scalp (the still head's ellipsoid at the
    // origin), within the few millimetres the roots are layered by.
    let radii = glam::Vec3::from(e.style.head.radii_m);
    for s in hair.points.chunks(n) {
        let r = (s[0] / radii).length();
        assert!(
            (0.97..1.15).contains(&r),
            "root at {} of the head's radius",
            r
        );
    }

    // scene.json parses back into the same description.
    let text = std::fs::read_to_string(dir.join("scene.json")).unwrap();
    let back: ReferenceScene = serde_json::from_str(&text).unwrap();
    assert_eq!(back, scene);
    assert_eq!((back.image.width, back.image.height), (96, 64));
    assert_eq!(back.camera.eye, e.camera().eye.to_array());
    assert!((back.camera.fov_y_deg - 30.0).abs() < 1e-4);
    assert_eq!(back.fiber_model, "marschner");
    assert!(!back.draw_solids);
    assert_eq!(back.fibers_per_strand, 30.0);
    // MAPPING.md: beta_R 7.5 deg gives longitudinal roughness 0.276.
    assert!((back.mitsuba_hair_bsdf.longitudinal_roughness - 0.276).abs() < 1e-3);
    assert_eq!(back.mitsuba_hair_bsdf.ext_ior, 1.0);
    // The fibre parameters are written as the hairstyle has them (no f32 -> f64 noise).
    assert!(text.contains("\"eta\": 1.55"), "{text}");

    // The EXR is the framebuffer, colour and coverage, exactly.
    let (w, h, rgb, alpha) = read_exr_rgba_f32(&dir.join("wisp.exr")).unwrap();
    let fb = e.framebuffer();
    assert_eq!((w, h), (96, 64));
    assert_eq!(rgb, fb.color);
    assert_eq!(alpha, fb.coverage);

    // vertex_rgb.f32: the shaded colour of every point, in hair.hair's order, bit for bit.
    let bytes = std::fs::read(dir.join("vertex_rgb.f32")).unwrap();
    assert_eq!(bytes.len(), 12 * hair.points.len());
    let back: Vec<Vec3> = bytes
        .chunks_exact(12)
        .map(|c| {
            let f = |k: usize| f32::from_le_bytes(c[4 * k..4 * k + 4].try_into().unwrap());
            Vec3::new(f(0), f(1), f(2))
        })
        .collect();
    assert_eq!(back, e.colors());
    assert!(back.iter().any(|c| c.max_element() > 0.0), "all black");
}

#[test]
fn hair_writer_refuses_what_cyhair_cannot_hold() {
    let dir = tmp("export-bad-hair");
    let p = dir.join("a.hair");
    let pts = [Vec3::ZERO, Vec3::X, Vec3::Y];
    for (points, per, thick) in [
        (&pts[..], 2, 1.0),                     // not whole strands
        (&pts[..], 1, 1.0),                     // a strand needs 2 points
        (&[Vec3::ZERO, Vec3::NAN][..], 2, 1.0), // non-finite point
        (&pts[..2], 2, f32::NAN),               // bad thickness
    ] {
        let err = cyhair::write_hair(&p, points, per, thick, "").unwrap_err();
        assert!(err.to_string().contains("a.hair"), "{err}");
        assert!(!p.exists());
    }
    // Not a cyHair file, a truncated one, counts that do not add up: clear errors.
    std::fs::write(&p, b"HAIR").unwrap();
    assert!(cyhair::read_hair(&p).is_err());
    cyhair::write_hair(&p, &pts[..2], 2, 1e-4, "x").unwrap();
    let mut bytes = std::fs::read(&p).unwrap();
    bytes.truncate(bytes.len() - 3);
    std::fs::write(&p, &bytes).unwrap();
    let err = cyhair::read_hair(&p).unwrap_err().to_string();
    assert!(err.contains("header announces"), "{err}");
    bytes[8] = 9; // point_count 9 with one strand of 1 segment
    std::fs::write(&p, &bytes).unwrap();
    assert!(cyhair::read_hair(&p).is_err());
}
