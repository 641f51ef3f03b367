//! Writes fur authored on a glTF character as a cyHair `.hair` file: 4-point strands rooted on
//! every Nth vertex of the character's rest-pose mesh, in the file's own frame and metres
//! (`wisp::groom::synthetic_fur`), to try a groom kept as authored on its character:
//!
//! `cargo run --release --example fur_on_character -- CHARACTER.glb EVERY LENGTH_M OUT.hair`
//! then `wisp render --animation CHARACTER.glb --hairstyle OUT.hair --groom-as-authored`.

use std::path::{Path, PathBuf};
use wisp::export::cyhair::write_hair;
use wisp::groom::{FUR_POINTS, synthetic_fur};
use wisp::motion::{Motion, MotionOptions};

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [character, every, length, out] = args.as_slice() else {
        anyhow::bail!("usage: fur_on_character CHARACTER.glb EVERY LENGTH_M OUT.hair");
    };
    let every: usize = every.parse()?;
    let length_m: f32 = length.parse()?;
    anyhow::ensure!(every >= 1, "EVERY must be at least 1");
    anyhow::ensure!(
        length_m > 0.0 && length_m.is_finite(),
        "LENGTH_M must be positive"
    );
    // The file's own frame: not turned upright, so the fur is in the file's coordinates.
    let opts = MotionOptions {
        keep_axes: true,
        ..MotionOptions::default()
    };
    let motion = Motion::load(Path::new(character), &opts)?;
    let Some(ch) = motion.character() else {
        anyhow::bail!("{character}: no mesh to grow fur on");
    };
    let fur = synthetic_fur(ch.rest_positions(), every, length_m);
    let out = PathBuf::from(out);
    // 50 µm fibres, in the file's metres.
    write_hair(
        &out,
        &fur.points,
        FUR_POINTS,
        5e-5,
        "wisp fur on a character",
    )?;
    println!(
        "{}: {} strands x {FUR_POINTS} points",
        out.display(),
        fur.strand_points.len()
    );
    Ok(())
}
