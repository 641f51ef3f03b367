//! Generated strand files whose header declares more strands than a groom may have
//! (`tests/support/hostile/headers.rs`: TressFX 3 and 4, cyHair, PLY, USC-HairSalon; each as
//! long as its header says, the body a hole). Each must be refused naming the field and the
//! cap after reading its header alone: a peak heap under [`PEAK_BOUND_BYTES`] however long the
//! file. Reading the body first, the loader took the whole file (up to 1 GiB) and its points
//! before the groom's strand cap refused it.
//!
//! Reproduce one case with `WISP_HOSTILE_ONLY=<seed>`; more cases: `WISP_HOSTILE_CASES=<n>`.

use crate::bounded::run_bounded;
use crate::support::hostile::Rng;
use crate::support::hostile::headers::oversize;
use crate::support::scratch_dir;
use std::time::Duration;
use wisp::input::strand_file::load_strand_file;

/// Peak heap allowed for a refusal: the 64 KiB read to check the header, the parsed PLY
/// header and the message, with room to spare; any of the bodies is at least 48 MB (2 M
/// strands of 2 points at 12 bytes a point).
const PEAK_BOUND_BYTES: usize = 1 << 20;
/// Hang bound per case (a refusal takes well under a millisecond).
const TIME_LIMIT: Duration = Duration::from_secs(30);

#[test]
fn oversize_strand_counts_are_refused_from_the_header() {
    let only: Option<u64> = std::env::var("WISP_HOSTILE_ONLY")
        .ok()
        .and_then(|v| v.parse().ok());
    let cases: u64 = std::env::var("WISP_HOSTILE_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(40);
    let dir = scratch_dir("hostile-headers");
    let mut failures = Vec::new();
    let seeds: Vec<u64> = match only {
        Some(s) => vec![s],
        None => (0..cases).map(|i| 0x4EAD_0060 + i).collect(),
    };
    for seed in seeds {
        let case = oversize(&mut Rng::new(seed));
        let path = case.write(&dir).expect("write the sparse file");
        let for_case = path.clone();
        let outcome = run_bounded(
            move || load_strand_file(&for_case).map(|f| f.strand_count()),
            TIME_LIMIT,
        );
        let _ = std::fs::remove_file(&path);
        let problem = match outcome {
            Err(e) => Some(e),
            Ok(r) => match r.value {
                Ok(n) => Some(format!("accepted ({n} strands)")),
                Err(e) if !e.to_string().contains("strands a groom may have") => {
                    Some(format!("refused without naming the cap: {e}"))
                }
                Err(_) if r.peak_bytes > PEAK_BOUND_BYTES => Some(format!(
                    "refused after a peak heap of {} B (bound {PEAK_BOUND_BYTES} B)",
                    r.peak_bytes
                )),
                Err(_) => None,
            },
        };
        if let Some(p) = problem {
            failures.push(format!(
                "WISP_HOSTILE_ONLY={seed} {} ({} strands, {} B): {p}",
                case.name, case.strands, case.len
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
