//! A gmsh session leaves the process's signal handling as it found it:
//! gmsh's initialization installs handlers of its own for about a dozen
//! signals and leaves several at their defaults afterwards, which took a
//! program's SIGTERM handling away after the first mesh it read.

use gmsh::Session;

extern "C" fn marker(_: libc::c_int) {}

/// The handler address of every standard signal.
fn handlers() -> Vec<(i32, usize)> {
    (1..32)
        .filter(|&s| s != libc::SIGKILL && s != libc::SIGSTOP)
        .map(|s| {
            // SAFETY: reads a disposition into a zeroed struct.
            let act = unsafe {
                let mut act: libc::sigaction = std::mem::zeroed();
                libc::sigaction(s, std::ptr::null(), &mut act);
                act
            };
            (s, act.sa_sigaction)
        })
        .collect()
}

#[test]
fn a_session_leaves_every_signal_disposition_as_it_found_it() {
    for sig in [libc::SIGTERM, libc::SIGHUP, libc::SIGINT] {
        // SAFETY: installs a handler that does nothing.
        unsafe {
            let mut act: libc::sigaction = std::mem::zeroed();
            act.sa_sigaction = marker as *const () as usize;
            libc::sigemptyset(&mut act.sa_mask);
            libc::sigaction(sig, &act, std::ptr::null_mut());
        }
    }
    let before = handlers();
    let s = Session::new().unwrap();
    assert_eq!(handlers(), before, "changed by gmshInitialize");
    s.option_set_number("General.Terminal", 0.0).unwrap();
    drop(s);
    assert_eq!(handlers(), before, "changed by gmshFinalize");
}
