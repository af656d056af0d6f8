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

/// The scalp tint's soft edge, as a fraction of the map's side (≈ 10 mm on the default
/// head).
const SCALP_EDGE: f32 = 0.02;

/// The mean of `v` (`w`×`h`) over a (2r + 1)² box around each texel, the box clipped to
/// the map: running sums along the rows, then along the columns.
fn box_blur(v: &[f32], w: usize, h: usize, r: usize) -> Vec<f32> {
    let pass = |src: &[f32], len: usize, stride: usize, count: usize, step: usize| {
        let mut out = vec![0.0f32; src.len()];
        for line in 0..count {
            let at = |i: usize| line * step + i * stride;
            let mut sum = 0.0f64;
            let mut n = 0usize;
            for i in 0..len.min(r + 1) {
                sum += f64::from(src[at(i)]);
                n += 1;
            }
            for i in 0..len {
                out[at(i)] = (sum / n as f64) as f32;
                if i + r + 1 < len {
                    sum += f64::from(src[at(i + r + 1)]);
                    n += 1;
                }
                if i >= r {
                    sum -= f64::from(src[at(i - r)]);
                    n -= 1;
                }
            }
        }
        out
    };
    let rows = pass(v, w, 1, h, w);
    pass(&rows, h, w, w, 1)
}

/// A transition age as [`hair_age_alpha`] stores it.
fn hair_age_byte(age: f32) -> u8 {
    if age > 0.0 {
        1 + (age.min(1.0) * 254.0).round() as u8
    } else {
        0
    }
}
