//! `wisp fiber eval | tables | plot`: the fibre model for users and for independent checking.
//!
//! Degrees live here only: flags and JSON are in degrees (variances in degrees² in the
//! `tables` JSON), and are converted to radians before anything reaches `wisp::fiber`.

use super::AppError;

mod fiber_plot;
use clap::{Args, Subcommand};
use serde_json::{Value, json};
use std::path::PathBuf;
use wisp::fiber::{Fiber, FiberParams, HairAngles, Lobe};
use wisp::hairstyle::Hairstyle;

#[derive(Args, Debug)]
pub struct FiberArgs {
    #[command(subcommand)]
    pub command: FiberCommand,
}

#[derive(Subcommand, Debug)]
pub enum FiberCommand {
    /// Print the BCSDF S(ωi, ωo) per lobe as JSON, exactly as the renderer evaluates it.
    Eval(EvalArgs),
    /// Print the dual-scattering tables as JSON (degrees, degrees²).
    Tables(TablesArgs),
    /// Write PNG plots of N_p(φ) and of ā_f, ā_b against θ.
    Plot(PlotArgs),
}

/// Fibre selection shared by the subcommands: a hairstyle's fibre, then flag overrides.
#[derive(Args, Debug, Clone, Default)]
pub struct FiberFlags {
    /// Hairstyle JSON whose `fiber` is used [default: the built-in fibre]
    #[arg(long, value_name = "FILE")]
    pub hairstyle: Option<PathBuf>,
    /// Index of refraction η, in (1, 4)
    #[arg(long, value_name = "ETA", allow_hyphen_values = true, value_parser = super::parse_f32_as_written)]
    pub eta: Option<f32>,
    /// Absorption per unit radius, R,G,B
    #[arg(long = "sigma-a", value_name = "R,G,B", allow_hyphen_values = true)]
    pub sigma_a: Option<String>,
    /// R lobe shift α_R, degrees
    #[arg(long = "alpha-r-deg", value_name = "DEG", allow_hyphen_values = true, value_parser = super::parse_f32_as_written)]
    pub alpha_r_deg: Option<f32>,
    /// R lobe width β_R, degrees
    #[arg(long = "beta-r-deg", value_name = "DEG", allow_hyphen_values = true, value_parser = super::parse_f32_as_written)]
    pub beta_r_deg: Option<f32>,
    /// Cross-section eccentricity a/b
    #[arg(long, value_name = "A/B", allow_hyphen_values = true, value_parser = super::parse_f32_as_written)]
    pub eccentricity: Option<f32>,
}

#[derive(Args, Debug)]
pub struct EvalArgs {
    /// Light inclination θi from the normal plane, degrees in [−90, 90]
    #[arg(long = "theta-i-deg", value_name = "DEG", allow_hyphen_values = true, value_parser = super::parse_f32_as_written)]
    pub theta_i_deg: f32,
    /// Light azimuth φi, degrees
    #[arg(long = "phi-i-deg", value_name = "DEG", allow_hyphen_values = true, value_parser = super::parse_f32_as_written)]
    pub phi_i_deg: f32,
    /// View inclination θo, degrees in [−90, 90]
    #[arg(long = "theta-o-deg", value_name = "DEG", allow_hyphen_values = true, value_parser = super::parse_f32_as_written)]
    pub theta_o_deg: f32,
    /// View azimuth φo, degrees
    #[arg(long = "phi-o-deg", value_name = "DEG", allow_hyphen_values = true, value_parser = super::parse_f32_as_written)]
    pub phi_o_deg: f32,
    #[command(flatten)]
    pub fiber: FiberFlags,
}

#[derive(Args, Debug)]
pub struct TablesArgs {
    /// Step of the θ column, degrees in [0.1, 90]
    #[arg(long = "theta-step-deg", value_name = "DEG", default_value_t = 5.0, allow_hyphen_values = true, value_parser = super::parse_f32_as_written)]
    pub theta_step_deg: f32,
    #[command(flatten)]
    pub fiber: FiberFlags,
}

#[derive(Args, Debug)]
pub struct PlotArgs {
    /// Output directory, created if missing
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    #[command(flatten)]
    pub fiber: FiberFlags,
}

