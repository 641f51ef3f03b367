//! Flags that scale work, and groom files whose header scales it, through the binary under an
//! address-space cap: each is refused with exit 2 naming the flag or the field and the rule,
//! or runs within the budget. Generated from a seed like the rest of the hostile suite.

use crate::support::hostile::Rng;
use crate::support::hostile::headers::oversize;
use crate::support::scratch_dir;
use std::path::Path;
use std::process::{Command, Output, Stdio};

/// Address-space cap of a run, KiB (`ulimit -v`): 1 GiB. A refusal from the header needs a
/// few megabytes; reading a generated groom's body (48 MB to 1 GiB) and its points does not
/// fit, so a loader that reads before it checks dies instead of exiting 2.
const ADDRESS_SPACE_KIB: u64 = 1 << 20;

fn wisp_capped(args: &[String], dir: &Path) -> Output {
    Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v {ADDRESS_SPACE_KIB} && exec \"$0\" \"$@\""
        ))
        .arg(env!("CARGO_BIN_EXE_wisp"))
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .output()
        .expect("run wisp")
}

fn quick(dir: &Path, extra: &[String]) -> Vec<String> {
    // Dual scattering: the light paths' bins (256 MB at `final`) would leave the widest lines
    // no room under the 1 GB budget this test draws them in.
    let mut a: Vec<String> =
        "render --still --frames 1 --width 32 --height 32 --max-memory-gb 1 --shading dual --quiet --out"
            .split_whitespace()
            .map(str::to_string)
            .collect();
    a.push(dir.join("out").display().to_string());
    a.extend_from_slice(extra);
    a
}

/// `--min-line-width-px` above 64 px (the widest line drawn) drew every segment 64 px wide at
/// an opacity of w/minimum: at 1e30 the hair vanished for 4.3× the memory and 20× the raster
/// time, uncounted. Generated values above the cap are refused naming the flag and the cap;
/// values up to it render.
#[test]
fn line_widths_past_the_widest_drawn_are_refused() {
    let dir = scratch_dir("hostile-work-flags");
    let mut rng = Rng::new(0x11DE_0060);
    let mut failures = Vec::new();
    let mut values: Vec<(String, bool)> = vec![
        ("64".into(), true),
        ("0.5".into(), true),
        ("64.01".into(), false),
        ("1e30".into(), false),
        ("3.4e38".into(), false),
    ];
    for _ in 0..6 {
        // 64 · 2^e for e in (0, 120]: every power of two past the cap up to near f32::MAX.
        let e = 1 + rng.below(120) as i32;
        values.push((format!("{:e}", 64.0f64 * 2f64.powi(e)), false));
    }
    for (value, accepted) in values {
        let args = quick(&dir, &["--min-line-width-px".into(), value.clone()]);
        let out = wisp_capped(&args, &dir);
        let stderr = String::from_utf8_lossy(&out.stderr);
        let ok = if accepted {
            out.status.code() == Some(0)
        } else {
            out.status.code() == Some(2)
                && stderr.contains("--min-line-width-px")
                && stderr.contains("at most 64 px")
        };
        if !ok {
            failures.push(format!(
                "--min-line-width-px {value}: exit {:?}: {}",
                out.status.code(),
                stderr.trim()
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Groom files whose header declares more strands than a groom may have exit 2 naming the
/// file and the cap, without reading the body (which would not fit the address-space cap).
#[test]
fn oversize_groom_headers_exit_2_before_the_body_is_read() {
    let dir = scratch_dir("hostile-work-headers");
    let mut failures = Vec::new();
    for seed in 0..10u64 {
        let case = oversize(&mut Rng::new(0x6E0_0060 + seed));
        let path = case.write(&dir).expect("write the sparse file");
        let args = quick(&dir, &["--hairstyle".into(), path.display().to_string()]);
        let out = wisp_capped(&args, &dir);
        let _ = std::fs::remove_file(&path);
        let stderr = String::from_utf8_lossy(&out.stderr);
        if !(out.status.code() == Some(2)
            && stderr.contains(&case.name)
            && stderr.contains("strands a groom may have"))
        {
            failures.push(format!(
                "{} ({} strands, {} B): exit {:?}: {}",
                case.name,
                case.strands,
                case.len,
                out.status.code(),
                stderr.trim()
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
