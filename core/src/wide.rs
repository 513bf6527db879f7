//! The CPU's vector width for the hot loops of the dense linear algebra (Auto's fit,
//! factorisations and metric products; not its eigen-decompositions, whose AVX2 copy
//! ran slower).
//!
//! A portable x86-64 build may use only SSE2: two f64 per instruction and sixteen
//! registers, too few for the blocked kernels' partial sums, which then spill to the
//! stack. A kernel defined with [`avx2_twin!`] is compiled twice, once as the build
//! targets and once with AVX2 (four f64 per instruction), and each call takes the AVX2
//! copy where the CPU has it (CPUID, checked once; [`cpufeatures`]) and, for a kernel
//! with a size rule (`wide_when`), where its vectors are long enough to gain from it.
//!
//! Both copies perform the same operations in the same order: Rust never contracts a
//! multiply and an add into a fused multiply-add (which would round once where the
//! baseline rounds twice), and the kernels fix their own summation order (their partial
//! sums are explicit lanes), so the results are identical bit for bit on every x86 CPU,
//! with or without AVX2. On other architectures (the Cortex-M, wasm, aarch64, whose
//! baseline NEON has no wider register to gain) there is one copy.

use core::sync::atomic::{AtomicBool, Ordering};

#[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
cpufeatures::new!(cpuid_avx2, "avx2");

/// Whether kernels may take their AVX2 copies ([`set_wide_kernels`]).
static WIDE: AtomicBool = AtomicBool::new(true);

/// Lets the dense kernels (Auto's fit, factorisations, metric products) use AVX2
/// where the CPU has it (`true`, the default) or keeps them to the build's own
/// instructions (`false`), for every thread from the next kernel call on. The results
/// are the same bit for bit either way; only the time changes. For timing comparisons,
/// and for tests of that claim. Has no effect off x86.
pub fn set_wide_kernels(enabled: bool) {
    WIDE.store(enabled, Ordering::Relaxed);
}

/// Whether kernels take their AVX2 copies: allowed ([`set_wide_kernels`]) and supported
/// by the CPU and its OS.
#[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
#[inline]
pub(crate) fn has_avx2() -> bool {
    WIDE.load(Ordering::Relaxed) && cpuid_avx2::get()
}

/// Defines a function whose body is compiled twice, for the build's target and with AVX2,
/// and runs the AVX2 copy where [`has_avx2`] holds (see the module's header). The
/// function is written as usual, with type parameters `<T: Bound, …>` (no lifetimes, no
/// `where` clause) and parameters that are plain names.
///
/// Written `avx2_twin! { wide_when(cond); fn … }`, the AVX2 copy runs only where `cond`
/// (an expression of the parameters) holds as well: where a kernel's vectors are short,
/// the baseline copy can be the faster one. Such a function is marked `#[inline]`, so
/// that every crate compiles its own instance at its own optimisation level (a shared
/// generic instance could be an unoptimised build's).
macro_rules! avx2_twin {
    (
        wide_when($cond:expr);
        $(#[$attr:meta])*
        $vis:vis fn $name:ident <$($g:ident : $bound:path),*> ($($arg:ident : $ty:ty),* $(,)?)
        $(-> $ret:ty)? $body:block
    ) => {
        $crate::wide::avx2_twin! {
            @twin [$cond] [#[inline]]
            $(#[$attr])*
            $vis fn $name<$($g: $bound),*>($($arg: $ty),*) $(-> $ret)? $body
        }
    };
    (
        $(#[$attr:meta])*
        $vis:vis fn $name:ident <$($g:ident : $bound:path),*> ($($arg:ident : $ty:ty),* $(,)?)
        $(-> $ret:ty)? $body:block
    ) => {
        $crate::wide::avx2_twin! {
            @twin [true] []
            $(#[$attr])*
            $vis fn $name<$($g: $bound),*>($($arg: $ty),*) $(-> $ret)? $body
        }
    };
    (
        @twin [$cond:expr] [$(#[$extra:meta])*]
        $(#[$attr:meta])*
        $vis:vis fn $name:ident <$($g:ident : $bound:path),*> ($($arg:ident : $ty:ty),* $(,)?)
        $(-> $ret:ty)? $body:block
    ) => {
        $(#[$attr])*
        $(#[$extra])*
        #[allow(unsafe_code)]
        $vis fn $name<$($g: $bound),*>($($arg: $ty),*) $(-> $ret)? {
            #[inline(always)]
            #[allow(clippy::too_many_arguments)]
            fn body<$($g: $bound),*>($($arg: $ty),*) $(-> $ret)? $body
            #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
            {
                #[target_feature(enable = "avx2")]
                #[allow(clippy::too_many_arguments)]
                fn avx2<$($g: $bound),*>($($arg: $ty),*) $(-> $ret)? {
                    body($($arg),*)
                }
                if $cond && $crate::wide::has_avx2() {
                    // SAFETY: the CPU supports AVX2 (`has_avx2`), the only feature the
                    // copy is compiled with beyond the build's own.
                    return unsafe { avx2($($arg),*) };
                }
            }
            // One copy off x86: the condition is evaluated and dropped, so that what it
            // names is used on every target.
            #[cfg(not(any(target_arch = "x86", target_arch = "x86_64")))]
            let _ = $cond;
            body($($arg),*)
        }
    };
}

pub(crate) use avx2_twin;
