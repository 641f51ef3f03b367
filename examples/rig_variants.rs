//! Writes copies of the embedded dance in the conventions other exporters use, to try wisp on
//! them as a user would (the tests build the same copies in memory, `tests/lib/rigs.rs`):
//!
//! ```text
//! cargo run --release --example rig_variants -- DIR
//! ```
//!
//! writes `DIR/dance_cm.glb` (centimetres under a 0.01 scale node, like Mixamo's exports),
//! `DIR/dance_zup.glb` (Z-up data under a −90° correcting root), `DIR/dance_zup_raw.glb` (Z-up
//! data with no correction: the model lies along +Z of the glTF world) and
//! `DIR/dance_unnamed.glb` (every node name dropped).

#[path = "../tests/support/rig_variants.rs"]
#[allow(dead_code)]
mod rig_variants;

use rig_variants::{Frame, re_expressed};
use wisp::motion::dance::DANCE_GLB;

fn main() -> std::io::Result<()> {
    let dir = std::path::PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| ".".into()));
    std::fs::create_dir_all(&dir)?;
    let unnamed = Frame {
        scale: 1.0,
        rotation: glam::Quat::IDENTITY,
        correcting_root: false,
        unnamed: true,
    };
    for (name, frame) in [
        ("dance_cm.glb", Frame::CM_UNDER_SCALE_NODE),
        ("dance_zup.glb", Frame::z_up_corrected()),
        ("dance_zup_raw.glb", Frame::z_up_raw()),
        ("dance_unnamed.glb", unnamed),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, re_expressed(DANCE_GLB, frame))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
