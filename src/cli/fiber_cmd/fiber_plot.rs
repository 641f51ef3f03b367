//! `wisp fiber plot`: a tiny 2D line-plot rasteriser (white background, axes, grid lines at
//! round values, coloured polylines) and the fibre plots built with it. No text rendering: each
//! run writes `plots.txt` next to the PNGs saying what the axes, grid lines and colours are.

use super::AppError;
use std::fmt::Write as _;
use std::path::Path;
use wisp::fiber::marschner::n_lobe;
use wisp::fiber::{Fiber, FiberParams, Lobe, LobeConstants};

const W: usize = 720;
const H: usize = 420;
const MARGIN: usize = 40;

/// An RGB8 canvas with a data window [x0, x1] × [y0, y1].
struct Plot {
    rgb: Vec<u8>,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
}

impl Plot {
    fn new(x0: f64, x1: f64, y0: f64, y1: f64, x_grid: f64, y_grid: f64) -> Self {
        let mut p = Self {
            rgb: vec![255; W * H * 3],
            x0,
            x1,
            y0,
            y1,
        };
        let grey = [220, 220, 220];
        let mut gx = (x0 / x_grid).ceil() * x_grid;
        while gx <= x1 + 1e-9 {
            p.line_data(gx, y0, gx, y1, grey, 1);
            gx += x_grid;
        }
        let mut gy = (y0 / y_grid).ceil() * y_grid;
        while gy <= y1 + 1e-9 {
            p.line_data(x0, gy, x1, gy, grey, 1);
            gy += y_grid;
        }
        // Axes: left and bottom frame, and y = 0 if visible.
        let black = [0, 0, 0];
        p.line_data(x0, y0, x1, y0, black, 1);
        p.line_data(x0, y0, x0, y1, black, 1);
        if y0 < 0.0 && y1 > 0.0 {
            p.line_data(x0, 0.0, x1, 0.0, black, 1);
        }
        p
    }

    fn to_px(&self, x: f64, y: f64) -> (f64, f64) {
        let px = MARGIN as f64 + (x - self.x0) / (self.x1 - self.x0) * (W - 2 * MARGIN) as f64;
        let py =
            (H - MARGIN) as f64 - (y - self.y0) / (self.y1 - self.y0) * (H - 2 * MARGIN) as f64;
        (px, py)
    }

    fn dot(&mut self, x: i64, y: i64, c: [u8; 3], r: i64) {
        for dy in -r / 2..=(r - 1) / 2 {
            for dx in -r / 2..=(r - 1) / 2 {
                let (xx, yy) = (x + dx, y + dy);
                if xx >= 0 && yy >= 0 && (xx as usize) < W && (yy as usize) < H {
                    let i = (yy as usize * W + xx as usize) * 3;
                    self.rgb[i..i + 3].copy_from_slice(&c);
                }
            }
        }
    }

    fn line_data(&mut self, xa: f64, ya: f64, xb: f64, yb: f64, c: [u8; 3], width: i64) {
        let clamp = |y: f64, p: &Self| y.clamp(p.y0, p.y1);
        let (ax, ay) = self.to_px(xa, clamp(ya, self));
        let (bx, by) = self.to_px(xb, clamp(yb, self));
        if !(ax.is_finite() && ay.is_finite() && bx.is_finite() && by.is_finite()) {
            return;
        }
        let steps = ((bx - ax).abs().max((by - ay).abs()).ceil() as usize).max(1);
        for s in 0..=steps {
            let t = s as f64 / steps as f64;
            let x = ax + (bx - ax) * t;
            let y = ay + (by - ay) * t;
            self.dot(x.round() as i64, y.round() as i64, c, width);
        }
    }

    fn polyline(&mut self, pts: &[(f64, f64)], c: [u8; 3], dashed: bool) {
        for (k, w) in pts.windows(2).enumerate() {
            if dashed && (k / 4) % 2 == 1 {
                continue;
            }
            self.line_data(w[0].0, w[0].1, w[1].0, w[1].1, c, 2);
        }
    }

