//! The raster pass: the framebuffer and what draws into it (`crate::raster`). The solids come
//! first (the character's mesh, or the head ellipsoid and body spheres, lit through each
//! light's shadows); then a first pass over the hair finds the points the raster can draw,
//! past the solids and nearer hair at every pixel (`raster::seen_points`: four fifths of the
//! dance's points at 1280 × 720 are not), so only those are shaded; then the kept fragments
//! are composited with their colours. Frames are the bytes of shading every point.
//!
//! Each render strand is drawn as a line of its physical width: its F fibres of radius r side
//! by side (F·2r, the most they can cover), thinning where its fibres end; with F ≥ 2 as a
//! bundle whose fibres spread over half the strand spacing, drawn as its fibres where the
//! bundle is wide on screen.

use super::sizes::RunSizes;
use crate::budget::{MemoryPart, grouped};
use crate::hairstyle::Hairstyle;
use crate::interp::StrandGeometry;
use crate::map::Solid;
use crate::motion::{Character, CharacterPose};
use crate::raster::{
    Bundle, Camera, Framebuffer, LineScratch, LineStyle, LineWidth, MAX_WIDTH_PX, Mesh,
    MeshScratch, Polylines, Surface, Texture, draw_ellipsoid, draw_mesh, seen_points,
};
#[cfg(doc)]
use crate::raster::{draw_polylines, draw_seen_polylines};
use crate::scene::Scene;
use glam::{Vec2, Vec3};

/// How the hair is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RasterConfig {
    /// The hair's lines: by default each render strand's physical width (fibres per strand ×
    /// fibre diameter) projected per segment, at least [`DEFAULT_MIN_LINE_WIDTH_PX`] wide with
    /// its opacity lowered to conserve coverage.
    pub line: LineStyle,
}

/// Narrowest drawn hair line in pixels; thinner strands are drawn this wide at lower opacity.
/// Half a pixel: eight of a pixel's 16 sub-samples across, so a thin line's coverage moves in
/// steps of an eighth of its α as it slides, and fibres side by side hide what is behind them
/// nearly as their summed width does. At 1 px each fibre covered a whole pixel row at a
/// fraction of the opacity, so neighbours overlapped as independent layers: side-lit dense
/// single scattering reads 0.91 of the path tracer at 1 px, 0.92 at 0.5 px and at 0.25 px
/// (ACCURACY.md).
pub const DEFAULT_MIN_LINE_WIDTH_PX: f32 = 0.5;

impl RasterConfig {
    /// The narrowest a hair line is drawn, pixels: the width model's minimum (or its fixed
    /// width), at most [`MAX_WIDTH_PX`]; what the memory budget sizes the line raster by.
    pub fn narrowest_drawn_px(&self) -> f32 {
        let px = match self.line.width {
            LineWidth::Pixels(w) => w,
            LineWidth::Projected { min_px } => min_px,
        };
        if px > 0.0 { px.min(MAX_WIDTH_PX) } else { 0.0 }
    }
}

impl Default for RasterConfig {
    fn default() -> Self {
        Self {
            line: LineStyle::projected(DEFAULT_MIN_LINE_WIDTH_PX),
        }
    }
}

/// The solids to draw: the head and body solids with their albedos, and the character.
#[derive(Clone, Copy)]
pub struct SolidsToDraw<'a> {
    pub solids: &'a [Solid],
    pub albedo: &'a [Vec3],
    pub character: Option<(&'a Character, &'a CharacterPose)>,
}

/// The hair to draw: its render strands and their colours.
#[derive(Clone, Copy)]
pub struct HairToDraw<'a> {
    pub strands: &'a StrandGeometry,
    pub colors: &'a [Vec3],
}

/// A hair line draw: [`draw_polylines`] or [`draw_seen_polylines`].
pub type DrawLines = fn(&mut Framebuffer, &Camera, &Polylines, &LineStyle, &mut LineScratch);

