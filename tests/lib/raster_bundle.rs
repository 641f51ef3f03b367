//! Render strands drawn as their fibres (`src/raster/bundle.rs`): a line with a `Bundle` keeps
//! the coverage of its physical width (F fibres × 2r), shows its fibres where the bundle is
//! wide enough on screen, and meets itself at joints without a gap or a second layer; the
//! engine's close-ups draw them, the same bytes on 1 and 2 threads.

use crate::common;

use glam::{Affine3A, Vec2, Vec3};
use wisp::disc::bundle_disc_points;
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;
use wisp::raster::{
    Bundle, Camera, Framebuffer, LineScratch, LineStyle, Polylines, draw_polylines,
};
use wisp::scene::{CameraSetup, CameraSpec};

/// Eye at the origin looking down −Z, 90° vertical fov on 400 × 400: focal length 200 px.
fn camera() -> Camera {
    Camera::look_at(
        Vec3::ZERO,
        Vec3::NEG_Z,
        Vec3::Y,
        std::f32::consts::FRAC_PI_2,
        400,
        400,
    )
}

/// World point at depth 2 projecting to pixel (px, py): 100 px per metre... per 0.01 m.
fn at(px: f32, py: f32) -> Vec3 {
    let z = 2.0;
    Vec3::new((px - 200.0) / 200.0 * z, -(py - 200.0) / 200.0 * z, -z)
}

const FIBRES: u32 = 30;
/// Fibre radius over bundle radius (the smooth preset's is about 0.017).
const RHO: f32 = 0.02;

/// Draws the polyline through pixel points `pix` as a bundle of projected radius `r_px`
/// (fibres of radius RHO·r_px, their summed width 2·FIBRES·RHO·r_px), white over black.
fn draw(pix: &[(f32, f32)], r_px: f32, bundle: bool) -> Framebuffer {
    draw_rho(pix, r_px, RHO, bundle)
}

/// [`draw`] with fibres of radius `rho`·R.
fn draw_rho(pix: &[(f32, f32)], r_px: f32, rho: f32, bundle: bool) -> Framebuffer {
    draw_shares(pix, &vec![1.0; pix.len()], r_px, rho, bundle)
}

/// [`draw_rho`] with a share of the fibres left at each point (a tapered tip: its width is
/// that share of the full bundle's).
fn draw_shares(
    pix: &[(f32, f32)],
    shares: &[f32],
    r_px: f32,
    rho: f32,
    bundle: bool,
) -> Framebuffer {
    let cam = camera();
    let pts: Vec<Vec3> = pix.iter().map(|&(x, y)| at(x, y)).collect();
    let m_per_px = 2.0 / 200.0;
    let radius_m = r_px * m_per_px;
    let fiber_radius_m = rho * radius_m;
    let widths: Vec<f32> = shares
        .iter()
        .map(|s| s * FIBRES as f32 * 2.0 * fiber_radius_m)
        .collect();
    let cols = vec![Vec3::ONE; pts.len()];
    let disc = bundle_disc_points(FIBRES);
    let lines = Polylines {
        points: &pts,
        colors: &cols,
        widths_m: &widths,
        points_per_line: pts.len(),
        bundle: bundle.then_some(Bundle {
            radius_m,
            fiber_radius_m,
            points: &disc,
        }),
    };
    let mut fb = Framebuffer::new(400, 400, Vec3::ZERO);
    draw_polylines(
        &mut fb,
        &cam,
        &lines,
        &LineStyle::projected(1.0),
        &mut LineScratch::default(),
    );
    fb
}

fn total(fb: &Framebuffer) -> f64 {
    fb.coverage.iter().map(|a| f64::from(*a)).sum()
}

