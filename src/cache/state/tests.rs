use super::*;

#[test]
fn a_record_reads_back_bit_for_bit() {
    let pts = [
        Vec3::new(0.1, -0.2, 0.3),
        Vec3::new(f32::MIN_POSITIVE / 8.0, -0.0, 1e30),
    ];
    let mut bytes = Vec::new();
    encode(5, 1.25, &pts, &mut bytes);
    assert_eq!(bytes.len() as u64, record_bytes(2));
    let mut back = Vec::new();
    assert_eq!(decode(5, &bytes, &mut back), Ok(1.25));
    let bits = |v: &[Vec3]| -> Vec<u32> {
        v.iter()
            .flat_map(|p| p.to_array().map(f32::to_bits))
            .collect()
    };
    assert_eq!(bits(&back), bits(&pts));
    // The same bytes at another index fail their checksum.
    assert!(matches!(
        decode(6, &bytes, &mut back),
        Err(RecordError::Checksum(..))
    ));
}

#[test]
fn a_nan_position_is_refused_even_with_a_good_checksum() {
    let mut bytes = Vec::new();
    encode(
        0,
        0.0,
        &[Vec3::ZERO, Vec3::new(0.0, f32::NAN, 0.0)],
        &mut bytes,
    );
    let mut back = Vec::new();
    assert!(matches!(
        decode(0, &bytes, &mut back),
        Err(RecordError::NotFinite(1, _))
    ));
}
