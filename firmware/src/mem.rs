//! The memory functions the compiler calls for copies and fills it does not inline:
//! `memcpy`, `memset` and, on Arm, their `__aeabi_` forms. They replace
//! compiler-builtins' (whose definitions are weak so that a program can).
//!
//! compiler-builtins' copy is built for throughput on large buffers of any alignment:
//! word loops with a shifting variant for each misalignment, larger than the rest of the
//! report glue and the runtime together. This firmware copies a few floats and small
//! structs at a time (θ, an optimiser's state), so plain byte loops serve it. Their
//! accesses are volatile so that the compiler cannot recognise a loop as a copy and
//! compile it into a call to the very function it implements.

/// Copies `n` bytes from `src` to `dest` and returns `dest`.
///
/// # Safety
/// `src` must be valid for reads and `dest` for writes of `n` bytes, and the two regions
/// must not overlap.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn memcpy(dest: *mut u8, src: *const u8, n: usize) -> *mut u8 {
    // SAFETY: the same contract.
    unsafe { copy_bytes(dest, src, n) };
    dest
}

/// Sets `n` bytes at `dest` to the low byte of `c` and returns `dest`.
///
/// # Safety
/// `dest` must be valid for writes of `n` bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn memset(dest: *mut u8, c: i32, n: usize) -> *mut u8 {
    // SAFETY: the same contract.
    unsafe { fill_bytes(dest, c as u8, n) };
    dest
}

/// The copy loop, under a name of its own: the compiler knows `memcpy` and the
/// `__aeabi_` names, and would turn a call from one to another back into a call to
/// whichever the target prefers — possibly the caller itself.
///
/// # Safety
/// As [`memcpy`].
unsafe fn copy_bytes(dest: *mut u8, src: *const u8, n: usize) {
    for i in 0..n {
        // SAFETY: `i < n`, within both regions by the caller's contract.
        unsafe { dest.add(i).write_volatile(src.add(i).read_volatile()) };
    }
}

/// The fill loop (see [`copy_bytes`]).
///
/// # Safety
/// As [`memset`].
unsafe fn fill_bytes(dest: *mut u8, value: u8, n: usize) {
    for i in 0..n {
        // SAFETY: `i < n`, within the region by the caller's contract.
        unsafe { dest.add(i).write_volatile(value) };
    }
}

/// The Arm run-time ABI's forms: copies and fills, the `4` and `8` variants promising
/// aligned pointers (which byte loops do not need); `memset`'s takes the length before
/// the value, `memclr` fills with zeros. compiler-builtins' forms call its own `memcpy`
/// and `memset`, not the symbols, so each needs replacing.
#[cfg(target_arch = "arm")]
mod aeabi {
    /// `memcpy` without its result.
    ///
    /// # Safety
    /// As [`super::memcpy`].
    #[unsafe(no_mangle)]
    pub unsafe extern "C" fn __aeabi_memcpy(dest: *mut u8, src: *const u8, n: usize) {
        // SAFETY: the same contract.
        unsafe { super::copy_bytes(dest, src, n) };
    }

    /// [`__aeabi_memcpy`] for 4-aligned pointers.
    ///
    /// # Safety
    /// As [`super::memcpy`].
    #[unsafe(no_mangle)]
    pub unsafe extern "C" fn __aeabi_memcpy4(dest: *mut u8, src: *const u8, n: usize) {
        // SAFETY: the same contract.
        unsafe { super::copy_bytes(dest, src, n) };
    }

    /// [`__aeabi_memcpy`] for 8-aligned pointers.
    ///
    /// # Safety
    /// As [`super::memcpy`].
    #[unsafe(no_mangle)]
    pub unsafe extern "C" fn __aeabi_memcpy8(dest: *mut u8, src: *const u8, n: usize) {
        // SAFETY: the same contract.
        unsafe { super::copy_bytes(dest, src, n) };
    }

    /// `memset` with the length before the value, without its result.
    ///
    /// # Safety
    /// As [`super::memset`].
    #[unsafe(no_mangle)]
    pub unsafe extern "C" fn __aeabi_memset(dest: *mut u8, n: usize, c: i32) {
        // SAFETY: the same contract.
        unsafe { super::fill_bytes(dest, c as u8, n) };
    }

    /// [`__aeabi_memset`] for 4-aligned pointers.
    ///
    /// # Safety
    /// As [`super::memset`].
    #[unsafe(no_mangle)]
    pub unsafe extern "C" fn __aeabi_memset4(dest: *mut u8, n: usize, c: i32) {
        // SAFETY: the same contract.
        unsafe { super::fill_bytes(dest, c as u8, n) };
    }

    /// [`__aeabi_memset`] for 8-aligned pointers.
    ///
    /// # Safety
    /// As [`super::memset`].
    #[unsafe(no_mangle)]
    pub unsafe extern "C" fn __aeabi_memset8(dest: *mut u8, n: usize, c: i32) {
        // SAFETY: the same contract.
        unsafe { super::fill_bytes(dest, c as u8, n) };
    }

    /// Zeros `n` bytes at `dest`.
    ///
    /// # Safety
    /// As [`super::memset`].
    #[unsafe(no_mangle)]
    pub unsafe extern "C" fn __aeabi_memclr(dest: *mut u8, n: usize) {
        // SAFETY: the same contract.
        unsafe { super::fill_bytes(dest, 0, n) };
    }

    /// [`__aeabi_memclr`] for 4-aligned pointers.
    ///
    /// # Safety
    /// As [`super::memset`].
    #[unsafe(no_mangle)]
    pub unsafe extern "C" fn __aeabi_memclr4(dest: *mut u8, n: usize) {
        // SAFETY: the same contract.
        unsafe { super::fill_bytes(dest, 0, n) };
    }

    /// [`__aeabi_memclr`] for 8-aligned pointers.
    ///
    /// # Safety
    /// As [`super::memset`].
    #[unsafe(no_mangle)]
    pub unsafe extern "C" fn __aeabi_memclr8(dest: *mut u8, n: usize) {
        // SAFETY: the same contract.
        unsafe { super::fill_bytes(dest, 0, n) };
    }
}
