//! The head a partial groom was made on, from its own roots: the sphere through them.
//!
//! A full scalp's roots pin the fit of [`super::fit`] down (a cap of the head in every
//! direction), but a mohawk's roots lie along one strip and bangs along one line: the fit can
//! then shrink the groom towards a point on the ellipsoid, where every root lies on the
//! surface and the cost is zero (a TressFX mohawk came out with its longest strand 0.00 m
//! long). The roots still lie on the head they were authored on, so a sphere through them
//! gives that head's centre and radius in the file's units, and with them the scale and
//! offset that put it on wisp's head.
//!
//! The sphere is the algebraic least-squares fit `|p|² = 2c·p + k` (radius² = k + |c|²),
//! linear in (c, k), on the roots taken relative to their centroid. Roots along a curve leave
//! the centre free along a line (the curve's axis): a small ridge on |c| picks the point of
//! that line nearest the roots' centroid, which is the centre of the curve's circle, the
//! smallest sphere through it. On a strip over the top of the head (a great circle) that is
//! the head's own centre. A groom whose roots form such a strip or line ([`is_strip`]) is
//! placed by this sphere; others by the fit onto the head, which knows the head's shape.

use glam::DVec3;

/// Ridge on the centre, relative to the mean squared distance of the roots from their
/// centroid: small enough to leave a well-determined centre where it is (1e-6 moves a full
/// scalp's centre by a millionth of its radius), large enough to fix the free direction.
const RIDGE: f64 = 1e-6;
/// Largest RMS distance of the roots from the sphere, as a share of its radius: a scalp's
/// roots lie within millimetres of a sphere a tenth of a metre wide.
const MAX_RMS_SHARE: f64 = 0.05;
/// See [`is_strip`].
pub const STRIP_ASPECT: f64 = 0.25;

/// Centre and radius (file units) of the sphere through `roots`, `None` for fewer than 3
/// distinct roots or a fit that is not finite (all roots on one line).
pub fn sphere_through(roots: &[DVec3]) -> Option<(DVec3, f64)> {
    if roots.len() < 3 {
        return None;
    }
    let mean = roots.iter().copied().sum::<DVec3>() / roots.len() as f64;
    let spread = roots
        .iter()
        .map(|p| (*p - mean).length_squared())
        .sum::<f64>()
        / roots.len() as f64;
    if !(spread > 0.0 && spread.is_finite()) {
        return None;
    }
    // Normal equations of rows [2x, 2y, 2z, 1] · (c, k) = |p|², points scaled to unit spread.
    let unit = spread.sqrt();
    let mut a = [[0.0f64; 4]; 4];
    let mut b = [0.0f64; 4];
    for p in roots {
        let q = (*p - mean) / unit;
        let row = [2.0 * q.x, 2.0 * q.y, 2.0 * q.z, 1.0];
        let rhs = q.length_squared();
        for u in 0..4 {
            b[u] += row[u] * rhs;
            for v in 0..4 {
                a[u][v] += row[u] * row[v];
            }
        }
    }
    let n = roots.len() as f64;
    for (u, row) in a.iter_mut().enumerate().take(3) {
        row[u] += RIDGE * 4.0 * n;
    }
    let x = super::fit::solve4(a, b)?;
    let c = DVec3::new(x[0], x[1], x[2]);
    let r2 = x[3] + c.length_squared();
    if !(r2 > 0.0 && r2.is_finite()) {
        return None;
    }
    let (centre, radius) = (mean + c * unit, r2.sqrt() * unit);
    // Roots that no sphere passes through (a straight line) leave the fit far from them.
    let rms = (roots
        .iter()
        .map(|p| (p.distance(centre) - radius).powi(2))
        .sum::<f64>()
        / n)
        .sqrt();
    (rms <= MAX_RMS_SHARE * radius).then_some((centre, radius))
}