/// The framebuffer and the raster's reusable buffers.
pub struct RasterPass {
    pub config: RasterConfig,
    fb: Framebuffer,
    lines: LineScratch,
    mesh: MeshScratch,
    /// Physical width of each render-strand point in metres.
    widths_m: Vec<f32>,
    /// Per render-strand point: whether the raster can draw its colour this frame.
    seen: Vec<bool>,
    /// How a render strand's fibres lie across it (`None` for one fibre per strand).
    bundle: Option<BundleShape>,
    /// The width of a render strand (its fibres side by side), metres.
    strand_width_m: f32,
    /// How the character's triangles look (from its materials), and its textures.
    surfaces: Vec<Surface>,
    textures: Vec<Texture>,
}

impl RasterPass {
    /// A framebuffer of the scene's size, for `style`'s hair and `character`'s look.
    pub fn new(
        config: RasterConfig,
        scene: &Scene,
        style: &Hairstyle,
        character: Option<&Character>,
    ) -> Self {
        let fibers = style.strands.fibers_per_strand.round();
        let bundle = (fibers >= 2.0).then(|| BundleShape {
            points: crate::disc::bundle_disc_points(fibers.min(256.0) as u32),
            radius_m: 0.5 * style.strand_spacing_m(),
            fiber_radius_m: style.fiber.radius_m,
        });
        let (surfaces, textures) = character.map_or((Vec::new(), Vec::new()), look_of);
        Self {
            config,
            fb: Framebuffer::new(scene.width, scene.height, scene.background),
            lines: LineScratch::default(),
            mesh: MeshScratch::default(),
            widths_m: Vec::new(),
            seen: Vec::new(),
            bundle,
            strand_width_m: style.strands.fibers_per_strand * 2.0 * style.fiber.radius_m,
            surfaces,
            textures,
        }
    }

    /// Clears the image to the scene's background and draws the solids when the scene draws
    /// them, shaded by `skin(p, n, albedo)` (world point, unit normal, albedo → linear RGB).
    pub fn draw_solids(
        &mut self,
        scene: &Scene,
        camera: &Camera,
        solids: SolidsToDraw,
        skin: impl Fn(Vec3, Vec3, Vec3) -> Vec3 + Sync,
    ) {
        self.fb.clear(scene.background);
        if scene.draw_solids {
            self.draw_solids_with(camera, solids, skin);
        }
    }

    /// The solids alone on black, shaded by `skin` (for measuring the skin's shadow against
    /// another light). The next [`Self::draw_solids`] clears it.
    pub fn solids_image(
        &mut self,
        camera: &Camera,
        solids: SolidsToDraw,
        skin: impl Fn(Vec3, Vec3, Vec3) -> Vec3 + Sync,
    ) -> &Framebuffer {
        self.fb.clear(Vec3::ZERO);
        self.draw_solids_with(camera, solids, skin);
        &self.fb
    }

    /// Draws the solids into the current image (not cleared) with the surface shader `skin`.
    fn draw_solids_with(
        &mut self,
        camera: &Camera,
        solids: SolidsToDraw,
        skin: impl Fn(Vec3, Vec3, Vec3) -> Vec3 + Sync,
    ) {
        for (s, albedo) in solids.solids.iter().zip(solids.albedo) {
            draw_ellipsoid(&mut self.fb, camera, s.unit_sphere_to_world, |p, n| {
                skin(p, n, *albedo)
            });
        }
        if let Some((ch, posed)) = solids.character {
            let mesh = Mesh {
                positions: &posed.positions,
                normals: &posed.normals,
                uv: &ch.uv,
                triangles: &ch.triangles,
                triangle_surface: &ch.triangle_material,
                surfaces: &self.surfaces,
                textures: &self.textures,
            };
            draw_mesh(&mut self.fb, camera, &mesh, &skin, &mut self.mesh);
        }
    }

    /// The first pass over the hair: which points the raster can draw past the solids drawn
    /// and nearer hair ([`seen_points`]); it keeps its fragments for [`Self::draw_hair`].
    pub fn find_seen(&mut self, camera: &Camera, hair: HairToDraw) {
        self.update_widths(hair.strands);
        let lines = polylines(hair, &self.widths_m, &self.bundle);
        seen_points(
            &self.fb,
            camera,
            &lines,
            &self.config.line,
            &mut self.lines,
            &mut self.seen,
        );
    }

