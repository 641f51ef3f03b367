//! # wisp: a CPU engine that animates and renders human hair
//!
//! Pipeline (one frame, data flowing one way; see `docs/DESIGN.md`):
//!
//! ```text
//! motion   glTF clip -> head (and body-sphere) transforms at time t
//! sim      rigid-link guide strands: roots on the moving scalp, gravity, damping, bending,
//!          head/body collisions, self-collision from the guides' own density grid (Bertails
//!          2005 §4.1)
//! groom    captured strands (.tfx .hair .ply .data) -> placed on the head, wisps, guides, rest offsets
//! interp   render strands from their wisp's 3 guides, Catmull-Rom smoothing, curls
//! map      light-oriented, modulo-indexed grid: fill, column sweep -> Tf, σ̄f², direct fraction
//! shade    per render-strand vertex: filtered map lookup -> fibre shader
//! raster   camera, depth-tested anti-aliased lines, the head -> framebuffer (+ coverage)
//! scene    where the camera is: fixed, or following the head
//! output   PNG frames or linear RGBA EXR (temporary name + rename), or a window
//! cache    the guide state of every frame of a run, written once and rendered anywhere
//! ```
//!
//! ## Conventions (stated once)
//! - SI units inside: metres, seconds, radians. Degrees only at the edges (JSON, CLI), in names
//!   ending `_deg`.
//! - World: right-handed, Y up (as glTF). The head frame of a hairstyle: origin at the head
//!   ellipsoid's centre, +Y up, +Z toward the face, +X to the head's left.
//! - Hair frame (Marschner 2003 §2.2): `u` is the unit tangent from root to tip; θ is measured
//!   from the normal plane (sin θ = ω·u); ωi points to the light, ωo to the camera.
//! - A directional light travels along `L`; the map's X axis is `L`.
//! - Colours are linear RGB until the PNG encoder converts to 8-bit sRGB.
//!
//! `unsafe` is denied throughout; one file allows it: the map build's counting sort
//! (`map/build/scatter.rs`), whose parallel chunks write interleaved places of one buffer.

#![deny(unsafe_code)]

pub mod accuracy;
pub mod budget;
pub mod cache;
pub mod color;
pub mod disc;
pub mod engine;
pub mod export;
pub mod fiber;
pub mod groom;
pub mod hairstyle;
pub mod input;
pub mod interp;
mod keysort;
pub mod light;
pub mod light_paths;
pub mod map;
pub mod motion;
pub mod output;
pub mod quality;
pub mod raster;
pub mod rng;
pub mod scene;
pub mod shade;
pub mod sim;
mod tri_span;
