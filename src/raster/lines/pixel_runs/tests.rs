use glam::Vec3;

use super::*;
use crate::raster::lines::samples::ALL_SAMPLES;

/// A layer stays 24 bytes, as a fragment: a frame keeps millions of them between emission
/// and compositing.
#[test]
fn layer_is_24_bytes() {
    assert_eq!(size_of::<Layer>(), 24);
}

proptest::proptest! {
    /// Grouping by pixel, then sorting each run, gives what a stable library sort by
    /// (pixel, 1/depth) of the fragments in reverse emission order gives, fragment for
    /// fragment, with each run where `starts` says and each colour its segment's at its
    /// place. Fragments carry their emission index in `alpha` to tell ties apart. Depths come from
    /// a few values (many ties), rising along the emission order or not at all, so runs
    /// both stay within the insertion budget and exceed it.
    #[test]
    fn pixel_runs_sort_stably_by_pixel_then_depth(
        raw in proptest::collection::vec((0u32..9, 0u32..6), 0..400),
        slope in 0u32..3,
    ) {
        let pixels = 9;
        let frags: Vec<Frag> = raw
            .iter()
            .enumerate()
            .map(|(i, &(pixel, depth))| Frag {
                pixel,
                iz_bits: (0.5 + 0.1 * (depth + slope * i as u32) as f32).to_bits(),
                alpha: i as f32,
                mask: ALL_SAMPLES,
                seg: i as u32 % 3,
                t: (i % 4) as f32 * 0.25,
            })
            .collect();
        let colors = [
            [Vec3::ZERO, Vec3::ONE],
            [Vec3::X, Vec3::Y],
            [Vec3::splat(0.5), Vec3::Z],
        ];
        // Runs hold reverse emission order, so ties come latest emitted first.
        let mut expected: Vec<Frag> = frags.iter().rev().copied().collect();
        expected.sort_by_key(|f| (f.pixel, f.iz_bits));
        let (mut sorted, mut starts, mut keys) = (Vec::new(), Vec::new(), Vec::new());
        sort_by_pixel(&frags, &colors, &mut sorted, &mut starts, pixels);
        let mut got = Vec::new();
        for p in 0..pixels {
            let run = &mut sorted[starts[p] as usize..starts[p + 1] as usize];
            sort_run(run, &mut keys, &mut Vec::new());
            got.extend(run.iter().map(|l| {
                (p as u32, l.iz_bits, l.alpha.to_bits(), l.color.to_array().map(f32::to_bits))
            }));
        }
        let want: Vec<_> = expected
            .iter()
            .map(|f| {
                let color = color_of(f, &colors).to_array().map(f32::to_bits);
                (f.pixel, f.iz_bits, f.alpha.to_bits(), color)
            })
            .collect();
        proptest::prop_assert_eq!(got, want);
        proptest::prop_assert_eq!(starts[pixels] as usize, frags.len());
    }
}

/// Both ways of sorting a run are taken: a nearly sorted run within the budget, a reversed
/// one beyond it; each ends sorted with ties in order.
#[test]
fn insertion_gives_up_beyond_its_budget_and_keys_finish() {
    let run_of = |depths: &[u32]| -> Vec<Layer> {
        depths
            .iter()
            .enumerate()
            .map(|(i, &d)| Layer {
                iz_bits: (1.0 + d as f32).to_bits(),
                alpha: i as f32,
                color: Vec3::ONE,
                mask: ALL_SAMPLES,
            })
            .collect()
    };
    let nearly = run_of(&[0, 2, 1, 3, 4, 4, 6, 5]);
    let reversed = run_of(&[7, 6, 5, 5, 4, 3, 2, 1, 0]);
    assert!(insertion_sort_by_depth(
        &mut nearly.clone(),
        SHIFT_BUDGET * nearly.len()
    ));
    assert!(!insertion_sort_by_depth(
        &mut reversed.clone(),
        SHIFT_BUDGET * reversed.len()
    ));
    for run in [nearly, reversed] {
        let mut expected = run.clone();
        expected.sort_by_key(|f| f.iz_bits);
        let mut got = run.clone();
        sort_run(&mut got, &mut Vec::new(), &mut Vec::new());
        let order = |v: &[Layer]| v.iter().map(|f| f.alpha.to_bits()).collect::<Vec<_>>();
        assert_eq!(order(&got), order(&expected));
    }
}