    fn save(&self, path: &Path) -> Result<(), AppError> {
        wisp::output::write_png_rgb8(path, W as u32, H as u32, &self.rgb)
            .map_err(|e| AppError::other(anyhow::anyhow!("{e}")))
    }
}

const LOBE_COLOURS: [[u8; 3]; 3] = [[0, 0, 0], [30, 90, 220], [20, 160, 60]];
const CHANNEL_COLOURS: [[u8; 3]; 3] = [[220, 30, 30], [30, 170, 30], [30, 60, 230]];

fn nice_step(range: f64) -> f64 {
    let raw = range / 8.0;
    let mag = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw)
        .unwrap_or(mag * 10.0)
}

/// Writes the plots into `out` (created if missing), and `plots.txt`, their legend.
pub fn plot(out: &Path, params: &FiberParams) -> Result<(), AppError> {
    std::fs::create_dir_all(out).map_err(|e| {
        AppError::input(anyhow::anyhow!(
            "--out {}: cannot create ({e})",
            out.display()
        ))
    })?;
    let fiber = Fiber::new(params);
    let mut notes = String::new();
    let _ = writeln!(
        notes,
        "wisp fiber plot: {}\nNo text in the PNGs; this file is the legend.\n",
        serde_json::to_string(params).unwrap_or_default()
    );
    plot_n_p(out, fiber.lobe_constants(), &mut notes)?;
    plot_trt_smoothing(out, fiber.lobe_constants(), &mut notes)?;
    plot_albedos(out, &fiber, params, &mut notes)?;
    std::fs::write(out.join("plots.txt"), notes)
        .map_err(|e| AppError::other(anyhow::anyhow!("{}: {e}", out.display())))?;
    Ok(())
}

/// N_p(φ) of each lobe at a few θd, channel mean, exact evaluation at cos 2φh = 0 (mean
/// eccentricity): `n_p_theta_d_*.png`.
fn plot_n_p(out: &Path, c: &LobeConstants, notes: &mut String) -> Result<(), AppError> {
    for theta_deg in [0.0f64, 30.0, 60.0] {
        let sin_td = theta_deg.to_radians().sin();
        let n = 721;
        let curves: Vec<Vec<(f64, f64)>> = Lobe::ALL
            .iter()
            .map(|&lobe| {
                (0..n)
                    .map(|k| {
                        let phi_deg = -180.0 + 360.0 * k as f64 / (n - 1) as f64;
                        let v = n_lobe(c, lobe, sin_td, phi_deg.to_radians(), 0.0);
                        (phi_deg, (v[0] + v[1] + v[2]) / 3.0)
                    })
                    .collect()
            })
            .collect();
        let y_max = curves.iter().flatten().map(|p| p.1).fold(1e-6, f64::max) * 1.1;
        let mut p = Plot::new(-180.0, 180.0, 0.0, y_max, 45.0, nice_step(y_max));
        for (l, curve) in curves.iter().enumerate() {
            p.polyline(curve, LOBE_COLOURS[l], false);
        }
        let name = format!("n_p_theta_d_{}.png", theta_deg as i32);
        p.save(&out.join(&name))?;
        let _ = writeln!(
            notes,
            "{name}: N_p(phi) at theta_d = {theta_deg} deg, mean of R,G,B, 1/rad. x: phi from -180 \
             to 180 deg, grid every 45 deg. y: 0 to {y_max:.4}, grid every {:.4}. black = R, \
             blue = TT, green = TRT (smoothed, section 5.2.2).",
            nice_step(y_max)
        );
    }
    Ok(())
}