/// A straight bundle 300 px long covers 300 × its fibres' summed width, as the plain line of
/// that width does, while its fibres do not overlap on screen (the bundle up to a few pixels
/// across). The plain line's sub-samples count its width to 2/64 of a sixteenth per column
/// averaged over heights (`raster_coverage.rs`), so both are held to 1%. Wider, where fibres a pixel wide pile
/// up in the middle of the disc's projection, a pixel's coverage is capped at 1 (their union,
/// not their sum): the bundle then covers less than the opaque band, never more (measured:
/// 0.98 at R = 6 px, 0.83 at 25 px, where the band's 30 px of fibre lie in 50 px).
#[test]
fn a_bundle_covers_what_its_fibers_cover_at_every_scale() {
    for r_px in [0.2f32, 0.8, 2.0, 6.0, 25.0] {
        let w_px = f64::from(2.0 * FIBRES as f32 * RHO * r_px);
        let expected = 300.0 * w_px;
        // Averaged over 64 heights spanning the pixels' sub-sample period (a sixteenth), as
        // `raster_coverage.rs` does, so a plain band's count of sub-samples is exact to
        // 2/64 of one per column.
        let (mut bundle, mut plain) = (0.0, 0.0);
        let steps = 64;
        for k in 0..steps {
            let y = 200.3 + k as f32 / (16.0 * steps as f32);
            let line: Vec<(f32, f32)> = (0..11).map(|i| (50.0 + 30.0 * i as f32, y)).collect();
            bundle += total(&draw(&line, r_px, true)) / f64::from(steps);
            plain += total(&draw(&line, r_px, false)) / f64::from(steps);
        }
        assert!((plain - expected).abs() < 0.01 * expected, "plain {plain}");
        if r_px <= 2.0 {
            assert!(
                (bundle - expected).abs() < 0.01 * expected,
                "R {r_px} px: bundle covers {bundle}, fibres {expected}"
            );
        } else {
            assert!(
                bundle <= expected * 1.001 && bundle > 0.8 * expected,
                "R {r_px} px: bundle covers {bundle}, fibres {expected}"
            );
        }
    }
}

/// Toward a tapered tip the fibres left are the innermost: where a quarter of them are left
/// the bundle is drawn half as wide (√¼ of its radius), and its coverage is still the
/// width's (the fibres' summed width × length, to 1%).
#[test]
fn a_tapered_tip_narrows_the_bundle() {
    let pix: Vec<(f32, f32)> = (0..9).map(|i| (40.0 + 40.0 * i as f32, 200.0)).collect();
    let shares = [1.0, 1.0, 1.0, 1.0, 0.25, 0.25, 0.25, 0.25, 0.25];
    let r_px = 20.0;
    let rho = 0.005;
    let fb = draw_shares(&pix, &shares, r_px, rho, true);
    let spread = |x: usize| {
        let c = column(&fb, x);
        let first = c.iter().position(|a| *a > 0.0).unwrap();
        let last = c.iter().rposition(|a| *a > 0.0).unwrap();
        (last - first + 1) as f32
    };
    // Mid-segment columns: full share at x = 60, a quarter at x = 300.
    let (root, tip) = (spread(60), spread(300));
    assert!(root > 30.0, "{root}");
    assert!(
        (tip / root - 0.5).abs() < 0.15,
        "root {root} px, tip {tip} px"
    );
    let w_full = 2.0 * FIBRES as f32 * rho * r_px;
    // Segment k's width is the mean of its ends' shares.
    let expected: f32 = shares
        .windows(2)
        .map(|s| 40.0 * w_full * 0.5 * (s[0] + s[1]))
        .sum();
    let got = total(&fb) as f32;
    assert!(
        (got - expected).abs() < 0.01 * expected,
        "{got} vs {expected}"
    );
}

/// Coverage down one image column across a horizontal bundle.
fn column(fb: &Framebuffer, x: usize) -> Vec<f32> {
    (0..400).map(|y| fb.coverage[y * 400 + x]).collect()
}

