use super::*;

#[test]
fn equal_inputs_are_reused_and_any_change_rebuilds() {
    let mut positions = vec![Vec3::ONE; 4];
    let lights = [crate::light::default_light()];
    fn view<'a>(p: &'a [Vec3], lights: &'a [Light]) -> MapInputsView<'a> {
        MapInputsView {
            positions: p,
            tangents: &[],
            lengths_m: &[],
            lights,
            aim_m: Vec3::ZERO,
            solids: &[],
            mesh: &[],
        }
    }
    let mut inputs = MapInputs::default();
    assert!(
        !inputs.unchanged_or_record(&view(&positions, &lights)),
        "first build"
    );
    assert!(inputs.unchanged_or_record(&view(&positions, &lights)));
    positions[2].x = f32::from_bits(positions[2].x.to_bits() + 1);
    assert!(
        !inputs.unchanged_or_record(&view(&positions, &lights)),
        "one ulp moved"
    );
    assert!(inputs.unchanged_or_record(&view(&positions, &lights)));
    positions[0] = Vec3::NAN;
    assert!(!inputs.unchanged_or_record(&view(&positions, &lights)));
    assert!(
        !inputs.unchanged_or_record(&view(&positions, &lights)),
        "NaN never reuses"
    );
    positions[0] = Vec3::ZERO;
    assert!(!inputs.unchanged_or_record(&view(&positions, &lights)));
    assert!(inputs.unchanged_or_record(&view(&positions, &lights)));
}
