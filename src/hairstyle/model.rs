//! The generated hair model: guides in their rest pose and the render-strand layout, all in the
//! head frame (metres). Produced by [`super::generate`] from a validated [`super::Hairstyle`].

use glam::Vec3;

/// Guide strands (3 per wisp), each a chain of `points_per_guide` particles joined by rigid links
/// of equal length. Storage is guide-major: point `i` of guide `g` is at `g * points_per_guide + i`.
#[derive(Clone, Debug)]
pub struct GuideSet {
    /// Particles per guide (links + 1), >= 2.
    pub points_per_guide: usize,
    /// Rest positions in the head frame, metres.
    pub rest: Vec<Vec3>,
    /// Link length of each guide in metres (all links of a guide are equal).
    pub link_length_m: Vec<f32>,
    /// Unit scalp normal at each guide's root, head frame.
    pub root_normal: Vec<Vec3>,
}

impl GuideSet {
    pub fn count(&self) -> usize {
        self.link_length_m.len()
    }
    /// The particles of guide `g`.
    pub fn guide(&self, g: usize) -> &[Vec3] {
        &self.rest[g * self.points_per_guide..(g + 1) * self.points_per_guide]
    }
}

/// How render strands are made from guides (Bertails 2005 §4.1: interpolated within a wisp).
#[derive(Clone, Debug)]
pub struct StrandLayout {
    /// The three guides of each wisp.
    pub wisp_guides: Vec<[u32; 3]>,
    /// Wisp of each render strand.
    pub strand_wisp: Vec<u32>,
    /// Barycentric weights of each render strand over its wisp's 3 guides (sum 1, each >= 0).
    pub strand_weights: Vec<[f32; 3]>,
    /// Curl phase of each render strand in radians.
    pub strand_phase: Vec<f32>,
    /// Length of each render strand as a fraction of its guides' (in (0, 1]).
    pub strand_length: Vec<f32>,
    /// The last fraction of each strand over which its fibres end one by one (in [0, 1]).
    pub tip_taper: f32,
    /// Smoothed points per render strand (Catmull-Rom output, drawn and filled), >= 2.
    pub points_per_strand: usize,
    /// Imported grooms only (empty for generated hair): each render strand's own departure
    /// from its wisp's interpolation, `points_per_strand` local offsets per strand, metres, in
    /// the frame of `crate::interp::apply_rest_offsets` (it turns with the guides).
    pub rest_offset: Vec<Vec3>,
}

impl StrandLayout {
    pub fn count(&self) -> usize {
        self.strand_wisp.len()
    }
    pub fn segments(&self) -> usize {
        self.count() * (self.points_per_strand - 1)
    }
}
