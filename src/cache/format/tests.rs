use super::*;

fn header() -> CacheHeader {
    CacheHeader {
        frames: 3,
        particles: 32,
        points_per_guide: 16,
        fps: 30.0,
        start_s: 0.5,
        settle_s: 2.0,
        hairstyle_digest: Digest([1; 32]),
        motion_digest: Digest([2; 32]),
        light_dir: Vec3::new(0.0, -1.0, 0.0),
        map_res: 64,
        simulated: true,
        self_collision: true,
        draw_solids: false,
        hairstyle_name: "smooth".into(),
        motion_label: "clip \"Dance\"".into(),
    }
}

#[test]
fn a_header_reads_back_as_written() {
    let h = header();
    let bytes = h.encode();
    assert_eq!(bytes.len(), h.header_bytes());
    assert_eq!(CacheHeader::decode(&bytes, "c").unwrap(), h);
    // 8 + 32 × 12 + 4 bytes per record, 4 records.
    assert_eq!(h.file_bytes(), bytes.len() as u64 + 4 * 396);
}

#[test]
fn long_names_are_cut_on_a_character_boundary() {
    let mut h = header();
    h.hairstyle_name = "é".repeat(200);
    let back = CacheHeader::decode(&h.encode(), "c").unwrap();
    assert_eq!(back.hairstyle_name, "é".repeat(127));
}

#[test]
fn every_single_bit_flip_in_the_header_is_refused() {
    let bytes = header().encode();
    for at in 0..bytes.len() {
        for bit in 0..8 {
            let mut b = bytes.clone();
            b[at] ^= 1 << bit;
            assert!(
                CacheHeader::decode(&b, "c").is_err(),
                "flip of bit {bit} at byte {at} accepted"
            );
        }
    }
}

#[test]
fn frame_times_are_those_render_computes() {
    let h = header();
    assert_eq!(h.frame_time_s(0), 0.5);
    assert_eq!(h.frame_time_s(7), 0.5 + 7.0 / 30.0f32 as f64);
}