/// Where the bundle is 50 px across, its 30 fibres (0.5 px wide each) show as separate
/// stripes: the profile across has many peaks and near-empty gaps, where the plain line of
/// the same coverage is one flat band 15 px wide.
#[test]
fn a_wide_bundle_shows_its_fibers() {
    let line: Vec<(f32, f32)> = (0..5).map(|i| (50.0 + 75.0 * i as f32, 200.0)).collect();
    let bundle = column(&draw_rho(&line, 25.0, 0.01, true), 200);
    let plain = column(&draw_rho(&line, 25.0, 0.01, false), 200);
    let peaks = |c: &[f32]| {
        (1..c.len() - 1)
            .filter(|&i| c[i] > 0.05 && c[i] > c[i - 1] && c[i] >= c[i + 1])
            .count()
    };
    let covered = |c: &[f32]| c.iter().filter(|a| **a > 0.0).count();
    assert!(
        peaks(&bundle) >= 12,
        "{} stripes: {bundle:?}",
        peaks(&bundle)
    );
    assert!(peaks(&plain) <= 1);
    // Spread over the bundle's 50 px, not the band's 15, with gaps between fibres inside it.
    assert!(covered(&bundle) > 34 && covered(&plain) <= 17);
    let first = bundle.iter().position(|a| *a > 0.0).unwrap();
    let last = bundle.iter().rposition(|a| *a > 0.0).unwrap();
    let gaps = bundle[first..=last].iter().filter(|a| **a < 0.05).count();
    assert!(gaps >= 3, "{gaps} gaps: {bundle:?}");
    assert!(plain.iter().filter(|a| **a > 0.99).count() >= 14);
}

/// A bundle bent by 40° at a joint: its two segments are cut on the joint's bisector, so the
/// outer side has no notch and the inner side no second layer. Measured as coverage: the bent
/// bundle covers what the same bundle drawn straight over the same length covers (the mitre
/// adds on the outside what it takes on the inside), and no pixel is covered more than the
/// pixels of its two arms drawn alone (a second layer over a stripe would be).
/// At a 70° turn, past the mitre limit, the joint is cut square and the second layer shows
/// (measured: 0.72 against the arms' 0.60), which is what the check is able to see.
#[test]
fn a_bent_bundle_meets_itself_on_the_mitre() {
    // Fibres a fifth of a pixel wide, so no pixel's coverage reaches its cap of 1.
    let (r_px, rho) = (20.0f32, 0.005);
    let straight = draw_rho(
        &[(60.0, 200.0), (200.0, 200.0), (340.0, 200.0)],
        r_px,
        rho,
        true,
    );
    let max_of = |fb: &Framebuffer| fb.coverage.iter().copied().fold(0.0f32, f32::max);
    let arm = 140.0f32;
    let bent = |turn_deg: f32| {
        let d = Vec2::from_angle(turn_deg.to_radians()) * arm;
        draw_rho(
            &[(60.0, 200.0), (200.0, 200.0), (200.0 + d.x, 200.0 + d.y)],
            r_px,
            rho,
            true,
        )
    };
    let arms_max = |turn_deg: f32| {
        let d = Vec2::from_angle(turn_deg.to_radians()) * arm;
        let first = draw_rho(&[(60.0, 200.0), (200.0, 200.0)], r_px, rho, true);
        let second = draw_rho(
            &[(200.0, 200.0), (200.0 + d.x, 200.0 + d.y)],
            r_px,
            rho,
            true,
        );
        max_of(&first).max(max_of(&second))
    };
    let mitred = bent(40.0);
    let expected = total(&straight) * f64::from(2.0 * arm) / 280.0;
    let got = total(&mitred);
    assert!(
        (got - expected).abs() < 0.02 * expected,
        "bent 40°: {got} vs {expected}"
    );
    let (max40, arms40) = (max_of(&mitred), arms_max(40.0));
    eprintln!("max 40°: bent {max40}, arms {arms40}");
    assert!(max40 <= arms40 * 1.001, "{max40} vs {arms40}");
    let (max70, arms70) = (max_of(&bent(70.0)), arms_max(70.0));
    eprintln!("max 70°: bent {max70}, arms {arms70}");
    assert!(max70 > arms70 * 1.1, "{max70} vs {arms70}");
}

