//! Run-time CPU-feature dispatch for the hot loops (micro-relief bake, normal maps).
//!
//! The kernels are plain generic Rust written over fixed-size chunks; [`dispatch`] runs a
//! [`Kernel`] inside a function compiled with AVX-512 or AVX2 enabled when the CPU has them,
//! so the same source is vectorised 16 or 8 lanes wide, and runs it as is (SSE2 baseline)
//! otherwise. No path uses fused multiply-add (Rust never contracts `a * b + c` on its own,
//! and the kernels never call `mul_add`), so every path does the same IEEE operations and
//! the output bytes do not depend on the CPU (SPEC §0 "Determinism"; tested per kernel).

/// An instruction-set level the kernels can be compiled for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Level {
    /// The target's baseline (SSE2 on x86-64).
    Baseline,
    /// AVX2 (256-bit vectors).
    Avx2,
    /// AVX-512 F/BW/DQ/VL (512-bit vectors).
    Avx512,
}

impl Level {
    /// The best level this CPU supports.
    pub fn detect() -> Self {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx512f")
                && std::arch::is_x86_feature_detected!("avx512bw")
                && std::arch::is_x86_feature_detected!("avx512dq")
                && std::arch::is_x86_feature_detected!("avx512vl")
            {
                return Self::Avx512;
            }
            if std::arch::is_x86_feature_detected!("avx2") {
                return Self::Avx2;
            }
        }
        Self::Baseline
    }
}

/// A piece of work to compile per instruction-set level. Implement [`Kernel::run`] with
/// `#[inline(always)]` (and make everything it calls in the hot path `#[inline(always)]`):
/// [`dispatch`] calls it from functions compiled with AVX-512 / AVX2 enabled, and only code
/// inlined into those is vectorised for them. (A closure would not do: it has one body per
/// type, called from three places, so LLVM keeps it out of line, compiled for the baseline.)
pub trait Kernel {
    type Output;
    fn run(self) -> Self::Output;
}

/// Runs `k` compiled for the best level of this CPU.
#[inline(always)]
pub fn dispatch<K: Kernel>(k: K) -> K::Output {
    dispatch_at(Level::detect(), k)
}

/// Runs `k` compiled for `level`, or for the best level below it this CPU has.
#[inline(always)]
pub fn dispatch_at<K: Kernel>(level: Level, k: K) -> K::Output {
    #[cfg(target_arch = "x86_64")]
    {
        let level = match (level, Level::detect()) {
            (Level::Avx512, Level::Avx512) => Level::Avx512,
            (Level::Avx512 | Level::Avx2, Level::Avx512 | Level::Avx2) => Level::Avx2,
            _ => Level::Baseline,
        };
        match level {
            // SAFETY: `Level::detect` found these features on this CPU, the only
            // requirement of calling a `#[target_feature]` function.
            Level::Avx512 => return unsafe { with_avx512(k) },
            // SAFETY: as above, AVX2 is present.
            Level::Avx2 => return unsafe { with_avx2(k) },
            Level::Baseline => {}
        }
    }
    let _ = level;
    k.run()
}

/// `k.run()` inlined into a function compiled with AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn with_avx2<K: Kernel>(k: K) -> K::Output {
    k.run()
}

/// `k.run()` inlined into a function compiled with AVX-512 (F, BW, DQ, VL).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,avx512f,avx512bw,avx512dq,avx512vl")]
fn with_avx512<K: Kernel>(k: K) -> K::Output {
    k.run()
}
