//! A small safe layer over the gmsh C API ([`gmsh_sys`], gmsh 4.15.2).
//!
//! # Sessions
//!
//! gmsh keeps all its state (models, options, meshes) in process-wide globals
//! and is not thread-safe. A [`Session`] is the only way to call it: creating
//! one takes a process-wide lock, calls `gmshInitialize`, and dropping it calls
//! `gmshFinalize` and releases the lock. A second [`Session::new`] on another
//! thread therefore waits until the first session is dropped; sessions in
//! sequence each start from a clean gmsh. A nested [`Session::new`] on the
//! thread that already holds one returns [`GmshError::NestedSession`] instead of
//! deadlocking. A `Session` is neither `Send` nor `Sync`: use it on the thread
//! that created it.
//!
//! A session leaves the process's signal dispositions as it found them
//! (gmsh installs and resets handlers of its own; see `signals.rs`).
//!
//! Terminal output of gmsh is switched off (`General.Terminal = 0`) unless the
//! environment variable `GMSH_VERBOSE` is set.
//!
//! # Errors
//!
//! Every call checks gmsh's `ierr`; a failure becomes [`GmshError::Call`] with
//! the C function name and gmsh's last error message. Arrays and strings that
//! gmsh allocates are copied into Rust values and released with `gmshFree`.
//! Entities are `(dim, tag)` pairs, [`DimTag`]; mesh node and element tags are
//! `usize` (C `size_t`).
//!
//! # Linking and rpath (for crates that use `gmsh`)
//!
//! `gmsh-sys` links `libgmsh.so` from the directory in `GMSH_LIB_DIR` or in
//! `<workspace>/.venv/gmsh-paths.env` (written by `make setup`). That
//! directory is not on the loader's search path, so every executable that
//! links gmsh needs an rpath. Cargo passes `cargo:rustc-link-arg` only to the
//! targets of the package whose build script prints it, so this crate's
//! build script covers its own tests, and **every crate with binaries, tests,
//! examples or benches that use `gmsh` needs this `build.rs`**, and `gmsh` as
//! a direct dependency under `[dependencies]`, which provides
//! `DEP_GMSH_SAFE_LIBDIR` via `links = "gmsh-safe"` (build scripts see the
//! `links` metadata of direct normal dependencies only: not of
//! `[dev-dependencies]`, and not of `gmsh-sys` through `gmsh`):
//!
//! ```text
//! fn main() {
//!     let dir = std::env::var("DEP_GMSH_SAFE_LIBDIR").expect("the gmsh crate exports its library dir");
//!     println!("cargo:rustc-link-arg=-Wl,-rpath,{dir}");
//!     println!("cargo:rerun-if-changed=build.rs");
//! }
//! ```
//!
//! (A crate that depends on `gmsh-sys` directly gets the same directory as
//! `DEP_GMSH_LIBDIR`.)
//!
//! # Example
//!
//! ```no_run
//! let gmsh = gmsh::Session::new()?;
//! gmsh.add_model("demo")?;
//! let vol = gmsh.occ_add_box(0.0, 0.0, 0.0, 1.0, 2.0, 3.0)?;
//! gmsh.occ_synchronize()?;
//! assert!((gmsh.occ_get_mass(3, vol)? - 6.0).abs() < 1e-12);
//! # Ok::<(), gmsh::GmshError>(())
//! ```

mod error;
mod ffi;
mod mesh;
mod model;
mod occ;
mod session;
mod signals;

pub use error::GmshError;
pub use session::Session;

/// A gmsh entity: `(dimension, tag)`.
pub type DimTag = (i32, i32);

/// Result of the OCC boolean operations: the resulting entities and, for each
/// input entity (objects first, then tools), the entities it became.
pub type BooleanResult = (Vec<DimTag>, Vec<Vec<DimTag>>);

/// Result of [`Session::mesh_get_elements`]: `(element types, element tags
/// per type, node tags per type)`.
pub type MeshElements = (Vec<i32>, Vec<Vec<usize>>, Vec<Vec<usize>>);

/// Shorthand for `Result<T, GmshError>`.
pub type Result<T, E = GmshError> = std::result::Result<T, E>;

/// The gmsh version the bindings were generated from; [`Session::new`]
/// requires the loaded library to report exactly this `General.Version`.
pub const GMSH_VERSION: &str = gmsh_sys::BINDINGS_GMSH_VERSION;
