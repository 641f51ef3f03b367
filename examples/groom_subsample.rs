//! Writes an even subsample of captured strand files as one cyHair `.hair` file: a sparse
//! groom from a real capture (the TressFX ponytail cut to 100 strands), for looking at how
//! wisp densifies sparse grooms (`wisp::groom::densify`).
//!
//! `cargo run --release --example groom_subsample -- IN[,IN...] STRANDS OUT.hair`
//!
//! Strand `i` of the `STRANDS` kept is strand `i · total / STRANDS` of the files' strands in
//! order; every kept strand must have the same number of points (a `.hair` file of one count).

use std::path::{Path, PathBuf};
use wisp::export::cyhair::write_hair;
use wisp::input::strand_file::load_strand_file;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [inputs, count, out] = args.as_slice() else {
        anyhow::bail!("usage: groom_subsample IN[,IN...] STRANDS OUT.hair");
    };
    let count: usize = count.parse()?;
    let mut strands: Vec<Vec<glam::Vec3>> = Vec::new();
    for p in inputs.split(',') {
        let file = load_strand_file(Path::new(p))?;
        strands.extend(file.strands().map(<[_]>::to_vec));
    }
    let total = strands.len();
    anyhow::ensure!(
        (1..=total).contains(&count),
        "STRANDS must be in [1, {total}] (got {count})"
    );
    let kept: Vec<&Vec<glam::Vec3>> = (0..count).map(|i| &strands[i * total / count]).collect();
    let points = kept[0].len();
    anyhow::ensure!(
        kept.iter().all(|s| s.len() == points),
        "the kept strands have different point counts; a .hair file needs one"
    );
    let flat: Vec<glam::Vec3> = kept.into_iter().flatten().copied().collect();
    let out = PathBuf::from(out);
    write_hair(&out, &flat, points, 0.008, "wisp subsampled groom")?;
    println!(
        "{}: {count} of {total} strands x {points} points",
        out.display()
    );
    Ok(())
}