/// TRT raw (Eq. 8) against smoothed (§5.2.2) at θd = 0, channel mean:
/// `n_trt_raw_vs_smoothed.png`.
fn plot_trt_smoothing(out: &Path, c: &LobeConstants, notes: &mut String) -> Result<(), AppError> {
    let n = 1441;
    let az = wisp::fiber::marschner::azimuth_for(c, Lobe::TRT, 0.0, 0.0);
    let mut raw = Vec::with_capacity(n);
    let mut smooth = Vec::with_capacity(n);
    for k in 0..n {
        let phi_deg = -90.0 + 180.0 * k as f64 / (n - 1) as f64;
        let r = az.n_raw(2, phi_deg.to_radians());
        let s = az.n_trt_smoothed(c, phi_deg.to_radians());
        raw.push((phi_deg, (r[0] + r[1] + r[2]) / 3.0));
        smooth.push((phi_deg, (s[0] + s[1] + s[2]) / 3.0));
    }
    let y_max = smooth.iter().map(|p| p.1).fold(1e-6, f64::max) * 3.0;
    let mut p = Plot::new(-90.0, 90.0, 0.0, y_max, 15.0, nice_step(y_max));
    p.polyline(&raw, [150, 150, 150], false);
    p.polyline(&smooth, LOBE_COLOURS[2], false);
    p.save(&out.join("n_trt_raw_vs_smoothed.png"))?;
    let _ = writeln!(
        notes,
        "n_trt_raw_vs_smoothed.png: N_TRT(phi) at theta_d = 0, mean of R,G,B. x: phi from -90 \
         to 90 deg, grid every 15 deg. y: 0 to {y_max:.4} (raw caustic spikes clipped), grid \
         every {:.4}. grey = raw Eq. 8 (infinite at the caustics), green = smoothed.",
        nice_step(y_max)
    );
    Ok(())
}

/// ā_f and ā_b against θ per channel (`a_f_a_b.png`), and ā_f of this fibre against a
/// lighter one, σa / 4 (`a_f_lighter.png`).
fn plot_albedos(
    out: &Path,
    fiber: &Fiber,
    params: &FiberParams,
    notes: &mut String,
) -> Result<(), AppError> {
    let lighter = Fiber::new(&FiberParams {
        sigma_a: params.sigma_a.map(|s| s / 4.0),
        ..params.clone()
    });
    let series = |f: &Fiber, which: usize, ch: usize| -> Vec<(f64, f64)> {
        let d = f.dual_tables();
        d.theta
            .iter()
            .zip(&d.at)
            .map(|(t, q)| {
                let v = if which == 0 { q.a_f[ch] } else { q.a_b[ch] };
                (t.to_degrees(), v)
            })
            .collect()
    };
    let mut p = Plot::new(-90.0, 90.0, 0.0, 1.0, 15.0, 0.1);
    for (ch, color) in CHANNEL_COLOURS.iter().enumerate() {
        p.polyline(&series(fiber, 0, ch), *color, false);
        p.polyline(&series(fiber, 1, ch), *color, true);
    }
    p.save(&out.join("a_f_a_b.png"))?;
    let _ = writeln!(
        notes,
        "a_f_a_b.png: x: theta (light inclination) from -90 to 90 deg, grid every 15 deg. y: 0 to \
         1, grid every 0.1. solid = a_f, dashed = a_b; red/green/blue = channel."
    );
    let mut p = Plot::new(-90.0, 90.0, 0.0, 1.0, 15.0, 0.1);
    for (ch, color) in CHANNEL_COLOURS.iter().enumerate() {
        p.polyline(&series(fiber, 0, ch), *color, false);
        p.polyline(&series(&lighter, 0, ch), *color, true);
    }
    p.save(&out.join("a_f_lighter.png"))?;
    let _ = writeln!(
        notes,
        "a_f_lighter.png: a_f against theta (axes as a_f_a_b.png); solid = this fibre, dashed = \
         the same fibre with sigma_a / 4 (lighter hair); red/green/blue = channel."
    );
    Ok(())
}