pub fn run(args: FiberArgs) -> Result<(), AppError> {
    match args.command {
        FiberCommand::Eval(a) => eval(a),
        FiberCommand::Tables(a) => tables(a),
        FiberCommand::Plot(a) => fiber_plot::plot(&a.out, &a.fiber.resolve()?),
    }
}

impl FiberFlags {
    /// The fibre parameters: defaults or the hairstyle's, overridden by flags, validated.
    pub fn resolve(&self) -> Result<FiberParams, AppError> {
        let mut p = match &self.hairstyle {
            Some(path) => Hairstyle::load(path)
                .map_err(AppError::input)?
                .fiber
                .clone(),
            None => FiberParams::default(),
        };
        let flag_err =
            |flag: &str, rule: String| AppError::input(anyhow::anyhow!("--{flag}: {rule}"));
        if let Some(v) = self.eta {
            p.eta = v;
        }
        if let Some(s) = &self.sigma_a {
            let parts: Vec<&str> = s.split(',').collect();
            if parts.len() != 3 {
                return Err(flag_err(
                    "sigma-a",
                    format!("must be three comma-separated numbers R,G,B (got {s:?})"),
                ));
            }
            for (c, part) in parts.iter().enumerate() {
                p.sigma_a[c] = part.trim().parse::<f32>().map_err(|_| {
                    flag_err(
                        "sigma-a",
                        format!("must be three comma-separated numbers R,G,B (got {s:?})"),
                    )
                })?;
            }
        }
        if let Some(v) = self.alpha_r_deg {
            p.alpha_r_deg = v;
        }
        if let Some(v) = self.beta_r_deg {
            p.beta_r_deg = v;
        }
        if let Some(v) = self.eccentricity {
            p.eccentricity = v;
        }
        p.validate().map_err(|rule| {
            // Name the flag that set the field when there is one.
            let field = rule.split(' ').next().unwrap_or("");
            let flag = match field {
                "eta" if self.eta.is_some() => Some("eta"),
                f if f.starts_with("sigma_a") && self.sigma_a.is_some() => Some("sigma-a"),
                "alpha_r_deg" if self.alpha_r_deg.is_some() => Some("alpha-r-deg"),
                "beta_r_deg" if self.beta_r_deg.is_some() => Some("beta-r-deg"),
                "eccentricity" if self.eccentricity.is_some() => Some("eccentricity"),
                _ => None,
            };
            match flag {
                Some(f) => flag_err(f, rule),
                None => AppError::input(anyhow::anyhow!("fiber.{rule}")),
            }
        })?;
        Ok(p)
    }
}

fn check_angle(flag: &str, v: f32, limit: f32) -> Result<f32, AppError> {
    if v.is_finite() && v.abs() <= limit {
        Ok(v)
    } else {
        Err(AppError::input(anyhow::anyhow!(
            "--{flag}: must be in [-{limit}, {limit}] degrees (got {v})"
        )))
    }
}

fn rgb(v: glam::Vec3) -> Value {
    json!([v.x, v.y, v.z])
}

fn eval(a: EvalArgs) -> Result<(), AppError> {
    let params = a.fiber.resolve()?;
    let ti = check_angle("theta-i-deg", a.theta_i_deg, 90.0)?.to_radians();
    let to = check_angle("theta-o-deg", a.theta_o_deg, 90.0)?.to_radians();
    let pi_ = check_angle("phi-i-deg", a.phi_i_deg, 1.0e6)?.to_radians();
    let po = check_angle("phi-o-deg", a.phi_o_deg, 1.0e6)?.to_radians();
    let fiber = Fiber::new(&params);
    let phi = wisp::fiber::marschner::wrap_pi((po - pi_) as f64) as f32;
    let angles = HairAngles {
        theta_i: ti,
        theta_o: to,
        phi,
        cos_2phi_h: (pi_ as f64 + po as f64).cos() as f32,
    };
    let lobes = fiber.bcsdf_lobes(&angles);
    let s = fiber.bcsdf(&angles);
    let chiang = params.model == wisp::fiber::FiberModel::Chiang;
    let out = json!({
        "S": rgb(s),
        "R": rgb(lobes[Lobe::R as usize]),
        "TT": rgb(lobes[Lobe::TT as usize]),
        "TRT": rgb(lobes[Lobe::TRT as usize]),
        "p_ge_3": rgb(lobes[3]),
        "m_normalization": if chiang { "sphere" } else { "theta_o" },
    });
    println!("{out}");
    Ok(())
}

