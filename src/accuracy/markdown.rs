//! The map-against-reference rows as the Markdown tables of ACCURACY.md: error and bias binned
//! by the reference's T_f, and calibration binned by the map's own.

use crate::accuracy::Row;
use crate::accuracy::comparison::{BIN_EDGES, Bin};

/// A row's label: N, and the columns per cell when they are not 1, marking the default.
fn label(r: &Row) -> String {
    let cols = if r.lateral > 1 {
        format!(" × {} cols", r.lateral)
    } else {
        String::new()
    };
    let mark = if r.is_default { " **(default)**" } else { "" };
    format!("{}{cols}{mark}", r.n)
}

/// The rows as Markdown tables (error binned by truth, and calibration binned by the estimate).
pub fn markdown(rows: &[Row]) -> String {
    let bins: Vec<String> = (0..4)
        .map(|b| format!("{:.1}–{:.1}", BIN_EDGES[b], BIN_EDGES[b + 1]))
        .collect();
    let mut s = String::new();
    s += &format!(
        "| N | cell (mm) | map ms | T_f MAE | overall bias | bias, true T_f {} | lum. rel. RMS | lum. map ÷ ref |\n",
        bins.join(" / ")
    );
    s += "|---|---|---|---|---|---|---|---|\n";
    for r in rows {
        let c = &r.comparison;
        s += &format!(
            "| {} | {:.2} | {:.1} | {:.4} | {:+.4} | {} | {:.3} | {:.3} |\n",
            label(r),
            r.ds_mm,
            r.ms,
            c.mae,
            c.overall_bias,
            bias_per_bin(&c.by_truth),
            r.luminance_rel_rms,
            r.luminance_ratio
        );
    }
    s += "\nCalibration (bias binned by the map's own T_f):\n\n";
    s += &format!("| N | bias, map T_f {} |\n|---|---|\n", bins.join(" / "));
    for r in rows {
        s += &format!(
            "| {} | {} |\n",
            label(r),
            bias_per_bin(&r.comparison.by_estimate)
        );
    }
    s
}

/// A table cell of the bias in each bin with its count, "—" for an empty bin, " / " between.
pub fn bias_per_bin(bins: &[Bin; 4]) -> String {
    let cells: Vec<String> = bins
        .iter()
        .map(|b| match b.count {
            0 => "—".to_string(),
            n => format!("{:+.3} ({n})", b.bias),
        })
        .collect();
    cells.join(" / ")
}
