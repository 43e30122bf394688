//! The machine's memory, for the local executor's bound and the Slurm
//! jobs' `--mem`.

/// Memory available now (`MemAvailable` of /proc/meminfo), MB; None where
/// it cannot be read.
pub fn available_mb() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024)
}
