//! Scenes from earlier runs for the same plot (`--plot-with A.json,…`): the quality part of a
//! `wisp bench --json` report read back as one scene's points, so that one picture holds a
//! curve per scene (a run of the bench measures one hairstyle).

use super::ScenePoints;
use crate::cli::AppError;
use crate::cli::bench_cmd::quality::LevelPoint;
use serde_json::Value;
use std::path::Path;
use wisp::quality::Quality;

/// The scene of the report at `path`: its hairstyle's name and its levels' points. Refused
/// (exit 2) naming the file and the field when it is not such a report.
pub fn read_report(path: &Path) -> Result<ScenePoints, AppError> {
    let bad = |what: String| {
        AppError::input(anyhow::anyhow!(
            "--plot-with {}: {what}; give a file `wisp bench --quality-list … --json FILE` wrote",
            path.display()
        ))
    };
    let text = std::fs::read_to_string(path).map_err(|e| bad(format!("cannot read it ({e})")))?;
    let report: Value = serde_json::from_str(&text).map_err(|e| bad(format!("not JSON ({e})")))?;
    let name = report["hairstyle"]
        .as_str()
        .ok_or_else(|| bad("`hairstyle` is missing or not a string".into()))?;
    let entries = report["quality"]
        .as_array()
        .filter(|e| !e.is_empty())
        .ok_or_else(|| bad("`quality` is missing or empty (no quality part)".into()))?;
    let mut points = Vec::new();
    for (i, entry) in entries.iter().enumerate() {
        points.push(level_point(entry).map_err(|field| bad(format!("quality[{i}].{field}")))?);
    }
    // The most accurate level run is the truth of its comparison, at error 0 (as the live
    // report plots it).
    let has = |q: Quality| points.iter().any(|p: &LevelPoint| p.level == q);
    let (reference, both) = (
        has(Quality::Reference),
        has(Quality::Preview) && has(Quality::Final),
    );
    for p in &mut points {
        if reference && p.level == Quality::Reference {
            p.vs_reference = Some(0.0);
        }
        if both && p.level == Quality::Final {
            p.vs_final = Some(0.0);
        }
    }
    Ok(ScenePoints {
        name: name.to_string(),
        points,
    })
}

/// One entry's point: its level, the total ms of its row on the most threads, and its mean
/// luminance errors; `Err` names the field that is wrong.
fn level_point(entry: &Value) -> Result<LevelPoint, String> {
    let level = entry["level"]
        .as_str()
        .and_then(Quality::from_name)
        .ok_or("level: not preview, final or reference")?;
    let ms = entry["timings"]
        .as_array()
        .and_then(|rows| {
            rows.iter()
                .filter_map(|r| Some((r["threads"].as_u64()?, r["total_ms"].as_f64()?)))
                .max_by_key(|&(threads, _)| threads)
        })
        .map(|(_, ms)| ms)
        .filter(|ms| ms.is_finite() && *ms > 0.0)
        .ok_or("timings: no row with threads and a positive total_ms")?;
    let error = |key: &str| -> Result<Option<f64>, String> {
        match &entry[key] {
            Value::Null => Ok(None),
            v => v["mean_rel_luminance"]
                .as_f64()
                .filter(|e| e.is_finite() && *e >= 0.0)
                .map(Some)
                .ok_or(format!("{key}.mean_rel_luminance: not a number ≥ 0")),
        }
    };
    Ok(LevelPoint {
        level,
        ms,
        vs_reference: error("vs_reference")?,
        vs_final: error("vs_final")?,
    })
}

#[cfg(test)]
mod tests;
