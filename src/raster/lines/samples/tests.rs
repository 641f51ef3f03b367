use super::*;

/// The sub-samples are n-rooks on the 4 × 4 grid: every sixteenth of x and of y holds one,
/// every cell of the grid one, and each lies at its sixteenth's centre within ±15/32 of
/// the pixel centre (what `sample_reach` assumes).
#[test]
fn sub_samples_are_n_rooks_on_a_grid() {
    let (mut xs, mut ys, mut cells) = ([0; 16], [0; 16], [0; 16]);
    for g in 0..4 {
        for l in 0..4 {
            let (x, y) = (SAMPLE_X[g][l], SAMPLE_Y[g][l]);
            let (xi, yi) = ((x + 0.5) * 16.0 - 0.5, (y + 0.5) * 16.0 - 0.5);
            assert_eq!(xi, xi.round(), "{x}");
            assert_eq!(yi, yi.round(), "{y}");
            assert!(x.abs() <= 15.0 / 32.0 && y.abs() <= 15.0 / 32.0);
            xs[xi as usize] += 1;
            ys[yi as usize] += 1;
            cells[(xi as usize / 4) * 4 + yi as usize / 4] += 1;
        }
    }
    assert_eq!((xs, ys, cells), ([1; 16], [1; 16], [1; 16]));
    for (n, lanes) in NIBBLE_LANES.iter().enumerate() {
        for l in 0..4 {
            assert_eq!(lanes[l], ((n >> l) & 1) as f32);
        }
    }
}
