//! Run-time CPU-feature dispatch for the hot loops (micro-relief bake, normal maps).
//!
//! The kernels are plain generic Rust written over fixed-size chunks; [`dispatch`] runs a
//! [`Kernel`] inside a function compiled with AVX-512 or AVX2 enabled when the CPU has them,
//! so the same source is vectorised 16 or 8 lanes wide, and runs it as is (SSE2 baseline)
//! otherwise. No path uses fused multiply-add (Rust never contracts `a * b + c` on its own,
//! and the kernels never call `mul_add`), so every path does the same IEEE operations and
//! the output bytes do not depend on the CPU (docs/models.md §1 "Determinism"; tested per kernel).

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

impl Level {
    /// The level [`dispatch_at`] really runs at when asked for `self`: `self`, or the best
    /// level below it this CPU has.
    pub fn effective(self) -> Self {
        match (self, Self::detect()) {
            (Self::Avx512, Self::Avx512) => Self::Avx512,
            (Self::Avx512 | Self::Avx2, Self::Avx512 | Self::Avx2) => Self::Avx2,
            _ => Self::Baseline,
        }
    }
}

/// Runs `k` compiled for `level`, or for the best level below it this CPU has
/// ([`Level::effective`]).
#[inline(always)]
pub fn dispatch_at<K: Kernel>(level: Level, k: K) -> K::Output {
    #[cfg(target_arch = "x86_64")]
    {
        match level.effective() {
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

/// Keeps LLVM from vectorising the loop this is called in *across* its iterations: call it
/// first thing in the body of a loop over chunks whose body is itself whole-vector code
/// over a fixed-size array (`for l in 0..LANES`).
///
/// Why: LLVM fully unrolls the `0..LANES` inner loop early; with AVX-512 its loop
/// vectoriser then sometimes prefers to vectorise the *outer* loop, 16 chunks at a time,
/// with gathers and transposes (measured on a stand-alone copy of the warp interpolation:
/// 1.5 against 0.25 ns per pixel). A compiler fence emits no instruction, but a loop
/// holding one is not vectorisable, so the body is left to the SLP vectoriser, which turns
/// each `0..LANES` loop into whole-register operations as intended.
#[inline(always)]
pub(crate) fn keep_chunk_loop() {
    std::sync::atomic::compiler_fence(std::sync::atomic::Ordering::SeqCst);
}

/// Copies `src` into `dst` (same length) with non-temporal ("streaming") stores where the
/// CPU has them: the bytes go to memory without first reading the destination's cache
/// lines in, which halves the memory traffic of writing a large output that is not read
/// again soon (measured on this 2-core Xeon: 117 MB of output in 7.6 ms instead of 31 ms on
/// one thread). Call [`stream_fence`] after the last copy of a task, before other threads
/// may read what it wrote.
#[inline]
pub(crate) fn stream_copy<T: bytemuck::Pod>(dst: &mut [T], src: &[T]) {
    let (dst, src): (&mut [u8], &[u8]) = (bytemuck::cast_slice_mut(dst), bytemuck::cast_slice(src));
    assert_eq!(dst.len(), src.len(), "stream_copy: lengths differ");
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{__m128i, _mm_loadu_si128, _mm_stream_si128};
        // SAFETY: `align_to_mut` on bytes is sound for any `__m128i` split (all bit
        // patterns are valid); the middle part is 16-byte aligned, as `_mm_stream_si128`
        // requires, and SSE2 is part of x86-64. Loads read 16 bytes of `src` at offsets
        // inside its length.
        unsafe {
            let (head, body, tail) = dst.align_to_mut::<__m128i>();
            let (h, t) = (head.len(), tail.len());
            head.copy_from_slice(&src[..h]);
            let mid = &src[h..src.len() - t];
            for (k, d) in body.iter_mut().enumerate() {
                let v = _mm_loadu_si128(mid.as_ptr().add(16 * k).cast());
                _mm_stream_si128(d, v);
            }
            tail.copy_from_slice(&src[src.len() - t..]);
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    dst.copy_from_slice(src);
}

/// Orders this thread's streaming stores ([`stream_copy`]) before its later stores, so a
/// thread that synchronises with it afterwards (rayon's join) sees them.
#[inline]
pub(crate) fn stream_fence() {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: `sfence` has no preconditions; SSE is part of x86-64.
    unsafe {
        std::arch::x86_64::_mm_sfence();
    }
}

/// Padding (in columns) kept after every per-column table and row buffer, and the width of
/// the chunks the row loops work in.
pub(crate) const LANES: usize = 16;

/// [`LANES`] floats aligned to 64 bytes (a cache line, an AVX-512 register). Buffers the
/// hot loops read as whole vectors are `Vec<Chunk>`: a `Vec<f32>` is only 16-byte
/// aligned, and then most 64-byte loads straddle two cache lines (measured: the noise
/// sum ran at about half speed that way).
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C, align(64))]
pub(crate) struct Chunk(pub [f32; LANES]);

impl Chunk {
    pub(crate) const ZERO: Self = Self([0.0; LANES]);
}

/// A `Vec<Chunk>` of at least `len` floats, all 0 (reusing `v`'s allocation).
pub(crate) fn resize_chunks(v: &mut Vec<Chunk>, len: usize) {
    v.clear();
    v.resize(len.div_ceil(LANES), Chunk::ZERO);
}
