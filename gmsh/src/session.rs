//! The process-wide gmsh session, options, file I/O and logger.

use std::cell::Cell;
use std::marker::PhantomData;
use std::os::raw::{c_char, c_int};
use std::path::Path;
use std::sync::{Mutex, MutexGuard, PoisonError};

use gmsh_sys as sys;

use crate::ffi::{check, cpath, cstr, OutStr};
use crate::signals::KeptDispositions;
use crate::{GmshError, Result};

/// gmsh is process-global: at most one initialized session at a time.
static GMSH_LOCK: Mutex<()> = Mutex::new(());

thread_local! {
    /// Whether this thread holds the session (a nested `Session::new` would
    /// deadlock on `GMSH_LOCK`).
    static HOLDS_SESSION: Cell<bool> = const { Cell::new(false) };
}

/// An initialized gmsh (`gmshInitialize` ... `gmshFinalize`), holding the
/// process-wide gmsh lock for its lifetime. All API calls are methods on it.
///
/// Neither `Send` nor `Sync`: gmsh is not thread-safe and the lock guard
/// must be released on the thread that took it.
pub struct Session {
    _guard: MutexGuard<'static, ()>,
    /// The signal dispositions before `gmshInitialize`, put back after it
    /// and after `gmshFinalize`.
    dispositions: KeptDispositions,
    _not_send_sync: PhantomData<*const ()>,
}

impl std::fmt::Debug for Session {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Session").finish_non_exhaustive()
    }
}

impl Session {
    /// Takes the process-wide gmsh lock (waiting while another thread holds a
    /// session), calls `gmshInitialize(0, argv = {NULL}, readConfigFiles = 0,
    /// run = 0)`, sets `General.Terminal = 0` unless the env var
    /// `GMSH_VERBOSE` is set, and checks that the loaded library's
    /// `General.Version` equals [`gmsh_sys::BINDINGS_GMSH_VERSION`]
    /// ([`GmshError::VersionMismatch`] otherwise).
    ///
    /// Returns [`GmshError::NestedSession`] if this thread already holds one.
    pub fn new() -> Result<Session> {
        if HOLDS_SESSION.with(Cell::get) {
            return Err(GmshError::NestedSession);
        }
        // A panic while a session was alive poisons the lock, but the
        // session's Drop has finalized gmsh by then: the state is clean.
        let guard = GMSH_LOCK.lock().unwrap_or_else(PoisonError::into_inner);

        let dispositions = KeptDispositions::now();
        let mut argv: [*mut c_char; 1] = [std::ptr::null_mut()];
        let initialized = check("gmshInitialize", |ierr| {
            // SAFETY: argc = 0 with a NULL-terminated argv; no config files,
            // no GUI/batch run.
            unsafe { sys::gmshInitialize(0, argv.as_mut_ptr(), 0, 0, ierr) }
        });
        dispositions.restore();
        initialized?;
        HOLDS_SESSION.with(|h| h.set(true));
        // From here on, Drop finalizes gmsh (also on the error returns below).
        let session = Session {
            _guard: guard,
            dispositions,
            _not_send_sync: PhantomData,
        };

        if std::env::var_os("GMSH_VERBOSE").is_none() {
            session.option_set_number("General.Terminal", 0.0)?;
        }
        let loaded = session.option_get_string("General.Version")?;
        if loaded != gmsh_sys::BINDINGS_GMSH_VERSION {
            return Err(GmshError::VersionMismatch {
                loaded,
                bindings: gmsh_sys::BINDINGS_GMSH_VERSION,
            });
        }
        Ok(session)
    }

    /// The loaded library's version (`General.Version`).
    pub fn version(&self) -> Result<String> {
        self.option_get_string("General.Version")
    }

    // ----------------------------------------------------------------- options

    /// Sets a numerical option (`gmshOptionSetNumber`), e.g.
    /// `("Mesh.MshFileVersion", 4.1)`.
    pub fn option_set_number(&self, name: &str, value: f64) -> Result<()> {
        let name = cstr("option name", name)?;
        // SAFETY: valid C string.
        check("gmshOptionSetNumber", |ierr| unsafe {
            sys::gmshOptionSetNumber(name.as_ptr(), value, ierr)
        })
    }

    /// Gets a numerical option (`gmshOptionGetNumber`).
    pub fn option_get_number(&self, name: &str) -> Result<f64> {
        let name = cstr("option name", name)?;
        let mut value = 0.0;
        // SAFETY: valid C string and out-pointer.
        check("gmshOptionGetNumber", |ierr| unsafe {
            sys::gmshOptionGetNumber(name.as_ptr(), &mut value, ierr)
        })?;
        Ok(value)
    }

    /// Sets a string option (`gmshOptionSetString`).
    pub fn option_set_string(&self, name: &str, value: &str) -> Result<()> {
        let name = cstr("option name", name)?;
        let value = cstr("option value", value)?;
        // SAFETY: valid C strings.
        check("gmshOptionSetString", |ierr| unsafe {
            sys::gmshOptionSetString(name.as_ptr(), value.as_ptr(), ierr)
        })
    }

    /// Gets a string option (`gmshOptionGetString`), e.g. `"General.Version"`.
    pub fn option_get_string(&self, name: &str) -> Result<String> {
        let name = cstr("option name", name)?;
        let mut out = OutStr::new();
        // SAFETY: valid C string; gmsh allocates the result (freed by OutStr).
        check("gmshOptionGetString", |ierr| unsafe {
            sys::gmshOptionGetString(name.as_ptr(), out.ptr(), ierr)
        })?;
        Ok(out.to_string())
    }

    // ---------------------------------------------------------------------- io

    /// Writes the current model to a file (`gmshWrite`); the format follows
    /// the extension (`.msh`, `.brep`, `.step`, `.vtk`, ...). For `.msh` the
    /// version is the option `Mesh.MshFileVersion`.
    pub fn write(&self, path: impl AsRef<Path>) -> Result<()> {
        let path = cpath(path.as_ref())?;
        // SAFETY: valid C string.
        check("gmshWrite", |ierr| unsafe {
            sys::gmshWrite(path.as_ptr(), ierr)
        })
    }

    /// Opens a file (`gmshOpen`); a file with model data creates a new model.
    pub fn open(&self, path: impl AsRef<Path>) -> Result<()> {
        let path = cpath(path.as_ref())?;
        // SAFETY: valid C string.
        check("gmshOpen", |ierr| unsafe {
            sys::gmshOpen(path.as_ptr(), ierr)
        })
    }

    // ------------------------------------------------------------------ logger

    /// gmsh's last error message (`gmshLoggerGetLastError`); empty if none.
    pub fn last_error(&self) -> Result<String> {
        crate::ffi::last_error()
    }
}

impl Drop for Session {
    /// Calls `gmshFinalize`, puts the signal dispositions back, then
    /// releases the process-wide lock.
    fn drop(&mut self) {
        let mut ierr: c_int = 0;
        // SAFETY: gmsh was initialized by `Session::new`; nothing else uses it.
        unsafe { sys::gmshFinalize(&mut ierr) };
        self.dispositions.restore();
        HOLDS_SESSION.with(|h| h.set(false));
        // `_guard` is dropped after this, releasing GMSH_LOCK.
    }
}
