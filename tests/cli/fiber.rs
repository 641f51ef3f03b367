//! `wisp fiber` end to end: the built binary's JSON matches the library, bad input exits 2 with
//! a message naming the flag and the rule, and `plot` writes PNG files.

use std::path::PathBuf;
use std::process::Command;
use wisp::fiber::{Fiber, FiberParams, HairAngles, Lobe};

fn wisp(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_wisp"))
        .args(args)
        .output()
        .expect("the wisp binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn rgb(v: &serde_json::Value) -> [f64; 3] {
    let a = v.as_array().expect("an RGB array");
    [0, 1, 2].map(|i| a[i].as_f64().expect("a number"))
}

#[test]
fn eval_matches_library_and_sums_lobes() {
    let (code, out, err) = wisp(&[
        "fiber",
        "eval",
        "--theta-i-deg",
        "25",
        "--phi-i-deg",
        "10",
        "--theta-o-deg",
        "-15",
        "--phi-o-deg",
        "160",
        "--sigma-a",
        "0.2,0.3,0.5",
        "--beta-r-deg",
        "6",
    ]);
    assert_eq!(code, 0, "{err}");
    let j: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    assert_eq!(j["m_normalization"], "theta_o");
    let (s, r, tt, trt) = (rgb(&j["S"]), rgb(&j["R"]), rgb(&j["TT"]), rgb(&j["TRT"]));
    let fiber = Fiber::new(&FiberParams {
        sigma_a: [0.2, 0.3, 0.5],
        beta_r_deg: 6.0,
        ..Default::default()
    });
    let a = HairAngles {
        theta_i: 25f32.to_radians(),
        theta_o: (-15f32).to_radians(),
        phi: 150f32.to_radians(),
        cos_2phi_h: (170f64.to_radians().cos()) as f32,
    };
    let lobes = fiber.bcsdf_lobes(&a);
    for ch in 0..3 {
        assert!((s[ch] - (r[ch] + tt[ch] + trt[ch])).abs() <= 1e-6 * s[ch].max(1e-9));
        for (got, l) in [(r[ch], Lobe::R), (tt[ch], Lobe::TT), (trt[ch], Lobe::TRT)] {
            let want = lobes[l as usize][ch] as f64;
            assert!(
                (got - want).abs() <= 1e-6 * want.max(1e-9),
                "{l:?}: {got} vs {want}"
            );
        }
    }
    assert!(tt[0] > 0.0, "TT lobe near φ = 150° must be lit");
}

#[test]
fn tables_json_has_every_column() {
    let (code, out, err) = wisp(&["fiber", "tables", "--theta-step-deg", "30"]);
    assert_eq!(code, 0, "{err}");
    let j: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    let theta = j["theta_deg"].as_array().expect("theta_deg");
    assert_eq!(theta.len(), 7); // −90, −60, …, 90
    assert_eq!(theta[0].as_f64(), Some(-90.0));
    for key in [
        "a_f", "a_b", "A_b", "beta_f2", "beta_b2", "alpha_f", "alpha_b", "delta_b", "sigma_b2",
    ] {
        let col = j[key].as_array().unwrap_or_else(|| panic!("{key} missing"));
        assert_eq!(col.len(), theta.len(), "{key}");
        for v in col {
            assert!(rgb(v).iter().all(|x| x.is_finite()), "{key}: {v}");
        }
    }
    for key in ["m_normalization", "eq6_eq12", "eq16", "eq17", "eq25"] {
        assert!(j["conventions"][key].is_string(), "conventions.{key}");
    }
    // Degrees in the JSON: θ = 0 row against the library (radians) converted here.
    let fiber = Fiber::new(&FiberParams::default());
    let q = fiber.dual_tables().quantities_at(0.0);
    let row = rgb(&j["sigma_b2"][3]);
    let want = q.sigma_b2[0].to_degrees().to_degrees();
    assert!((row[0] - want).abs() <= 1e-9 * want, "{} vs {want}", row[0]);
}

#[test]
fn bad_input_exits_2_naming_flag_and_rule() {
    let base = [
        "fiber",
        "eval",
        "--theta-i-deg",
        "0",
        "--phi-i-deg",
        "0",
        "--theta-o-deg",
        "0",
        "--phi-o-deg",
        "90",
    ];
    let cases: [(&[&str], &str); 5] = [
        (
            &["--sigma-a", "1,2"],
            "--sigma-a: must be three comma-separated numbers",
        ),
        (&["--eta", "0.5"], "--eta: eta must be in (1, 4) (got 0.5)"),
        (
            &["--eccentricity", "0.5"],
            "--eccentricity: eccentricity must be in",
        ),
        (
            &["--beta-r-deg", "nan"],
            "--beta-r-deg: beta_r_deg must be in",
        ),
        (
            &["--hairstyle", "/nonexistent/wisp.json"],
            "/nonexistent/wisp.json",
        ),
    ];
    for (extra, msg) in cases {
        let args: Vec<&str> = base.iter().chain(extra.iter()).copied().collect();
        let (code, _, err) = wisp(&args);
        assert_eq!(code, 2, "{extra:?}: {err}");
        assert!(err.contains(msg), "{extra:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
    let (code, _, err) = wisp(&[
        "fiber",
        "eval",
        "--theta-i-deg",
        "91",
        "--phi-i-deg",
        "0",
        "--theta-o-deg",
        "0",
        "--phi-o-deg",
        "0",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("--theta-i-deg"), "{err}");
    let (code, _, err) = wisp(&["fiber", "tables", "--theta-step-deg", "0"]);
    assert_eq!(code, 2);
    assert!(err.contains("--theta-step-deg"), "{err}");
}

#[test]
fn hairstyle_fiber_is_used_and_flags_override() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("hairstyles/curly.json");
    let p = path.to_str().expect("utf-8 path");
    let args = |extra: &[&str]| {
        let mut v = vec![
            "fiber",
            "eval",
            "--theta-i-deg",
            "10",
            "--phi-i-deg",
            "0",
            "--theta-o-deg",
            "-5",
            "--phi-o-deg",
            "170",
            "--hairstyle",
            p,
        ];
        v.extend_from_slice(extra);
        let (code, out, err) = wisp(&v);
        assert_eq!(code, 0, "{err}");
        let j: serde_json::Value = serde_json::from_str(&out).expect("JSON");
        rgb(&j["TT"])
    };
    let curly = args(&[]);
    let (_, out, _) = wisp(&[
        "fiber",
        "eval",
        "--theta-i-deg",
        "10",
        "--phi-i-deg",
        "0",
        "--theta-o-deg",
        "-5",
        "--phi-o-deg",
        "170",
    ]);
    let j: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    let default = rgb(&j["TT"]);
    // curly.json's σa = [0.31, 0.62, 1.53] is lighter than the default brown in every channel.
    assert!(
        (0..3).all(|c| curly[c] > default[c]),
        "{curly:?} vs {default:?}"
    );
    let overridden = args(&["--sigma-a", "0.545,0.906,1.78"]);
    for c in 0..3 {
        assert!((overridden[c] - default[c]).abs() <= 1e-6 * default[c]);
    }
}

#[test]
fn plot_writes_pngs() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("fiber_plot_test");
    let _ = std::fs::remove_dir_all(&dir);
    let (code, _, err) = wisp(&["fiber", "plot", "--out", dir.to_str().expect("utf-8")]);
    assert_eq!(code, 0, "{err}");
    for name in [
        "n_p_theta_d_0.png",
        "n_p_theta_d_30.png",
        "n_p_theta_d_60.png",
        "n_trt_raw_vs_smoothed.png",
        "a_f_a_b.png",
        "a_f_lighter.png",
    ] {
        let bytes = std::fs::read(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{name}");
    }
    assert!(dir.join("plots.txt").exists());
}

/// A hairstyle whose fibre says `"model": "chiang"` is evaluated with the Chiang model: S is the
/// sum of the four lobes (p ≥ 3 included), equal to the library's tabulated BCSDF.
#[test]
fn eval_chiang_from_hairstyle() {
    let src = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("hairstyles/smooth.json");
    let mut style: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&src).expect("preset")).expect("JSON");
    style["fiber"]["model"] = serde_json::json!("chiang");
    let dir = std::env::temp_dir().join(format!("wisp_fiber_cli_{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("smooth_chiang.json");
    std::fs::write(&path, style.to_string()).expect("write");
    let (code, out, err) = wisp(&[
        "fiber",
        "eval",
        "--theta-i-deg",
        "20",
        "--phi-i-deg",
        "0",
        "--theta-o-deg",
        "-10",
        "--phi-o-deg",
        "150",
        "--hairstyle",
        path.to_str().expect("utf-8 path"),
    ]);
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(code, 0, "{err}");
    let j: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    assert_eq!(j["m_normalization"], "sphere");
    let params: FiberParams =
        serde_json::from_value(style["fiber"].clone()).expect("fibre parameters");
    let fiber = Fiber::new(&params);
    let a = HairAngles {
        theta_i: 20f32.to_radians(),
        theta_o: (-10f32).to_radians(),
        phi: 150f32.to_radians(),
        cos_2phi_h: (150f64.to_radians().cos()) as f32,
    };
    let want = fiber.bcsdf(&a);
    let (s, r, tt, trt, rest) = (
        rgb(&j["S"]),
        rgb(&j["R"]),
        rgb(&j["TT"]),
        rgb(&j["TRT"]),
        rgb(&j["p_ge_3"]),
    );
    for ch in 0..3 {
        assert!((s[ch] - (r[ch] + tt[ch] + trt[ch] + rest[ch])).abs() <= 1e-6 * s[ch]);
        assert!(
            (s[ch] - want[ch] as f64).abs() <= 1e-6 * s[ch],
            "{s:?} vs {want}"
        );
        assert!(
            rest[ch] > 0.0,
            "the p ≥ 3 residual is part of the Chiang model"
        );
    }
}