    /// Draws the hair over what is drawn, with `hair`'s colours, by `draw`
    /// ([`draw_seen_polylines`] composites what [`Self::find_seen`] kept).
    pub fn draw_hair(&mut self, camera: &Camera, hair: HairToDraw, draw: DrawLines) {
        self.update_widths(hair.strands);
        let lines = polylines(hair, &self.widths_m, &self.bundle);
        draw(
            &mut self.fb,
            camera,
            &lines,
            &self.config.line,
            &mut self.lines,
        );
    }

    /// Each point's physical width: its strand's fibres side by side (F·2r), times the share
    /// of fibres left there (tapered tips thin).
    fn update_widths(&mut self, strands: &StrandGeometry) {
        let strand_width_m = self.strand_width_m;
        self.widths_m.clear();
        self.widths_m.extend(
            strands
                .fiber_share
                .iter()
                .map(|share| strand_width_m * share),
        );
    }

    pub fn framebuffer(&self) -> &Framebuffer {
        &self.fb
    }

    /// Per render-strand point, whether the last [`Self::find_seen`] found it drawable.
    pub fn seen(&self) -> &[bool] {
        &self.seen
    }

    /// Physical width of each render-strand point in metres (after a draw).
    pub fn widths_m(&self) -> &[f32] {
        &self.widths_m
    }

    /// The framebuffer, the hair's line raster (its lines at least as wide as `config` draws
    /// them) and the character's raster.
    pub fn estimate(config: &RasterConfig, sizes: &RunSizes) -> Vec<MemoryPart> {
        let (w, h) = (sizes.width, sizes.height);
        let mut parts = vec![
            MemoryPart {
                what: "framebuffer",
                product: format!("{w}×{h} pixels"),
                bytes: Framebuffer::estimated_bytes(w, h),
                set_by: "--width × --height",
            },
            MemoryPart {
                what: "hair line raster",
                product: format!("{} segments on {h} rows", grouped(sizes.segments)),
                bytes: LineScratch::estimated_bytes(
                    sizes.segments,
                    w,
                    h,
                    sizes.sample_len_m * sizes.px_per_m,
                    config.narrowest_drawn_px() as f64,
                    sizes.fibers_per_strand.round() >= 2.0,
                ) + sizes.points * POINT_BYTES as u64,
                set_by: "render strands × strands.points (× --segment-pieces), --height and --min-line-width-px",
            },
        ];
        if sizes.character_vertices > 0 {
            parts.push(MemoryPart {
                what: "character raster",
                product: format!(
                    "{w}×{h} pixels × 4 samples, {} triangles",
                    grouped(sizes.character_triangles)
                ),
                bytes: MeshScratch::estimated_bytes(w, h, sizes.character_triangles),
                set_by: "--width × --height, and the glTF's meshes",
            });
        }
        parts
    }
}

/// A bundle of F ≥ 2 fibres: the fibres' points in the bundle's unit disc (as the exact
/// reference places them), which spreads over half the strand spacing.
struct BundleShape {
    points: Vec<Vec2>,
    radius_m: f32,
    fiber_radius_m: f32,
}

/// The render strands as the raster draws them: points, colours and physical widths, and the
/// bundle their fibres spread over.
fn polylines<'a>(
    hair: HairToDraw<'a>,
    widths_m: &'a [f32],
    bundle: &'a Option<BundleShape>,
) -> Polylines<'a> {
    Polylines {
        points: &hair.strands.positions,
        colors: hair.colors,
        widths_m,
        points_per_line: hair.strands.points_per_strand,
        bundle: bundle.as_ref().map(|b| Bundle {
            radius_m: b.radius_m,
            fiber_radius_m: b.fiber_radius_m,
            points: &b.points,
        }),
    }
}

/// Bytes per render point the raster keeps: its width, and whether it is seen.
const POINT_BYTES: usize = size_of::<f32>() + size_of::<bool>();

/// How `character`'s triangles look (its materials) and its textures, as the raster takes them.
fn look_of(character: &Character) -> (Vec<Surface>, Vec<Texture>) {
    let surfaces = character
        .materials
        .iter()
        .map(|m| Surface {
            albedo: m.base_color,
            texture: m.texture.map(|t| t as u32),
            double_sided: m.double_sided,
        })
        .collect();
    let textures = character
        .textures
        .iter()
        .map(|t| Texture {
            width: t.width,
            height: t.height,
            texels: t.texels.clone(),
        })
        .collect();
    (surfaces, textures)
}
