//! The plans of a separable 2-D FFT of real data, in `f32` and `f64`, made here.
//!
//! rustfft's planner chooses among dozens of algorithms, each in scalar, SSE and AVX forms,
//! and every one of them is generic in the float: a crate that asks for a plan compiles all
//! of them for its float, and so does each of its test builds. Asking here, through
//! [`Float::plans_2d`], compiles them once, in this crate, and hands out trait objects:
//! a user's crate then compiles only its calls through those objects. The plans are the
//! planners' own (rustfft picks the fastest algorithm the CPU supports at run time), so the
//! results are what the planners give directly, bit for bit.

#![deny(clippy::print_stdout, clippy::print_stderr)]

use std::sync::Arc;

pub use realfft::{ComplexToReal, FftNum, RealToComplex};
pub use rustfft::Fft;
pub use rustfft::num_complex::{Complex, Complex64};

/// The plans of a 2-D transform of a real `width × height` image, row by row and then
/// column by column: each row real-to-complex (`width / 2 + 1` frequencies), each column
/// of those complex to complex, and both inverses (unnormalised, as the planners' are).
pub struct Plans2d<T> {
    /// Real rows of `width` to their `width / 2 + 1` complex frequencies.
    pub row_forward: Arc<dyn RealToComplex<T>>,
    /// `width / 2 + 1` complex frequencies back to real rows of `width`.
    pub row_inverse: Arc<dyn ComplexToReal<T>>,
    /// Complex columns of `height`, forward.
    pub col_forward: Arc<dyn Fft<T>>,
    /// Complex columns of `height`, inverse.
    pub col_inverse: Arc<dyn Fft<T>>,
}

impl<T> std::fmt::Debug for Plans2d<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Plans2d")
            .field("width", &self.row_forward.len())
            .field("height", &self.col_forward.len())
            .finish()
    }
}

/// A float the plans are made for here: `f32` and `f64`.
pub trait Float: FftNum {
    /// The plans of a real `width × height` image (one real planner for the rows' forward
    /// and inverse, one complex planner for the columns', so each pair shares its twiddle
    /// factors).
    fn plans_2d(width: usize, height: usize) -> Plans2d<Self>;
}

/// The plans of `T`, written once and made concrete by each `impl` below, so that the
/// planners' code is compiled in this crate.
fn plans<T: FftNum>(width: usize, height: usize) -> Plans2d<T> {
    let mut real = realfft::RealFftPlanner::<T>::new();
    let mut complex = rustfft::FftPlanner::<T>::new();
    Plans2d {
        row_forward: real.plan_fft_forward(width),
        row_inverse: real.plan_fft_inverse(width),
        col_forward: complex.plan_fft_forward(height),
        col_inverse: complex.plan_fft_inverse(height),
    }
}

impl Float for f64 {
    fn plans_2d(width: usize, height: usize) -> Plans2d<Self> {
        plans(width, height)
    }
}

impl Float for f32 {
    fn plans_2d(width: usize, height: usize) -> Plans2d<Self> {
        plans(width, height)
    }
}
