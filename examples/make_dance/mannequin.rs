//! A low-poly skinned mannequin for the dance's skeleton: ellipsoid head, lofted neck, torso,
//! arms and legs, each vertex weighted to one or two joints (blended across every joint, so
//! elbows, knees, the waist and the neck bend smoothly).
//!
//! The head is the smooth preset's head ellipsoid (0.076, 0.098, 0.094 m) scaled by 1.0135 so
//! that its radii have a geometric mean of exactly 0.09 m, centred 0.09 m above the `Head`
//! joint: wisp's automatic fit then reads scale 1 and the same head centre from the mesh as it
//! did from the `HeadTop_End` bone. Its vertices weigh on `Head` alone, and the neck's top
//! ring leans 55/45 toward `Neck`, so the head box the fit measures is the ellipsoid's.
//!
//! Materials (linear base colours): skin (the renderer's former head colour), a dark blue
//! shirt (its former body-sphere colour), grey trousers, dark shoes.

use glam::Vec3;

/// Skin, shirt, trousers, shoes (linear RGB).
pub const MATERIALS: [(&str, [f32; 3]); 4] = [
    ("Skin", [0.55, 0.38, 0.30]),
    ("Shirt", [0.10, 0.14, 0.22]),
    ("Trousers", [0.16, 0.16, 0.17]),
    ("Shoes", [0.05, 0.04, 0.04]),
];

/// Up to two joint influences of a vertex: (joint index, weight).
type Influence = [(usize, f32); 2];

fn only(j: usize) -> Influence {
    [(j, 1.0), (j, 0.0)]
}

fn blend(a: usize, b: usize, t: f32) -> Influence {
    let t = t.clamp(0.0, 1.0);
    [(a, 1.0 - t), (b, t)]
}

/// The mesh, one triangle list per material.
pub struct MeshData {
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    /// Joint indices and weights (normalised to bytes summing to 255).
    pub joints: Vec<[u8; 4]>,
    pub weights: Vec<[u8; 4]>,
    /// Per material: triangle indices.
    pub indices: Vec<Vec<u16>>,
}

#[derive(Default)]
struct Part {
    p: Vec<Vec3>,
    w: Vec<Influence>,
    tris: Vec<[u32; 3]>,
}

impl Part {
    /// A tube through `rings` (centre, radius across `u`, radius across `v`, influence) along
    /// the direction `d` from first to last ring, `segs` vertices per ring, closed at both ends.
    /// `u` ⟂ `d` and `v = u × d`, so the triangles wind counter-clockwise seen from outside.
    fn tube(&mut self, rings: &[(Vec3, f32, f32, Influence)], u: Vec3, segs: usize) {
        let d = (rings[rings.len() - 1].0 - rings[0].0).normalize();
        let u = (u - d * u.dot(d)).normalize();
        let v = u.cross(d);
        let base = self.p.len() as u32;
        for &(c, ru, rv, w) in rings {
            for k in 0..segs {
                let a = std::f32::consts::TAU * k as f32 / segs as f32;
                self.p.push(c + u * (ru * a.cos()) + v * (rv * a.sin()));
                self.w.push(w);
            }
        }
        let at = |i: usize, k: usize| base + (i * segs + k % segs) as u32;
        for i in 0..rings.len() - 1 {
            for k in 0..segs {
                self.tris.push([at(i, k), at(i + 1, k), at(i, k + 1)]);
                self.tris
                    .push([at(i, k + 1), at(i + 1, k), at(i + 1, k + 1)]);
            }
        }
        // End caps: a centre vertex each, fanned.
        let (first, last) = (&rings[0], &rings[rings.len() - 1]);
        let c0 = self.p.len() as u32;
        self.p.push(first.0);
        self.w.push(first.3);
        let c1 = c0 + 1;
        self.p.push(last.0);
        self.w.push(last.3);
        let n = rings.len() - 1;
        for k in 0..segs {
            self.tris.push([c0, at(0, k), at(0, k + 1)]);
            self.tris.push([c1, at(n, k + 1), at(n, k)]);
        }
    }

