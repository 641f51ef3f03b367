use super::*;

#[test]
fn grouped_inserts_thousands_separators() {
    assert_eq!(grouped(0), "0");
    assert_eq!(grouped(999), "999");
    assert_eq!(grouped(1_000), "1,000");
    assert_eq!(grouped(40_000_000), "40,000,000");
}

#[test]
fn cpu_time_reads_in_the_largest_fitting_unit() {
    assert_eq!(cpu_time(0.5), "0.50 CPU-seconds");
    assert_eq!(cpu_time(1200.0), "20 CPU-minutes");
    assert_eq!(cpu_time(9000.0), "2.5 CPU-hours");
}
