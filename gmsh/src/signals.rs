//! gmsh leaves the process's signal handling as it found it. Its
//! `gmshInitialize` (through OpenCASCADE's signal set-up) installs handlers
//! of its own for about a dozen signals (SIGHUP, SIGTERM, SIGSEGV, SIGFPE,
//! SIGBUS, ...), and the session leaves several of them at their defaults;
//! a program's own SIGTERM handling was gone after the first mesh was
//! read, and a SIGTERM delivered to a thread that has it unblocked (gmsh
//! starts one from its library constructor, before `main`) then killed the
//! process outright. [`KeptDispositions`] records every signal's
//! disposition and puts it back.

use std::os::raw::c_int;

/// Every standard signal's disposition (SIGKILL and SIGSTOP have none to
/// keep), as read at [`KeptDispositions::now`].
pub(crate) struct KeptDispositions(Vec<(c_int, libc::sigaction)>);

impl KeptDispositions {
    /// Reads the dispositions of signals 1–31.
    pub(crate) fn now() -> KeptDispositions {
        let read = |sig: c_int| {
            // SAFETY: reads the disposition into a zeroed struct.
            unsafe {
                let mut act: libc::sigaction = std::mem::zeroed();
                (libc::sigaction(sig, std::ptr::null(), &mut act) == 0).then_some((sig, act))
            }
        };
        KeptDispositions(
            (1..32)
                .filter(|&s| s != libc::SIGKILL && s != libc::SIGSTOP)
                .filter_map(read)
                .collect(),
        )
    }

    /// Puts back the dispositions read by [`Self::now`].
    pub(crate) fn restore(&self) {
        for (sig, act) in &self.0 {
            // SAFETY: sets a disposition read by `now`.
            unsafe {
                libc::sigaction(*sig, act, std::ptr::null_mut());
            }
        }
    }
}
