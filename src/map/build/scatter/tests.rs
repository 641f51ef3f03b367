//! The guard the scatter's raw writes stand on: the cursors' totals are exact or the sort
//! stops. Counts near `u32::MAX` are given to `cursors` directly (a map of 2^32 pieces would
//! not fit the memory budget, so no build can reach them).

use super::cursors;

/// Two chunks over two columns: the totals, the column starts and each chunk's cursor,
/// worked by hand.
#[test]
fn cursors_place_each_chunk_after_the_earlier_ones() {
    // Chunk 0 counts (2, 1), chunk 1 counts (3, 4): column 0 holds 5 pieces from 0, column 1
    // holds 5 from 5; chunk 1 writes column 0 from 2 and column 1 from 6.
    let mut counts = vec![2, 1, 3, 4];
    let (mut starts, mut running) = (Vec::new(), vec![0u32; 2]);
    let total = cursors(&mut counts, &mut starts, &mut running);
    assert_eq!(total, 10);
    assert_eq!(starts, [0, 5, 10]);
    assert_eq!(counts, [0, 5, 2, 6]);
}

/// Totals that reach `u32::MAX` exactly are still exact.
#[test]
fn a_total_of_u32_max_is_exact() {
    let mut counts = vec![u32::MAX - 1, 1];
    let (mut starts, mut running) = (Vec::new(), vec![0u32; 2]);
    assert_eq!(cursors(&mut counts, &mut starts, &mut running), u32::MAX);
    assert_eq!(starts, [0, u32::MAX - 1, u32::MAX]);
}

/// Two columns whose prefix passes `u32::MAX` by one: unchecked, the total wraps to 0 and the
/// second column's start to 0, so both columns' pieces would be written over each other.
#[test]
#[should_panic(expected = "passed u32::MAX")]
fn a_prefix_past_u32_max_stops_the_sort() {
    let mut counts = vec![u32::MAX, 1];
    let (mut starts, mut running) = (Vec::new(), vec![0u32; 2]);
    cursors(&mut counts, &mut starts, &mut running);
}

/// Two chunks whose counts in one column add past `u32::MAX`.
#[test]
#[should_panic(expected = "passed u32::MAX")]
fn a_column_total_past_u32_max_stops_the_sort() {
    let mut counts = vec![u32::MAX, 1];
    let (mut starts, mut running) = (Vec::new(), vec![0u32; 1]);
    cursors(&mut counts, &mut starts, &mut running);
}
