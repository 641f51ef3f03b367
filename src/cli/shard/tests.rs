use super::*;

#[test]
fn shards_cover_every_frame_once_in_order() {
    for len in [0u32, 1, 2, 7, 240, 1001] {
        for count in [1u32, 2, 3, 8, 300] {
            let mut next = 5;
            for index in 1..=count {
                let b = Shard { index, count }.block(5..5 + len);
                assert_eq!(b.start, next, "len {len}, shard {index}/{count}");
                assert!(b.len() as u32 <= len.div_ceil(count));
                next = b.end;
            }
            assert_eq!(next, 5 + len);
        }
    }
}

#[test]
fn shard_flags_are_checked() {
    assert_eq!(parse_shard("2/8"), Ok(Shard { index: 2, count: 8 }));
    assert!(parse_shard("0/8").unwrap_err().contains("numbered from 1"));
    assert!(parse_shard("9/8").unwrap_err().contains("1..=8"));
    assert!(parse_shard("1/0").unwrap_err().contains("N must be"));
    assert!(parse_shard("3").unwrap_err().contains("expected I/N"));
    assert!(
        parse_shard("a/2")
            .unwrap_err()
            .contains("not a whole number")
    );
    assert!(parse_shard("1/100001").is_err());
}