/// Whether `roots` cover a strip or a line of the sphere about `centre` rather than a patch:
/// their directions from the centre, in the tangent plane at their mean direction, spread
/// less than [`STRIP_ASPECT`] as much across as along (standard deviations). Measured: the
/// generated mohawk (3 rows over 140°, `tests/lib/groom_partial.rs`) 0.15, one row of bangs
/// near 0; the shared TressFX ponytail's parts: front and top 0.33, back 0.91, the ring of
/// roots at the tail's tie 0.81.
pub fn is_strip(roots: &[DVec3], centre: DVec3) -> bool {
    let dirs: Vec<DVec3> = roots
        .iter()
        .map(|p| (*p - centre).normalize_or_zero())
        .collect();
    let Some(m) = dirs.iter().copied().sum::<DVec3>().try_normalize() else {
        return false;
    };
    let t1 = m.any_orthonormal_vector();
    let t2 = m.cross(t1);
    let (mut sxx, mut sxy, mut syy, mut sx, mut sy) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for d in &dirs {
        let (x, y) = (d.dot(t1), d.dot(t2));
        (sx, sy) = (sx + x, sy + y);
        (sxx, sxy, syy) = (sxx + x * x, sxy + x * y, syy + y * y);
    }
    let n = dirs.len() as f64;
    let (cxx, cxy, cyy) = (
        sxx / n - (sx / n).powi(2),
        sxy / n - sx * sy / (n * n),
        syy / n - (sy / n).powi(2),
    );
    // Eigenvalues of the 2×2 covariance.
    let half_trace = 0.5 * (cxx + cyy);
    let root = (0.25 * (cxx - cyy).powi(2) + cxy * cxy).sqrt();
    let (major, minor) = (half_trace + root, (half_trace - root).max(0.0));
    major > 0.0 && (minor / major).sqrt() < STRIP_ASPECT
}

#[cfg(test)]
mod tests {
    use super::*;

    fn on_sphere(centre: DVec3, r: f64, dirs: impl Iterator<Item = DVec3>) -> Vec<DVec3> {
        dirs.map(|d| centre + r * d.normalize()).collect()
    }

    #[test]
    fn a_cap_of_roots_gives_its_sphere() {
        // 200 roots on the upper half of a sphere of radius 11 at (3, −2, 5).
        let dirs = (0..200).map(|i| {
            let a = i as f64 * 2.399_963;
            let y = 1.0 - i as f64 / 200.0;
            let r = (1.0 - y * y).sqrt();
            DVec3::new(r * a.cos(), y, r * a.sin())
        });
        let roots = on_sphere(DVec3::new(3.0, -2.0, 5.0), 11.0, dirs);
        let (c, r) = sphere_through(&roots).expect("fits");
        assert!((c - DVec3::new(3.0, -2.0, 5.0)).length() < 1e-4, "{c}");
        assert!((r - 11.0).abs() < 1e-4, "{r}");
    }

    #[test]
    fn a_strip_along_a_great_circle_gives_the_head_it_was_on() {
        // A mohawk: roots 1 unit either side of the midline, over 150° of a radius-9 head.
        let dirs = (0..300).map(|i| {
            let t = (i / 3) as f64 / 100.0 * 150f64.to_radians() - 75f64.to_radians();
            let side = (i % 3) as f64 - 1.0;
            DVec3::new(side / 9.0, t.cos(), t.sin())
        });
        let roots = on_sphere(DVec3::new(0.0, 150.0, 0.0), 9.0, dirs);
        let (c, r) = sphere_through(&roots).expect("fits");
        assert!((c - DVec3::new(0.0, 150.0, 0.0)).length() < 0.05, "{c}");
        assert!((r - 9.0).abs() < 0.05, "{r}");
    }

    #[test]
    fn roots_on_a_line_or_in_one_point_have_no_sphere() {
        let line: Vec<DVec3> = (0..10).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect();
        assert!(sphere_through(&line).is_none());
        assert!(sphere_through(&[DVec3::ONE; 5]).is_none());
        assert!(sphere_through(&[DVec3::ONE, DVec3::ZERO]).is_none());
    }
}
