//! Advisories: what a hairstyle may legally ask for but the renderer is measured to get wrong.
//!
//! A rule of `Hairstyle::validate` refuses a file; an advisory lets it load and says what the
//! picture will suffer and which field fixes it. Each advisory cites the measurement it rests
//! on, so its threshold is not a matter of taste.

use super::spec::Hairstyle;

/// Largest turn of a curl's helix per render-strand segment, degrees, that the light between
/// the points is right for. Measured against a path tracer (ACCURACY.md §2, "Curls need their
/// points": the curly preset back-lit, single scattering; turns at its mean strand length):
/// 52° per segment (7 per turn) read 16–26% too bright, 26° (14 per turn) 4–6%, 13° 3–6%;
/// the error is in the light averaged along a segment that cuts across the curl (the shadows
/// alone: "along the fibre" 1.174 at 52°, 1.016 at 26°).
pub const MAX_CURL_TURN_PER_SEGMENT_DEG: f32 = 30.0;

/// One advisory: the field to change and why, in words for a user.
#[derive(Clone, Debug, PartialEq)]
pub struct Advisory {
    /// Dotted path of the field that fixes it (as in validation errors).
    pub field: String,
    pub message: String,
}

impl Hairstyle {
    /// What this (valid) hairstyle asks for that the renderer is measured to get wrong; empty
    /// for the presets.
    pub fn advisories(&self) -> Vec<Advisory> {
        self.curl_resolution_advisory().into_iter().collect()
    }

    /// The helix turn per segment on the longest strands (their segments are longest: every
    /// strand has the same number of points), degrees; `None` for straight hair.
    pub fn curl_turn_per_segment_deg(&self) -> Option<f32> {
        let curl = &self.curl;
        if !(curl.radius_m > 0.0 && curl.period_m > 0.0) || self.strands.points < 2 {
            return None;
        }
        let segment_m = self.max_length_m() / (self.strands.points - 1) as f32;
        Some(360.0 * segment_m / curl.period_m)
    }

    fn curl_resolution_advisory(&self) -> Option<Advisory> {
        let turn = self.curl_turn_per_segment_deg()?;
        if turn <= MAX_CURL_TURN_PER_SEGMENT_DEG {
            return None;
        }
        // The turn scales as 1/segments: this many bring it to the limit.
        let segments =
            ((self.strands.points - 1) as f32 * turn / MAX_CURL_TURN_PER_SEGMENT_DEG).ceil() as u64;
        Some(Advisory {
            field: "strands.points".into(),
            message: format!(
                "curls of period {:.1} mm turn {turn:.0}° per segment on the longest strands \
                 ({} points over {:.0} mm); beyond {MAX_CURL_TURN_PER_SEGMENT_DEG:.0}° the light \
                 between the points is wrong (measured against a path tracer: 7 segments per \
                 turn read back-lit curls 16-26% too bright, 14 per turn 4-6%); {} points or \
                 more keep it under {MAX_CURL_TURN_PER_SEGMENT_DEG:.0}°, at a cost linear in \
                 the points",
                self.curl.period_m * 1e3,
                self.strands.points,
                self.max_length_m() * 1e3,
                segments + 1,
            ),
        })
    }
}

#[cfg(test)]
mod tests;
