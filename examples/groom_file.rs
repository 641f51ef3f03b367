//! Writes a synthetic captured groom as a cyHair `.hair` file, for timing the set-up of
//! `wisp render --hairstyle FILE.hair` at sizes no shared file has (BENCHMARKS.md, "Groom
//! set-up"): `wisp::groom::synthetic_strands` (centimetres, Y-up, roots on the upper part of a
//! 9 cm sphere, hanging down and back with a wave).
//!
//! `cargo run --release --example groom_file -- STRANDS POINTS OUT.hair`

use std::path::PathBuf;
use wisp::export::cyhair::write_hair;
use wisp::groom::synthetic_strands;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [count, points, out] = args.as_slice() else {
        anyhow::bail!("usage: groom_file STRANDS POINTS OUT.hair");
    };
    let count: usize = count.parse()?;
    let points: usize = points.parse()?;
    anyhow::ensure!(points >= 2, "POINTS must be at least 2 (got {points})");
    let file = synthetic_strands(count, points);
    let out = PathBuf::from(out);
    // 0.008 cm: a 80 µm fibre in the file's centimetres.
    write_hair(&out, &file.points, points, 0.008, "wisp synthetic groom")?;
    println!("{}: {count} strands x {points} points", out.display());
    Ok(())
}
