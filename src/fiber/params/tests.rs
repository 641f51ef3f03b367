use super::*;

#[test]
fn default_is_valid_and_inside_table_1() {
    let p = FiberParams::default();
    assert!(p.validate().is_ok());
    assert!((-10.0..=-5.0).contains(&p.alpha_r_deg));
    assert!((5.0..=10.0).contains(&p.beta_r_deg));
    assert!((0.85..=1.0).contains(&p.eccentricity));
    assert!((0.5..=5.0).contains(&p.k_g));
    assert!((10.0..=25.0).contains(&p.w_c_deg));
    assert!((0.2..=0.4).contains(&p.delta_eta_prime));
}

#[test]
fn validate_names_field_and_rule() {
    let cases: Vec<(FiberParams, &str)> = vec![
        (
            FiberParams {
                eta: 0.5,
                ..Default::default()
            },
            "eta must be in (1, 4)",
        ),
        (
            FiberParams {
                beta_r_deg: 0.0,
                ..Default::default()
            },
            "beta_r_deg must be in",
        ),
        (
            FiberParams {
                eccentricity: 0.5,
                ..Default::default()
            },
            "eccentricity must be in",
        ),
        (
            FiberParams {
                d_b: f32::NAN,
                ..Default::default()
            },
            "d_b must be in",
        ),
        (
            FiberParams {
                sigma_a: [0.1, -1.0, 0.1],
                ..Default::default()
            },
            "sigma_a[1] must be",
        ),
    ];
    for (p, prefix) in cases {
        let e = p.validate().expect_err("must be rejected");
        assert!(e.starts_with(prefix), "{e}");
    }
}

#[test]
fn table_1_lobe_ratios() {
    let c = LobeConstants::from_params(&FiberParams::default());
    let a_r = (-7.5f64).to_radians();
    assert!((c.alpha[1] - (-a_r / 2.0)).abs() < 1e-15);
    assert!((c.alpha[2] - (-1.5 * a_r)).abs() < 1e-15);
    assert!((c.beta[1] - c.beta[0] / 2.0).abs() < 1e-15);
    assert!((c.beta[2] - 2.0 * c.beta[0]).abs() < 1e-15);
}
