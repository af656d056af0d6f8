//! A square or rectangular grid of `f32` heights in UV space (docs/models.md §1).
//!
//! Row 0 is the top of the image; pixel (x, y) has its centre at
//! u = (x + 0.5)/W, v = 1 − (y + 0.5)/H. Heights are signed height units:
//! 0 is undisturbed skin, negative is into the skin.

use crate::base::error::Error;

/// The largest map side agesim will allocate, in pixels (an issue-level limit: a
/// 16384² f32 map is 1 GiB).
pub const MAX_SIZE_PX: u32 = crate::base::limits::MAX_MAP_SIDE_PX;

/// A row-major grid of heights, `width_px × height_px`, row 0 at the top.
#[derive(Clone, Debug, PartialEq)]
pub struct HeightMap {
    width_px: u32,
    height_px: u32,
    data: Vec<f32>,
}

impl HeightMap {
    /// A zeroed map. Fails (without allocating) when a side is 0 or above
    /// [`MAX_SIZE_PX`], or when the allocation cannot be made.
    pub fn zeros(width_px: u32, height_px: u32) -> Result<Self, Error> {
        check_size(width_px, height_px)?;
        let len = width_px as usize * height_px as usize;
        let data = zeroed_vec(len, "height map")?;
        Ok(Self {
            width_px,
            height_px,
            data,
        })
    }

    /// Wraps existing data; `data.len()` must be `width_px * height_px`.
    pub fn from_vec(width_px: u32, height_px: u32, data: Vec<f32>) -> Result<Self, Error> {
        check_size(width_px, height_px)?;
        if data.len() != width_px as usize * height_px as usize {
            return Err(Error::InvalidValue {
                what: "height map data length".into(),
                value: data.len().to_string(),
                expected: format!("{}", width_px as usize * height_px as usize),
            });
        }
        Ok(Self {
            width_px,
            height_px,
            data,
        })
    }

    pub fn width_px(&self) -> u32 {
        self.width_px
    }

    pub fn height_px(&self) -> u32 {
        self.height_px
    }

    /// All heights, row-major, row 0 at the top.
    pub fn data(&self) -> &[f32] {
        &self.data
    }

    pub fn data_mut(&mut self) -> &mut [f32] {
        &mut self.data
    }

    pub fn into_vec(self) -> Vec<f32> {
        self.data
    }

    /// One row (row 0 at the top).
    pub fn row(&self, y: u32) -> &[f32] {
        let w = self.width_px as usize;
        &self.data[y as usize * w..(y as usize + 1) * w]
    }

    /// The height at pixel (x, y); panics when out of bounds like slice indexing.
    #[inline]
    pub fn get(&self, x: u32, y: u32) -> f32 {
        self.data[y as usize * self.width_px as usize + x as usize]
    }

    /// Smallest and largest height; (0, 0) for a map of only NaN (never produced here).
    pub fn min_max(&self) -> (f32, f32) {
        let (lo, hi) = self
            .data
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &h| {
                (lo.min(h), hi.max(h))
            });
        if lo > hi { (0.0, 0.0) } else { (lo, hi) }
    }

    /// Box-downsamples by an integer `factor` (both sides must divide).
    pub fn downsample_box(&self, factor: u32) -> Result<Self, Error> {
        if factor == 0
            || !self.width_px.is_multiple_of(factor)
            || !self.height_px.is_multiple_of(factor)
        {
            return Err(Error::InvalidValue {
                what: "downsample factor".into(),
                value: factor.to_string(),
                expected: format!("a divisor of {}×{}", self.width_px, self.height_px),
            });
        }
        let (w, h) = (self.width_px / factor, self.height_px / factor);
        let mut out = Self::zeros(w, h)?;
        let inv = 1.0 / (factor * factor) as f64;
        for y in 0..h {
            for x in 0..w {
                let mut sum = 0.0f64;
                for yy in 0..factor {
                    for xx in 0..factor {
                        sum += self.get(x * factor + xx, y * factor + yy) as f64;
                    }
                }
                out.data[(y * w + x) as usize] = (sum * inv) as f32;
            }
        }
        Ok(out)
    }
}