    /// An ellipsoid: `rings` latitude rings between the poles (odd, so one is the equator),
    /// `segs` (a multiple of 4) longitudes, so the extreme points along each axis are vertices.
    fn ellipsoid(&mut self, c: Vec3, r: Vec3, rings: usize, segs: usize, w: Influence) {
        let lat: Vec<(Vec3, f32, f32, Influence)> = (0..rings)
            .map(|j| {
                let t = -std::f32::consts::FRAC_PI_2
                    + std::f32::consts::PI * (j + 1) as f32 / (rings + 1) as f32;
                (
                    c + Vec3::Y * (r.y * t.sin()),
                    r.x * t.cos(),
                    r.z * t.cos(),
                    w,
                )
            })
            .collect();
        let base = self.p.len();
        self.tube(&lat, Vec3::X, segs);
        // The caps' centres become the poles.
        let n = self.p.len();
        self.p[n - 2] = c - Vec3::Y * r.y;
        self.p[n - 1] = c + Vec3::Y * r.y;
        debug_assert!(n > base);
    }
}

/// Builds the mannequin for joints at rest world positions `at(name)` with indices `ix(name)`.
pub fn build(at: impl Fn(&str) -> Vec3, ix: impl Fn(&str) -> usize) -> MeshData {
    let mut parts: Vec<(usize, Part)> = Vec::new();
    let (skin, shirt, trousers, shoes) = (0, 1, 2, 3);
    let (hips, spine, chest, neck, head) =
        (ix("Hips"), ix("Spine"), ix("Chest"), ix("Neck"), ix("Head"));

    // Head: the preset ellipsoid scaled to a 0.09 m geometric mean, 0.09 m above the joint.
    let k = 0.09 / (0.076f32 * 0.098 * 0.094).cbrt();
    let mut p = Part::default();
    p.ellipsoid(
        at("Head") + Vec3::Y * 0.09,
        Vec3::new(0.076, 0.098, 0.094) * k,
        15,
        24,
        only(head),
    );
    parts.push((skin, p));

    // Neck: from inside the chest to inside the head.
    let y_neck = at("Neck").y;
    let mut p = Part::default();
    p.tube(
        &[
            (
                Vec3::new(0.0, y_neck - 0.06, -0.01),
                0.058,
                0.055,
                blend(chest, neck, 0.5),
            ),
            (
                Vec3::new(0.0, y_neck + 0.03, -0.005),
                0.053,
                0.05,
                only(neck),
            ),
            (
                Vec3::new(0.0, y_neck + 0.11, 0.0),
                0.05,
                0.048,
                blend(neck, head, 0.45),
            ),
            (
                Vec3::new(0.0, y_neck + 0.15, 0.005),
                0.045,
                0.043,
                blend(neck, head, 0.45),
            ),
        ],
        Vec3::X,
        16,
    );
    parts.push((skin, p));

    // Torso: elliptic sections from the hips to the base of the neck.
    let torso: [(f32, f32, f32); 12] = [
        (0.86, 0.14, 0.095),
        (0.92, 0.165, 0.105),
        (0.99, 0.165, 0.105),
        (1.06, 0.145, 0.095),
        (1.12, 0.145, 0.098),
        (1.19, 0.158, 0.108),
        (1.26, 0.165, 0.112),
        (1.33, 0.17, 0.108),
        (1.39, 0.172, 0.098),
        (1.43, 0.15, 0.085),
        (1.47, 0.10, 0.068),
        (1.50, 0.062, 0.056),
    ];
    let (y_spine, y_chest) = (at("Spine").y, at("Chest").y);
    let rings: Vec<_> = torso
        .iter()
        .map(|&(y, rx, rz)| {
            let w = if y < y_spine {
                blend(hips, spine, (y - (y_spine - 0.1)) / 0.1)
            } else {
                blend(spine, chest, (y - y_spine) / (y_chest - y_spine))
            };
            (Vec3::new(0.0, y, 0.0), rx, rz, w)
        })
        .collect();
    let mut p = Part::default();
    p.tube(&rings, Vec3::X, 24);
    parts.push((shirt, p));

    for side in ["L", "R"] {
        let j = |n: &str| format!("{n}.{side}");
        let (sh, ua, la, hand) = (
            ix(&j("Shoulder")),
            ix(&j("UpperArm")),
            ix(&j("LowerArm")),
            ix(&j("Hand")),
        );
        let (a0, a1, a2) = (at(&j("UpperArm")), at(&j("LowerArm")), at(&j("Hand")));
        // Arm: shoulder cap, upper arm, elbow, forearm, wrist.
        let mut p = Part::default();
        p.tube(
            &[
                (
                    a0 + Vec3::new(-0.02, 0.025, 0.0),
                    0.03,
                    0.03,
                    blend(sh, ua, 0.6),
                ),
                (a0 + Vec3::Y * 0.005, 0.05, 0.048, blend(sh, ua, 0.8)),
                (a0.lerp(a1, 0.15), 0.052, 0.052, only(ua)),
                (a0.lerp(a1, 0.6), 0.045, 0.045, only(ua)),
                (a1, 0.04, 0.04, blend(ua, la, 0.5)),
                (a1.lerp(a2, 0.3), 0.04, 0.038, only(la)),
                (a1.lerp(a2, 0.9), 0.031, 0.028, blend(la, hand, 0.2)),
                (a2, 0.03, 0.026, blend(la, hand, 0.5)),
            ],
            Vec3::X,
            14,
        );
        parts.push((shirt, p));
        // Hand: a flat mitten.
        let tip = a2 + (a2 - a1).normalize() * 0.18;
        let mut p = Part::default();
        p.tube(
            &[
                (a2, 0.028, 0.022, blend(la, hand, 0.6)),
                (a2.lerp(tip, 0.35), 0.045, 0.018, only(hand)),
                (a2.lerp(tip, 0.8), 0.04, 0.015, only(hand)),
                (tip, 0.02, 0.01, only(hand)),
            ],
            Vec3::Z,
            12,
        );
        parts.push((skin, p));

        let (ul, ll, foot) = (ix(&j("UpperLeg")), ix(&j("LowerLeg")), ix(&j("Foot")));
        let (h0, h1, h2) = (at(&j("UpperLeg")), at(&j("LowerLeg")), at(&j("Foot")));
        let mut p = Part::default();
        p.tube(
            &[
                (h0 + Vec3::Y * 0.06, 0.06, 0.06, blend(hips, ul, 0.5)),
                (h0, 0.082, 0.085, blend(hips, ul, 0.8)),
                (h0.lerp(h1, 0.4), 0.07, 0.072, only(ul)),
                (h1, 0.052, 0.055, blend(ul, ll, 0.5)),
                (h1.lerp(h2, 0.3), 0.052, 0.055, only(ll)),
                (h1.lerp(h2, 0.85), 0.036, 0.038, only(ll)),
                (h2, 0.034, 0.036, blend(ll, foot, 0.5)),
            ],
            Vec3::X,
            14,
        );
        parts.push((trousers, p));
        // Foot: from the heel to the toes, along +Z.
        let mut p = Part::default();
        let heel = Vec3::new(h2.x, 0.045, h2.z - 0.05);
        p.tube(
            &[
                (heel, 0.035, 0.04, only(foot)),
                (heel + Vec3::new(0.0, 0.0, 0.07), 0.045, 0.045, only(foot)),
                (heel + Vec3::new(0.0, -0.01, 0.17), 0.045, 0.03, only(foot)),
                (heel + Vec3::new(0.0, -0.015, 0.23), 0.03, 0.02, only(foot)),
            ],
            Vec3::X,
            12,
        );
        parts.push((shoes, p));
    }

    let mut out = MeshData {
        positions: Vec::new(),
        normals: Vec::new(),
        joints: Vec::new(),
        weights: Vec::new(),
        indices: vec![Vec::new(); MATERIALS.len()],
    };
    for (material, part) in parts {
        let base = out.positions.len() as u32;
        // Smooth normals: area-weighted face normals of the part.
        let mut n = vec![Vec3::ZERO; part.p.len()];
        for t in &part.tris {
            let [a, b, c] = t.map(|i| part.p[i as usize]);
            let f = (b - a).cross(c - a);
            for &i in t {
                n[i as usize] += f;
            }
        }
        out.positions.extend(&part.p);
        out.normals
            .extend(n.iter().map(|v| v.normalize_or(Vec3::Y)));
        for w in &part.w {
            let a = (w[0].1 * 255.0).round().clamp(0.0, 255.0) as u8;
            out.joints.push([w[0].0 as u8, w[1].0 as u8, 0, 0]);
            out.weights.push([a, 255 - a, 0, 0]);
        }
        out.indices[material].extend(
            part.tris.iter().flat_map(|t| {
                t.map(|i| u16::try_from(i + base).expect("fewer than 65536 vertices"))
            }),
        );
    }
    out
}
