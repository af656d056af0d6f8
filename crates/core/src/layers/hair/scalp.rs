//! The scalp under the hair (docs/models.md §9 "The scalp under the hair"): the hair's
//! disappearance age per texel of the head's layout, which the 3D view's colour map carries
//! in its alpha so the skin pass tints the scalp under the hair present at its age.

use rayon::prelude::*;

use super::transition::TransitionTexture;

/// The hair's disappearance age at each texel of a `width`×`height` map of the head's
/// layout, as the 3D view's colour map carries it in its alpha (docs/models.md §9 "The
/// scalp under the hair"): 0 where there is no hair at t = 0, else 1 + 254·a, a the
/// transition texture's age (0 where no hair grows) averaged over a box of
/// [`SCALP_EDGE`] of the map's side around the texel, so the tint fades in over a few mm
/// at the edge of the hair. Rows from the top (docs/models.md §1).
pub fn hair_age_alpha(transition: &TransitionTexture, width: u32, height: u32) -> Vec<u8> {
    let (w, h) = (width as usize, height as usize);
    let mut ages: Vec<f32> = vec![0.0; w * h];
    ages.par_chunks_mut(w.max(1))
        .enumerate()
        .for_each(|(y, row)| {
            let v = crate::maps::heightmap::pixel_to_v(y as u32, height);
            for (x, a) in row.iter_mut().enumerate() {
                *a = transition
                    .age_at_uv(crate::maps::heightmap::pixel_to_u(x as u32, width), v)
                    .max(0.0);
            }
        });
    let r = ((w.max(h) as f32 * SCALP_EDGE).round() as usize).max(1);
    box_blur(&ages, w, h, r)
        .into_iter()
        .map(hair_age_byte)
        .collect()
}

/// [`hair_age_alpha`]'s bytes where the pattern keeps the hairline (female, none): the
/// hairline kept where the male pattern has it at [`super::KEPT_HAIRLINE_T`] (0 below it),
/// and the hair there as if it went late, the byte ramping to 255 over
/// [`super::KEPT_HAIRLINE_RAMP`] of the male pattern's ages: the texels along the hairline (the taper's shorter, sparser hair) tint
/// the scalp less (at 255 the tint ran full to the hairline's edge, a band of hair colour
/// below the hair).
pub fn kept_hairline_alpha(male: &[u8]) -> Vec<u8> {
    let kept = super::KEPT_HAIRLINE_T;
    male.par_iter()
        .map(|&a| {
            if a == 0 {
                return 0;
            }
            let age = (f32::from(a) - 1.0) / 254.0;
            if age < kept {
                0
            } else {
                1 + (254.0 * ((age - kept) / super::KEPT_HAIRLINE_RAMP).min(1.0)).round() as u8
            }
        })
        .collect()
}

/// The scalp tint's soft edge, as a fraction of the map's side (≈ 10 mm on the default
/// head).
const SCALP_EDGE: f32 = 0.02;

/// The mean of `v` (`w`×`h`) over a (2r + 1)² box around each texel, the box clipped to
/// the map: running sums along the rows, then along the columns (the rows in parallel,
/// then the columns in parallel blocks; each line's sums in one order, so the same on any
/// thread count).
fn box_blur(v: &[f32], w: usize, h: usize, r: usize) -> Vec<f32> {
    // One line's running mean: `len` values `at(i)` apart, written through `put`.
    let line = |len: usize, at: &dyn Fn(usize) -> f32, put: &mut dyn FnMut(usize, f32)| {
        let mut sum = 0.0f64;
        let mut n = 0usize;
        for i in 0..len.min(r + 1) {
            sum += f64::from(at(i));
            n += 1;
        }
        for i in 0..len {
            put(i, (sum / n as f64) as f32);
            if i + r + 1 < len {
                sum += f64::from(at(i + r + 1));
                n += 1;
            }
            if i >= r {
                sum -= f64::from(at(i - r));
                n -= 1;
            }
        }
    };
    if w == 0 || h == 0 {
        return Vec::new();
    }
    let mut rows = vec![0.0f32; w * h];
    rows.par_chunks_mut(w)
        .zip(v.par_chunks(w))
        .for_each(|(out, src)| line(w, &|i| src[i], &mut |i, m| out[i] = m));
    // The columns in blocks of 64: each block's means gathered, then put in place.
    const BLOCK: usize = 64;
    let blocks: Vec<(usize, Vec<f32>)> = (0..w)
        .step_by(BLOCK)
        .collect::<Vec<_>>()
        .into_par_iter()
        .map(|x0| {
            let bw = BLOCK.min(w - x0);
            let mut out = vec![0.0f32; bw * h];
            for c in 0..bw {
                let x = x0 + c;
                line(h, &|i| rows[i * w + x], &mut |i, m| out[i * bw + c] = m);
            }
            (x0, out)
        })
        .collect();
    let mut out = vec![0.0f32; w * h];
    for (x0, block) in blocks {
        let bw = BLOCK.min(w - x0);
        for (y, src) in block.chunks_exact(bw).enumerate() {
            out[y * w + x0..y * w + x0 + bw].copy_from_slice(src);
        }
    }
    out
}

/// A transition age as [`hair_age_alpha`] stores it.
fn hair_age_byte(age: f32) -> u8 {
    if age > 0.0 {
        1 + (age.min(1.0) * 254.0).round() as u8
    } else {
        0
    }
}

#[cfg(test)]
mod tests {
    /// The running sums give each texel the mean of its clipped box (checked against the
    /// sum of every texel in it), on maps narrower and wider than a block of columns.
    #[test]
    fn the_blur_is_the_mean_of_each_clipped_box() {
        let mut rng = crate::base::rng::Rng::for_stream(3, 1);
        for (w, h, r) in [(7, 5, 2), (150, 9, 4), (3, 40, 10)] {
            let v: Vec<f32> = (0..w * h).map(|_| rng.next_f32()).collect();
            let blurred = super::box_blur(&v, w, h, r);
            let v = &v;
            for y in 0..h {
                for x in 0..w {
                    let (ys, xs) = (
                        y.saturating_sub(r)..(y + r + 1).min(h),
                        x.saturating_sub(r)..(x + r + 1).min(w),
                    );
                    let count = ys.len() * xs.len();
                    let sum: f64 = ys
                        .flat_map(|yy| xs.clone().map(move |xx| f64::from(v[yy * w + xx])))
                        .sum();
                    let want = sum / count as f64;
                    assert!(
                        (f64::from(blurred[y * w + x]) - want).abs() < 1e-5,
                        "({x}, {y})"
                    );
                }
            }
        }
        assert!(super::box_blur(&[], 0, 0, 3).is_empty());
    }
}
