//! What every export shares, written once (after rustls-ffi's panic boundary and hyper's one
//! helper per export shape):
//!
//! - [`status_call`]: the shape of every fallible export. It runs the body behind
//!   `catch_unwind` (a panic becomes `ROCKING_ERR_INTERNAL`, never an unwind into C), keeps the
//!   error's detail for `rocking_last_error_message()` and returns the status code.
//! - [`input`], [`optional_input`]: an array (or struct) the caller passes in: checked non-NULL
//!   and aligned, then copied — so inputs and outputs may even overlap.
//! - [`Output`]: an array the caller passes out (or in and out): checked when the call starts,
//!   read (in-out arrays) before anything is computed, written only once the whole call has
//!   succeeded.
//!
//! Every check names the argument: "velocity is NULL", "mass is not aligned".

use std::cell::RefCell;
use std::ffi::{c_char, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

use crate::error::{codes, ErrorKind, RockingError};

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

fn set_last_error(text: &str) {
    let c = CString::new(text.replace('\0', " ")).unwrap_or_default();
    LAST_ERROR.with(|e| *e.borrow_mut() = c);
}

/// The detail of the last failure on this thread ("" after a success).
pub(super) fn last_error() -> *const c_char {
    LAST_ERROR.with(|e| e.borrow().as_ptr())
}

/// Runs the body of a fallible export behind the panic boundary, records the error detail and
/// returns the status code.
pub(super) fn status_call(body: impl FnOnce() -> Result<(), RockingError>) -> i32 {
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => {
            set_last_error("");
            codes::ROCKING_OK
        }
        Ok(Err(e)) => {
            set_last_error(&e.to_string());
            e.code()
        }
        Err(_) => {
            set_last_error(ErrorKind::Internal.message());
            codes::ROCKING_ERR_INTERNAL
        }
    }
}

/// `ptr` is non-NULL and aligned for `T`, or the error that names it.
fn check_pointer<T>(ptr: *const T, name: &str) -> Result<(), RockingError> {
    if ptr.is_null() {
        return Err(RockingError::new(
            ErrorKind::NullPointer,
            format!("{name} is NULL"),
        ));
    }
    if (ptr as usize) % std::mem::align_of::<T>() != 0 {
        return Err(RockingError::new(
            ErrorKind::InvalidSize,
            format!("{name} is not aligned"),
        ));
    }
    Ok(())
}

/// Copies `len` values of an input argument after checking the pointer.
///
/// # Safety
/// `ptr` must be NULL or point to `len` readable, initialised values.
pub(super) unsafe fn input<T: Copy>(
    ptr: *const T,
    len: usize,
    name: &str,
) -> Result<Vec<T>, RockingError> {
    check_pointer(ptr, name)?;
    Ok(std::slice::from_raw_parts(ptr, len).to_vec())
}

/// [`input`] for an argument that may be NULL (`None`).
///
/// # Safety
/// As for [`input`].
pub(super) unsafe fn optional_input<T: Copy>(
    ptr: *const T,
    len: usize,
    name: &str,
) -> Result<Option<Vec<T>>, RockingError> {
    if ptr.is_null() {
        Ok(None)
    } else {
        input(ptr, len, name).map(Some)
    }
}

/// An output (or in-out) argument: `len` values at `ptr`, checked when the call starts and
/// written only at its end, after every check and computation has succeeded. An optional output
/// may be NULL: then nothing is written.
pub(super) struct Output<T> {
    ptr: *mut T,
    len: usize,
}

impl<T: Copy> Output<T> {
    /// A required output: NULL is an error.
    pub(super) fn required(ptr: *mut T, len: usize, name: &str) -> Result<Output<T>, RockingError> {
        check_pointer(ptr, name)?;
        Ok(Output { ptr, len })
    }

    /// An output the caller may skip by passing NULL.
    pub(super) fn optional(ptr: *mut T, len: usize, name: &str) -> Result<Output<T>, RockingError> {
        if ptr.is_null() {
            Ok(Output { ptr, len })
        } else {
            Output::required(ptr, len, name)
        }
    }

    /// Whether the caller asked for this output (the pointer is not NULL).
    pub(super) fn is_requested(&self) -> bool {
        !self.ptr.is_null()
    }

    /// A copy of the current contents of a required in-out argument.
    ///
    /// # Safety
    /// The pointer must point to `len` readable, initialised values.
    pub(super) unsafe fn read(&self) -> Vec<T> {
        input(self.ptr.cast_const(), self.len, "in-out argument")
            .expect("checked by Output::required")
    }

    /// Writes the result (nothing if the caller passed NULL).
    ///
    /// # Safety
    /// The pointer must be NULL or point to `len` writable values.
    pub(super) unsafe fn write(self, values: &[T]) {
        assert_eq!(values.len(), self.len, "output length");
        if self.is_requested() {
            std::ptr::copy_nonoverlapping(values.as_ptr(), self.ptr, self.len);
        }
    }
}
