//! A synthetic captured groom for benchmarks and examples: any number of strands in the units
//! and axes of a real capture (centimetres, Y-up), so import figures can be measured at sizes
//! no shared file has (50,000 strands).

use crate::input::strands::StrandFile;
use glam::Vec3;

/// `count` strands of `points` vertices (>= 2), rooted on the upper 60% of a 9 cm sphere
/// (a Fibonacci lattice), each falling down and back with a small side-to-side wave, kept
/// 2 mm outside the sphere.
pub fn synthetic_strands(count: usize, points: usize) -> StrandFile {
    let mut f = StrandFile::default();
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    for i in 0..count {
        let y = 1.0 - 1.2 * (i as f32 + 0.5) / count as f32;
        let r = (1.0 - y * y).max(0.0).sqrt();
        let a = golden * i as f32;
        let d = Vec3::new(r * a.sin(), y, r * a.cos());
        let mut p = d * 9.0;
        let mut dir = d;
        for k in 0..points {
            f.points.push(p);
            dir = (dir + Vec3::new(0.0, -0.35, -0.1)).normalize();
            let wave = Vec3::new((k as f32 * 0.9 + a).sin() * 0.2, 0.0, 0.0);
            p += dir * 1.5 + wave;
            if (p / 9.2).length() < 1.0 {
                p = p.normalize() * 9.2;
            }
        }
        f.strand_points.push(points as u32);
    }
    f
}
