//! Raw FFI bindings to the gmsh C API (`gmshc.h`).
//!
//! The bindings in `bindings.rs` were generated once by bindgen from the C
//! header of the pinned official gmsh wheel (see `generate.sh`, which records
//! the exact command) and are checked in: the build never runs bindgen.
//! `build.rs` only locates the shared library installed by `make setup`
//! (`.venv/lib/libgmsh.so`) or the directory in the env var `GMSH_LIB_DIR`.
//!
//! All functions are `unsafe`. Every call takes a trailing `ierr: *mut c_int`
//! that is set to a non-zero value on error (the message is then available
//! from [`gmshLoggerGetLastError`]), and every array or string that gmsh
//! returns is allocated with `gmshMalloc` and must be released with
//! [`gmshFree`]. Use the safe `gmsh` crate instead of calling these directly.
//!
//! The bindings match exactly one gmsh API version, [`BINDINGS_GMSH_VERSION`]:
//! the C API changes signatures between minor versions (e.g. the crates.io
//! `gmsh-sys` 0.1.2, generated from gmsh 4.4, crashes against 4.15), so the
//! safe layer compares it with the loaded library's `General.Version`.

#![allow(non_upper_case_globals, non_camel_case_types, non_snake_case)]
#![allow(clippy::all)]

/// The gmsh version of the `gmshc.h` the bindings were generated from.
pub const BINDINGS_GMSH_VERSION: &str = "4.15.2";

include!("bindings.rs");

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_version_matches_constant() {
        let header = std::str::from_utf8(&GMSH_API_VERSION[..GMSH_API_VERSION.len() - 1]).unwrap();
        assert_eq!(header, BINDINGS_GMSH_VERSION);
        assert_eq!(
            format!("{GMSH_API_VERSION_MAJOR}.{GMSH_API_VERSION_MINOR}.{GMSH_API_VERSION_PATCH}"),
            BINDINGS_GMSH_VERSION
        );
    }

    /// Raw smoke test of the ABI: initialize, read `General.Version`, free it,
    /// finalize. (The only test in this binary that calls gmsh.)
    #[test]
    fn raw_initialize_version_finalize() {
        use std::ffi::{CStr, CString};
        use std::os::raw::{c_char, c_int};
        let mut ierr: c_int = 0;
        let mut argv: [*mut c_char; 1] = [std::ptr::null_mut()];
        unsafe {
            gmshInitialize(0, argv.as_mut_ptr(), 0, 0, &mut ierr);
            assert_eq!(ierr, 0);
            assert_eq!(gmshIsInitialized(&mut ierr), 1);
            let terminal = CString::new("General.Terminal").unwrap();
            gmshOptionSetNumber(terminal.as_ptr(), 0.0, &mut ierr);
            assert_eq!(ierr, 0);
            let name = CString::new("General.Version").unwrap();
            let mut value: *mut c_char = std::ptr::null_mut();
            gmshOptionGetString(name.as_ptr(), &mut value, &mut ierr);
            assert_eq!(ierr, 0);
            let version = CStr::from_ptr(value).to_str().unwrap().to_owned();
            gmshFree(value.cast());
            assert_eq!(version, BINDINGS_GMSH_VERSION);
            gmshFinalize(&mut ierr);
            assert_eq!(ierr, 0);
        }
    }
}
