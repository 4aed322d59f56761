//! The lane width chosen at run time: the widest vector unit the CPU has,
//! so that a binary built for baseline x86-64 still uses AVX2 or AVX-512.

use crate::lanes::Lanes;
#[cfg(target_arch = "x86_64")]
use crate::lanes::{F64x4, F64x8};

/// The lanes a batch runs in.
///
/// ```
/// use dynamics_runtime::batch::Level;
/// let best = Level::detect();
/// assert!(best >= Level::Scalar && best.width() >= 1);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Level {
    /// One state at a time: the scalar code.
    Scalar,
    /// Four states per instruction, in code compiled for AVX2 and FMA.
    Avx2,
    /// Eight states per instruction, in code compiled for AVX-512F.
    Avx512,
}

impl Level {
    /// The widest level this CPU runs: checked at run time with `std`
    /// (x86-64), else what the build targets.
    ///
    /// ```
    /// let l = dynamics_runtime::batch::Level::detect();
    /// println!("{l:?}: {} states at a time", l.width());
    /// ```
    pub fn detect() -> Level {
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        {
            if std::is_x86_feature_detected!("avx512f") {
                return Level::Avx512;
            }
            if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
                return Level::Avx2;
            }
            Level::Scalar
        }
        #[cfg(not(all(feature = "std", target_arch = "x86_64")))]
        {
            if cfg!(all(target_arch = "x86_64", target_feature = "avx512f")) {
                Level::Avx512
            } else if cfg!(all(
                target_arch = "x86_64",
                target_feature = "avx2",
                target_feature = "fma"
            )) {
                Level::Avx2
            } else {
                Level::Scalar
            }
        }
    }

    /// States per instruction.
    ///
    /// ```
    /// assert_eq!(dynamics_runtime::batch::Level::Avx2.width(), 4);
    /// ```
    pub fn width(self) -> usize {
        match self {
            Level::Scalar => 1,
            Level::Avx2 => 4,
            Level::Avx512 => 8,
        }
    }
}

/// A computation generic over the lane type, run at one [`Level`].
pub(crate) trait Kernel {
    type Output;
    /// The computation over `L` (implementations are `#[inline(always)]`,
    /// so that their whole body is compiled for the caller's CPU features).
    fn run<L: Lanes>(self) -> Self::Output;
}

/// Runs `kernel` at `level`, or at the widest level below it that this
/// CPU has.
#[inline]
// Calling a function compiled for CPU features is `unsafe`: the check that
// the CPU has them is `Level::detect`, right here.
#[allow(unsafe_code)]
pub(crate) fn run<K: Kernel>(level: Level, kernel: K) -> K::Output {
    #[cfg(target_arch = "x86_64")]
    match level.min(Level::detect()) {
        // SAFETY: `detect` found the features these functions are compiled
        // for on this CPU.
        Level::Avx512 => return unsafe { avx512(kernel) },
        Level::Avx2 => return unsafe { avx2(kernel) },
        Level::Scalar => {}
    }
    let _ = level;
    kernel.run::<f64>()
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx2,fma")]
fn avx512<K: Kernel>(kernel: K) -> K::Output {
    kernel.run::<F64x8>()
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn avx2<K: Kernel>(kernel: K) -> K::Output {
    kernel.run::<F64x4>()
}
