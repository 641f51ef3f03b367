//! Parsers of the command line's numbers and vectors: each refuses what the engine cannot
//! take (non-finite, out of range) with a message clap prints after the flag's name.

use glam::Vec3;

/// Highest `--speed` (a clip played a thousand times faster is a blur).
pub const MAX_SPEED: f32 = 1000.0;
/// Highest `--fps`.
pub const MAX_FPS: f32 = 1000.0;

/// A budget: a finite number > 0, at most 10⁶.
pub fn parse_budget(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 && v <= 1e6 => Ok(v),
        Ok(v) => Err(format!("must be a number in (0, 1e6] (got {v})")),
        Err(_) => Err(format!("`{s}` is not a number")),
    }
}

/// A playback speed in (0, [`MAX_SPEED`]].
pub fn parse_speed(s: &str) -> Result<f32, String> {
    let v = parse_positive_f32(s)?;
    if v > MAX_SPEED {
        return Err(format!("must be at most {MAX_SPEED} (got {v})"));
    }
    Ok(v)
}

/// A frame rate in (0, [`MAX_FPS`]].
pub fn parse_fps(s: &str) -> Result<f32, String> {
    let v = parse_positive_f32(s)?;
    if v > MAX_FPS {
        return Err(format!("must be at most {MAX_FPS} (got {v})"));
    }
    Ok(v)
}

/// Longest contact-shadow window, millimetres (a metre holds any head of hair whole).
pub const MAX_CONTACT_MM: f32 = 1000.0;

/// A contact-shadow window in millimetres: 0 (off) to [`MAX_CONTACT_MM`].
pub fn parse_contact_mm(s: &str) -> Result<f32, String> {
    let v = parse_finite_f32(s)?;
    if (0.0..=MAX_CONTACT_MM).contains(&v) {
        Ok(v)
    } else {
        Err(format!("must be 0 (off) to {MAX_CONTACT_MM} mm (got {v})"))
    }
}

/// A finite f64 (times in seconds, which may exceed f32 precision).
pub fn parse_finite_f64(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(v) if v.is_infinite() && !s.trim().to_ascii_lowercase().contains("inf") => Err(format!(
            "{} is outside the range of a 64-bit float (about ±1.8e308)",
            s.trim()
        )),
        Ok(v) => Err(format!("must be finite (got {v})")),
        Err(_) => Err(format!("`{s}` is not a number")),
    }
}

/// A finite number > 0. Parsed as f64 first, so that 1e308 is reported as written, not as the
/// infinity f32 would make of it.
pub fn parse_positive_f32(s: &str) -> Result<f32, String> {
    let v = parse_finite_f32(s)?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(format!("must be a finite number > 0 (got {v})"))
    }
}

/// A number for a validator to judge (NaN and infinities pass through), refusing only a finite
/// number f32 cannot hold, which would otherwise arrive as "inf".
pub fn parse_f32_as_written(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v.abs() > f32::MAX as f64 => Err(format!(
            "{} is outside the range of a 32-bit float (about ±3.4e38)",
            s.trim()
        )),
        Ok(v) => Ok(v as f32),
        Err(_) => Err(format!("`{s}` is not a number")),
    }
}

/// A finite number that f32 holds.
pub fn parse_finite_f32(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v.abs() <= f32::MAX as f64 => Ok(v as f32),
        Ok(v) if v.is_finite() => Err(format!(
            "{} is outside the range of a 32-bit float (about ±3.4e38)",
            s.trim()
        )),
        Ok(v) => Err(format!("must be finite (got {v})")),
        Err(_) => Err(format!("`{s}` is not a number")),
    }
}

/// `X,Y,Z`: three finite numbers.
pub fn parse_point(s: &str) -> Result<Vec3, String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 3 {
        return Err(format!("expected three numbers X,Y,Z (got `{s}`)"));
    }
    let mut v = [0.0f32; 3];
    for (o, p) in v.iter_mut().zip(&parts) {
        *o = parse_finite_f32(p)?;
    }
    Ok(Vec3::from(v))
}

/// `X,Y,Z`: three finite numbers, not all zero.
pub fn parse_direction(s: &str) -> Result<Vec3, String> {
    let v = parse_point(s)?;
    if v.length_squared() < 1e-12 {
        return Err("the direction must not be zero".into());
    }
    // Scaled by its largest component first: 1e30,1e30,1e30 squares to infinity and
    // normalised to zero.
    Ok((v / v.abs().max_element()).normalize())
}

/// `V` or `R,G,B`: finite numbers >= 0 (one number is grey).
pub fn parse_rgb(s: &str) -> Result<Vec3, String> {
    let parts: Vec<&str> = s.split(',').collect();
    let values = parts
        .iter()
        .map(|p| parse_finite_f32(p))
        .collect::<Result<Vec<f32>, String>>()?;
    let v = match values[..] {
        [g] => Vec3::splat(g),
        [r, g, b] => Vec3::new(r, g, b),
        _ => return Err(format!("expected one number or three R,G,B (got `{s}`)")),
    };
    if v.min_element() < 0.0 {
        return Err(format!("must be >= 0 (got `{s}`)"));
    }
    Ok(v)
}

#[cfg(test)]
mod tests;

/// A camera framing by name (`wisp::scene::Framing`).
pub fn parse_framing(s: &str) -> Result<wisp::scene::Framing, String> {
    wisp::scene::Framing::from_name(s)
        .ok_or_else(|| format!("must be head, upper or full (got {s:?})"))
}

/// A quality level by name (`wisp::quality::Quality`).
pub fn parse_quality(s: &str) -> Result<wisp::quality::Quality, String> {
    wisp::quality::Quality::from_name(s)
        .ok_or_else(|| format!("must be preview, final or reference (got {s:?})"))
}