/// A vector of `len` zeros, allocated already zeroed (`alloc_zeroed`: for large sizes the
/// system hands out fresh zero pages, so nothing is written here and the pages are first
/// touched by whichever thread fills them, instead of one thread clearing them all).
/// `what` names the buffer in the error when the allocation fails.
pub(crate) fn zeroed_vec<T: bytemuck::Zeroable>(
    len: usize,
    what: &'static str,
) -> Result<Vec<T>, Error> {
    let oom = || Error::OutOfMemory {
        bytes: (len as u64).saturating_mul(std::mem::size_of::<T>() as u64),
        what,
    };
    let layout = std::alloc::Layout::array::<T>(len).map_err(|_| oom())?;
    if layout.size() == 0 {
        return Ok(Vec::new());
    }
    // SAFETY: the layout has a non-zero size; the pointer, when not null, is a fresh
    // allocation of exactly `len` `T`s made by the global allocator with `T`'s alignment,
    // whose bytes are all zero, a valid `T` (`Zeroable`); the Vec takes ownership of it.
    unsafe {
        let ptr = std::alloc::alloc_zeroed(layout).cast::<T>();
        if ptr.is_null() {
            return Err(oom());
        }
        advise_huge_pages(ptr.cast(), layout.size());
        Ok(Vec::from_raw_parts(ptr, len, len))
    }
}

/// Asks Linux to back the whole 2 MiB pages inside a large fresh allocation with huge
/// pages (`MADV_HUGEPAGE`; this machine's transparent huge pages are "madvise" only). A
/// 4096² bake's 117 MB of fresh output then takes about 60 page faults instead of 28,000
/// (measured, interleaved runs on the 2-core Xeon: a cold 4096² micro-relief bake with
/// normals went from 134–151 ms to 93–103 ms). Advice only: any failure is ignored.
fn advise_huge_pages(ptr: *mut u8, len: usize) {
    const HUGE: usize = 2 << 20;
    if len < 2 * HUGE {
        return;
    }
    #[cfg(target_os = "linux")]
    {
        let start = (ptr as usize).next_multiple_of(HUGE);
        let end = (ptr as usize + len) / HUGE * HUGE;
        if end > start {
            // SAFETY: [start, end) lies inside the allocation just made (rounded inward to
            // whole huge pages); madvise with MADV_HUGEPAGE only changes how the kernel
            // backs those pages, not their content or validity.
            unsafe {
                libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE);
            }
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = ptr;
}

/// Centre of pixel `x` of `width_px` in u (docs/models.md §1).
#[inline]
pub fn pixel_to_u(x: u32, width_px: u32) -> f32 {
    (x as f32 + 0.5) / width_px as f32
}

/// Centre of pixel row `y` of `height_px` in v (docs/models.md §1: row 0 at the top, v up).
#[inline]
pub fn pixel_to_v(y: u32, height_px: u32) -> f32 {
    1.0 - (y as f32 + 0.5) / height_px as f32
}

/// Checks a requested map size against [`MAX_SIZE_PX`] before any work starts.
pub fn check_size(width_px: u32, height_px: u32) -> Result<(), Error> {
    for side in [width_px, height_px] {
        if side == 0 || side > MAX_SIZE_PX {
            return Err(Error::InvalidSize {
                width_px,
                height_px,
                max_px: MAX_SIZE_PX,
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixel_centres_follow_spec_0() {
        assert_eq!(pixel_to_u(0, 4), 0.125);
        assert_eq!(pixel_to_v(0, 4), 0.875);
        assert_eq!(pixel_to_v(3, 4), 0.125);
    }

    #[test]
    fn oversized_maps_are_refused_without_allocating() {
        assert!(matches!(
            HeightMap::zeros(80000, 80000),
            Err(Error::InvalidSize { .. })
        ));
        assert!(matches!(
            HeightMap::zeros(0, 4),
            Err(Error::InvalidSize { .. })
        ));
    }

    #[test]
    fn box_downsample_averages() {
        let m = HeightMap::from_vec(2, 2, vec![0.0, 1.0, 2.0, 3.0]).unwrap();
        let d = m.downsample_box(2).unwrap();
        assert_eq!(d.data(), &[1.5]);
        assert!(m.downsample_box(3).is_err());
    }
}