fn tables(a: TablesArgs) -> Result<(), AppError> {
    let params = a.fiber.resolve()?;
    let step = a.theta_step_deg;
    if !(step.is_finite() && (0.1..=90.0).contains(&step)) {
        return Err(AppError::input(anyhow::anyhow!(
            "--theta-step-deg: must be in [0.1, 90] (got {step})"
        )));
    }
    let fiber = Fiber::new(&params);
    let dual = fiber.dual_tables();
    let n = (180.0 / step as f64).floor() as usize;
    let mut theta_deg = Vec::new();
    let names = [
        "a_f", "a_b", "A_b", "beta_f2", "beta_b2", "alpha_f", "alpha_b", "delta_b", "sigma_b2",
    ];
    let mut cols: Vec<Vec<Value>> = vec![Vec::new(); names.len()];
    let deg = 180.0 / std::f64::consts::PI;
    for i in 0..=n {
        let t = -90.0 + step as f64 * i as f64;
        if t > 90.0 + 1e-9 {
            break;
        }
        theta_deg.push(t);
        let q = dual.quantities_at(t.to_radians());
        let vals: [[f64; 3]; 9] = [
            q.a_f,
            q.a_b,
            q.big_a_b,
            q.beta_f2.map(|x| x * deg * deg),
            q.beta_b2.map(|x| x * deg * deg),
            q.alpha_f.map(|x| x * deg),
            q.alpha_b.map(|x| x * deg),
            q.delta_b.map(|x| x * deg),
            q.sigma_b2.map(|x| x * deg * deg),
        ];
        for (k, v) in vals.iter().enumerate() {
            cols[k].push(json!(v));
        }
    }
    let mut obj = serde_json::Map::new();
    obj.insert("theta_deg".into(), json!(theta_deg));
    for (k, name) in names.iter().enumerate() {
        obj.insert((*name).into(), Value::Array(std::mem::take(&mut cols[k])));
    }
    obj.insert("conventions".into(), conventions());
    obj.insert(
        "fiber".into(),
        serde_json::to_value(&params).unwrap_or(Value::Null),
    );
    println!("{}", Value::Object(obj));
    Ok(())
}

fn conventions() -> Value {
    json!({
        "theta": "light inclination to the fibre's normal plane, sin(theta) = w_i . u, degrees",
        "angles": "shifts alpha_*, delta_b in degrees of x = theta_i + theta_o (= 2 theta_h); variances beta_*2, sigma_b2 in degrees squared of x",
        "m_normalization": "theta_o: each lobe M_p is a unit-area Gaussian in theta_o at fixed theta_i (Marschner's g(beta; theta_h - alpha) / 2), mean 2 alpha_p, std 2 beta_p",
        "eq6_eq12": "outgoing cosine (energy fraction; Eq. 6 prints the incident one): a = (1/pi) int_front/back int f_s cos(theta_o) dphi_i dw_o, dw_o = cos(theta_o) dtheta_o dphi_o; world-fixed halves, weights |phi|/pi (front) and 1 - |phi|/pi (back) of the relative azimuth; circular fibre (eccentricity ignored)",
        "eq16": "exact closed form of the series above Eq. 16 (equals Eq. 16 with +2 a_b^2/(1-a_f^2)^2 in the alpha_b term to second order; the printed minus sign is wrong)",
        "eq17": "series above Eq. 17 summed numerically (unit-consistent); the printed fit is not used because its denominator adds an angle to a number",
        "eq25": "convolution N^G(theta, phi) = (1/pi) int_{-pi/2}^{pi/2} N(theta, phi - phi') dphi'",
        "lobe_moments": "alpha = energy-weighted mean of 2 alpha_p; beta2 = moment-matched variance of the lobe mixture",
        "a_f_max": wisp::fiber::dual::A_F_MAX,
    })
}
