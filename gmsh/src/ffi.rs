//! Helpers around the raw calls: `ierr` checking, gmsh-allocated outputs
//! (freed with `gmshFree` on drop, also on early error returns), C strings
//! and flattened `(dim, tag)` arrays.

use std::ffi::{CStr, CString};
use std::os::raw::{c_char, c_int, c_void};
use std::ptr;

use gmsh_sys as sys;

use crate::{DimTag, GmshError, Result};

/// Runs `f` with a fresh `ierr` and turns a non-zero value into
/// [`GmshError::Call`] carrying gmsh's last error message.
pub(crate) fn check<R>(call: &'static str, f: impl FnOnce(*mut c_int) -> R) -> Result<R> {
    let mut ierr: c_int = 0;
    let r = f(&mut ierr);
    if ierr != 0 {
        let message = match last_error() {
            Ok(m) if !m.trim().is_empty() => m,
            Ok(_) => "(gmsh gave no error message)".to_owned(),
            Err(e) => format!("(gmshLoggerGetLastError failed too: {e})"),
        };
        return Err(GmshError::Call {
            call,
            ierr,
            message,
        });
    }
    Ok(r)
}

/// gmsh's last error message (`gmshLoggerGetLastError`).
pub(crate) fn last_error() -> Result<String> {
    let mut out = OutStr::new();
    let mut ierr: c_int = 0;
    // SAFETY: valid out-pointers; gmsh allocates the string with gmshMalloc.
    unsafe { sys::gmshLoggerGetLastError(out.ptr(), &mut ierr) };
    if ierr != 0 {
        return Err(GmshError::Call {
            call: "gmshLoggerGetLastError",
            ierr,
            message: String::new(),
        });
    }
    Ok(out.to_string())
}

/// A C string argument.
pub(crate) fn cstr(what: &'static str, s: &str) -> Result<CString> {
    CString::new(s).map_err(|_| GmshError::InteriorNul {
        what,
        value: s.to_owned(),
    })
}

/// A path argument as a C string (gmsh takes UTF-8 `char *` file names).
pub(crate) fn cpath(path: &std::path::Path) -> Result<CString> {
    let s = path
        .to_str()
        .ok_or_else(|| GmshError::NonUtf8Path(path.to_owned()))?;
    cstr("path", s)
}

/// `[(d0, t0), (d1, t1), ...]` -> `[d0, t0, d1, t1, ...]` as gmsh expects.
pub(crate) fn flatten(dimtags: &[DimTag]) -> Vec<c_int> {
    dimtags.iter().flat_map(|&(d, t)| [d, t]).collect()
}

/// `[d0, t0, d1, t1, ...]` -> `[(d0, t0), (d1, t1), ...]`.
pub(crate) fn pairs(flat: &[c_int]) -> Vec<DimTag> {
    flat.chunks_exact(2).map(|c| (c[0], c[1])).collect()
}

/// `true`/`false` -> `1`/`0`.
pub(crate) fn b(v: bool) -> c_int {
    c_int::from(v)
}

/// Frees a gmsh-allocated block (null is fine).
fn free<T>(p: *mut T) {
    if !p.is_null() {
        // SAFETY: `p` was allocated by gmsh (gmshMalloc) and is freed once.
        unsafe { sys::gmshFree(p.cast::<c_void>()) }
    }
}

/// An output array `T **a, size_t *a_n` that gmsh allocates.
pub(crate) struct OutArray<T: Copy> {
    ptr: *mut T,
    len: usize,
}

impl<T: Copy> OutArray<T> {
    pub(crate) fn new() -> Self {
        Self {
            ptr: ptr::null_mut(),
            len: 0,
        }
    }

    /// The `T **` argument.
    pub(crate) fn ptr(&mut self) -> *mut *mut T {
        &mut self.ptr
    }

    /// The `size_t *` argument.
    pub(crate) fn len(&mut self) -> *mut usize {
        &mut self.len
    }

    pub(crate) fn as_slice(&self) -> &[T] {
        if self.ptr.is_null() || self.len == 0 {
            &[]
        } else {
            // SAFETY: gmsh filled `len` valid elements at `ptr`.
            unsafe { std::slice::from_raw_parts(self.ptr, self.len) }
        }
    }

    pub(crate) fn to_vec(&self) -> Vec<T> {
        self.as_slice().to_vec()
    }
}

impl<T: Copy> Drop for OutArray<T> {
    fn drop(&mut self) {
        free(self.ptr);
    }
}

/// An output array of arrays `T ***a, size_t **a_n, size_t *a_nn`: `a_nn`
/// inner arrays, each allocated by gmsh, plus the outer pointer and size
/// arrays.
pub(crate) struct OutNested<T: Copy> {
    ptr: *mut *mut T,
    lens: *mut usize,
    n: usize,
}

impl<T: Copy> OutNested<T> {
    pub(crate) fn new() -> Self {
        Self {
            ptr: ptr::null_mut(),
            lens: ptr::null_mut(),
            n: 0,
        }
    }

    /// The `T ***` argument.
    pub(crate) fn ptr(&mut self) -> *mut *mut *mut T {
        &mut self.ptr
    }

    /// The `size_t **` argument.
    pub(crate) fn lens(&mut self) -> *mut *mut usize {
        &mut self.lens
    }

    /// The `size_t *` argument.
    pub(crate) fn n(&mut self) -> *mut usize {
        &mut self.n
    }

    fn inner(&self) -> &[*mut T] {
        if self.ptr.is_null() || self.n == 0 {
            &[]
        } else {
            // SAFETY: gmsh filled `n` inner pointers.
            unsafe { std::slice::from_raw_parts(self.ptr, self.n) }
        }
    }

    fn lens_slice(&self) -> &[usize] {
        if self.lens.is_null() || self.n == 0 {
            &[]
        } else {
            // SAFETY: gmsh filled `n` sizes.
            unsafe { std::slice::from_raw_parts(self.lens, self.n) }
        }
    }

    pub(crate) fn to_vecs(&self) -> Vec<Vec<T>> {
        let lens = self.lens_slice();
        self.inner()
            .iter()
            .enumerate()
            .map(|(i, &p)| {
                let len = lens.get(i).copied().unwrap_or(0);
                if p.is_null() || len == 0 {
                    Vec::new()
                } else {
                    // SAFETY: inner array `i` has `lens[i]` valid elements.
                    unsafe { std::slice::from_raw_parts(p, len) }.to_vec()
                }
            })
            .collect()
    }
}

impl<T: Copy> Drop for OutNested<T> {
    fn drop(&mut self) {
        for &p in self.inner() {
            free(p);
        }
        free(self.ptr);
        free(self.lens);
    }
}

/// An output string `char **s` that gmsh allocates.
pub(crate) struct OutStr {
    ptr: *mut c_char,
}

impl OutStr {
    pub(crate) fn new() -> Self {
        Self {
            ptr: ptr::null_mut(),
        }
    }

    /// The `char **` argument.
    pub(crate) fn ptr(&mut self) -> *mut *mut c_char {
        &mut self.ptr
    }
}

impl std::fmt::Display for OutStr {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.ptr.is_null() {
            return Ok(());
        }
        // SAFETY: gmsh returns a NUL-terminated string.
        let s = unsafe { CStr::from_ptr(self.ptr) };
        f.write_str(&s.to_string_lossy())
    }
}

impl Drop for OutStr {
    fn drop(&mut self) {
        free(self.ptr);
    }
}
