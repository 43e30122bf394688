use super::lock::process_start;
use super::*;

#[test]
fn utc_formats_known_dates() {
    let at = |s: u64| utc(UNIX_EPOCH + std::time::Duration::from_secs(s));
    assert_eq!(at(0), "1970-01-01T00:00:00Z");
    assert_eq!(at(951_782_400), "2000-02-29T00:00:00Z");
    assert_eq!(at(1_709_210_096), "2024-02-29T12:34:56Z");
}

#[test]
fn process_start_of_this_process_is_read() {
    if Path::new("/proc/self/stat").exists() {
        assert!(process_start(std::process::id()).is_some());
    }
}