/// A close-up of the smooth preset's crown (still head, 128 × 128, 6° field of view about
/// 0.4 m away, 0.35 mm a pixel: the bundles, 2.3 mm in radius, about 6 px), the engine's
/// whole frame. `tests/golden/closeup_fibres_128.png`
/// was written by this test when strands started to be drawn as their fibres; it shows thin
/// stripes where the frames before showed opaque ribbons with notched joints. Tolerance 2
/// levels (a libm that rounds a transcendental differently elsewhere); on failure a diff
/// image is written; `WISP_UPDATE_GOLDEN=1` rewrites it after a deliberate change. The same
/// frame is byte-identical on 1 and 2 threads.
#[test]
fn a_close_up_draws_the_fibers_the_same_on_any_thread_count() {
    let config = {
        let mut config = EngineConfig::sized(128, 128);
        config.scene.camera = CameraSetup::Fixed(
            CameraSpec::new(
                Vec3::new(0.2, 0.25, 0.4),
                Vec3::new(0.02, 0.08, 0.05),
                Vec3::Y,
                6f32.to_radians(),
            )
            .unwrap(),
        );
        config
    };
    let frame = |threads| {
        common::on_threads(threads, || {
            let mut e = Engine::new(
                Hairstyle::default_smooth(),
                Motion::still(Affine3A::IDENTITY),
                config.clone(),
            );
            e.frame(0.0).to_srgb8()
        })
    };
    let one = frame(1);
    assert!(one == frame(2), "1 and 2 threads differ");
    common::golden::assert_golden("closeup_fibres_128.png", 128, 128, &one, 2);
}

/// Hostile input with bundles: points at NaN, infinity, behind the eye or beside it, widths of
/// every sign and size, bundles of NaN, zero, huge or fibre-sized radius, and a joint turned
/// back on itself. Nothing panics, and every pixel stays finite within [0, 1].
#[test]
fn hostile_bundles_never_panic_and_stay_within_the_unit_range() {
    let cam = camera();
    let good = at(200.0, 200.0);
    let near = at(210.0, 230.0);
    let nasty = [
        Vec3::NAN,
        Vec3::new(f32::INFINITY, 0.0, -1.0),
        Vec3::new(1e30, -1e30, -1.0),
        Vec3::new(0.0, 0.0, 5.0),   // behind the eye
        Vec3::new(0.0, 0.0, -1e-4), // nearer than the near plane
        Vec3::new(1e-3, 0.0, 0.0),  // beside the eye
        good,                       // a zero-length segment with the middle point
        near,                       // back where the line came from: a 180° joint
    ];
    let disc = bundle_disc_points(FIBRES);
    let one = [Vec2::ZERO];
    let nan_points = [Vec2::NAN, Vec2::ONE];
    let mut scratch = LineScratch::default();
    for a in nasty {
        for c in nasty {
            let pts = [a, near, good, c];
            let cols = [Vec3::ONE; 4];
            for width_m in [0.02f32, 0.0, -1.0, f32::NAN, 1e9, f32::INFINITY] {
                let widths = [width_m; 4];
                // At depth 2 on the 48-row image (focal 24 px) a 0.5 m bundle is 6 px in
                // radius: drawn as its fibres.
                for (radius_m, fiber_radius_m, points) in [
                    (0.5f32, 0.01f32, &disc[..]),
                    (0.3, 0.006, &disc[..]),
                    (f32::NAN, 0.01, &disc[..]),
                    (0.0, 0.01, &disc[..]),
                    (1e30, 1e-30, &disc[..]),
                    (0.5, 0.5, &disc[..]),
                    (0.5, 0.01, &one[..]),
                    (0.5, 0.01, &nan_points[..]),
                ] {
                    let lines = Polylines {
                        points: &pts,
                        colors: &cols,
                        widths_m: &widths,
                        points_per_line: 4,
                        bundle: Some(Bundle {
                            radius_m,
                            fiber_radius_m,
                            points,
                        }),
                    };
                    let mut fb = Framebuffer::new(64, 48, Vec3::ZERO);
                    draw_polylines(
                        &mut fb,
                        &cam,
                        &lines,
                        &LineStyle::projected(1.0),
                        &mut scratch,
                    );
                    assert!(fb.color.iter().all(|c| c.is_finite()
                        && c.min_element() >= 0.0
                        && c.max_element() <= 1.0 + 1e-6));
                    assert!(fb.coverage.iter().all(|a| (0.0..=1.0 + 1e-6).contains(a)));
                }
            }
        }
    }
}
