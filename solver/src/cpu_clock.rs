//! CPU time of the calling thread: what a position of a parallel sweep
//! costs, unaffected by other work sharing the cores (wall-clock time of a
//! thread that waits for a core would count the wait); and of the whole
//! process, for a command's total.

/// Seconds of CPU time of the clock `id` (a CPU-time clock of Linux).
fn cpu_clock_s(id: libc::clockid_t, name: &str) -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: a valid out-pointer; the CPU-time clocks exist on Linux.
    let rc = unsafe { libc::clock_gettime(id, &mut ts) };
    assert_eq!(rc, 0, "clock_gettime({name}) failed");
    ts.tv_sec as f64 + 1e-9 * ts.tv_nsec as f64
}

/// Seconds of CPU time the calling thread has used so far.
pub fn thread_cpu_s() -> f64 {
    cpu_clock_s(libc::CLOCK_THREAD_CPUTIME_ID, "CLOCK_THREAD_CPUTIME_ID")
}

/// Runs `f` and returns its result with the CPU seconds it took on this thread.
pub fn timed<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let t = thread_cpu_s();
    let out = f();
    (out, thread_cpu_s() - t)
}

/// Seconds of CPU time the whole process (all its threads, not its
/// children) has used so far.
pub fn process_cpu_s() -> f64 {
    cpu_clock_s(libc::CLOCK_PROCESS_CPUTIME_ID, "CLOCK_PROCESS_CPUTIME_ID")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn busy_loop_uses_cpu_time_and_sleep_does_not() {
        let (_, busy) = timed(|| {
            let mut x = 0u64;
            let t = std::time::Instant::now();
            while t.elapsed().as_millis() < 50 {
                x = x.wrapping_add(std::hint::black_box(1));
            }
            x
        });
        let (_, slept) = timed(|| std::thread::sleep(std::time::Duration::from_millis(50)));
        assert!(busy > 0.01, "busy loop took {busy} s of CPU");
        assert!(slept < 0.01, "sleep took {slept} s of CPU");
    }
}
