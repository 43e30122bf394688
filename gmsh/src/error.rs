//! Typed errors.

/// Errors of the safe gmsh layer.
#[derive(Debug, thiserror::Error)]
pub enum GmshError {
    /// A gmsh C API call reported `ierr != 0`.
    #[error("gmsh call {call} failed (ierr = {ierr}): {message}")]
    Call {
        /// Name of the C function, e.g. `"gmshModelOccGetMass"`.
        call: &'static str,
        /// The `ierr` value it set.
        ierr: i32,
        /// gmsh's last error message (`gmshLoggerGetLastError`). gmsh never
        /// clears it, so for the rare failure that logs nothing it can be the
        /// message of an earlier error.
        message: String,
    },
    /// The loaded libgmsh is not the version the bindings were generated from.
    #[error(
        "loaded gmsh library is version {loaded}, but the gmsh-sys bindings are for {bindings}"
    )]
    VersionMismatch {
        /// `General.Version` of the loaded library.
        loaded: String,
        /// [`gmsh_sys::BINDINGS_GMSH_VERSION`].
        bindings: &'static str,
    },
    /// A string argument (name, option, path) contains a NUL byte.
    #[error("{what} contains a NUL byte: {value:?}")]
    InteriorNul {
        /// Which argument.
        what: &'static str,
        /// Its value.
        value: String,
    },
    /// A path argument is not valid UTF-8 (gmsh takes `char *` file names).
    #[error("path is not valid UTF-8: {0:?}")]
    NonUtf8Path(std::path::PathBuf),
    /// `Session::new` was called on a thread that already holds a session.
    #[error(
        "a gmsh Session is already active on this thread (gmsh allows one session per process)"
    )]
    NestedSession,
}
