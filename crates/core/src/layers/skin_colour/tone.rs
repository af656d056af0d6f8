//! The local skin tone round each texel (what lips and brows fade toward) and the bare
//! skin's tone round the beard, on a coarse grid of the layout.

use super::*;

/// The local skin tone per texel: the base colour averaged over a coarse grid of the UV
/// layout ([`ToneCells`]), read back bilinearly. What lips and brows fade toward, and
/// what brow hair is darker than. The lips do not count: the skin round them is what they
/// fade toward (with their own red in the average they kept much of it, and read blind as
/// "barely thinner").
pub(super) fn local_tone(
    n: usize,
    texels: &SurfaceTexels,
    base_at: &(dyn Fn(usize, usize) -> Vec3 + Sync),
) -> Vec<Vec3> {
    let cells = ToneCells::new(n, texels, base_at, 2, |i| {
        1.0 - from_unit(texels.fields[i].lips)
    });
    let mut out = vec![Vec3::ZERO; n * n];
    out.par_chunks_mut(n).enumerate().for_each(|(y, row)| {
        for (x, o) in row.iter_mut().enumerate() {
            *o = cells.at(x, y);
        }
    });
    out
}

/// The bare skin's tone round the beard: the base colour of [`Regions::bare_skin`] away
/// from the beard, the lips, the redness and the eyes, blurred far enough ([`BARE_TONE_PASSES`]) to
/// reach across the beard from the skin round it (the cheeks above, the neck below).
pub(super) fn bare_tone(
    n: usize,
    texels: &SurfaceTexels,
    base_at: &(dyn Fn(usize, usize) -> Vec3 + Sync),
) -> ToneCells {
    ToneCells::new(n, texels, base_at, BARE_TONE_PASSES, |i| {
        let f = &texels.fields[i];
        [f.beard, f.lips, f.red, f.under_eye]
            .iter()
            .map(|&b| 1.0 - from_unit(b))
            .product::<f32>()
            * from_unit(f.bare)
    })
}

/// A skin tone over the UV layout: the base colour averaged over a [`TONE_GRID`]² grid
/// (only texels on the surface count, each with its weight, so the background and the
/// pad round the islands do not darken their edges), blurred by a number of 3×3 box
/// passes (normalised convolution).
#[derive(Clone, Debug)]
pub(super) struct ToneCells {
    /// The bake's side, texels.
    pub(super) n: usize,
    /// Mean colour per cell; NaN where nothing counted within the blur's reach.
    pub(super) cells: Vec<Vec3>,
}

impl ToneCells {
    pub(super) fn new(
        n: usize,
        texels: &SurfaceTexels,
        base_at: &(dyn Fn(usize, usize) -> Vec3 + Sync),
        passes: usize,
        weight_of: impl Fn(usize) -> f32,
    ) -> Self {
        let g = TONE_GRID;
        let mut sum = vec![Vec3::ZERO; g * g];
        let mut weight = vec![0.0f32; g * g];
        // A sparse sample is enough for a coarse average.
        let step = (n / 256).max(1);
        for y in (0..n).step_by(step) {
            for x in (0..n).step_by(step) {
                let i = y * n + x;
                if !texels.on_surface(i) {
                    continue;
                }
                let w = weight_of(i);
                if w <= 0.0 {
                    continue;
                }
                let k = (y * g / n) * g + x * g / n;
                sum[k] += base_at(x, y) * w;
                weight[k] += w;
            }
        }
        for _ in 0..passes {
            let (s0, w0) = (sum.clone(), weight.clone());
            for y in 0..g {
                for x in 0..g {
                    let (mut s, mut w) = (Vec3::ZERO, 0.0);
                    for dy in -1i32..=1 {
                        for dx in -1i32..=1 {
                            let (xx, yy) = (x as i32 + dx, y as i32 + dy);
                            if xx < 0 || yy < 0 || xx >= g as i32 || yy >= g as i32 {
                                continue;
                            }
                            let k = yy as usize * g + xx as usize;
                            s += s0[k];
                            w += w0[k];
                        }
                    }
                    sum[y * g + x] = s;
                    weight[y * g + x] = w;
                }
            }
        }
        let cells = sum
            .iter()
            .zip(&weight)
            .map(|(s, &w)| {
                if w > 0.0 {
                    *s / w
                } else {
                    Vec3::splat(f32::NAN)
                }
            })
            .collect();
        Self { n, cells }
    }

    /// The tone at texel (x, y), bilinear over the cells that have one (mid-gray where
    /// none near has).
    pub(super) fn at(&self, x: usize, y: usize) -> Vec3 {
        let (g, n) = (TONE_GRID, self.n);
        let cell =
            |t: usize| ((t as f32 + 0.5) * g as f32 / n as f32 - 0.5).clamp(0.0, (g - 1) as f32);
        let (fx, fy) = (cell(x), cell(y));
        let (x0, y0) = (fx.floor() as usize, fy.floor() as usize);
        let (x1, y1) = ((x0 + 1).min(g - 1), (y0 + 1).min(g - 1));
        let (tx, ty) = (fx - x0 as f32, fy - y0 as f32);
        let mut acc = Vec3::ZERO;
        let mut w = 0.0;
        for (cx, cy, cw) in [
            (x0, y0, (1.0 - tx) * (1.0 - ty)),
            (x1, y0, tx * (1.0 - ty)),
            (x0, y1, (1.0 - tx) * ty),
            (x1, y1, tx * ty),
        ] {
            let v = self.cells[cy * g + cx];
            if !v.x.is_nan() && cw > 0.0 {
                acc += v * cw;
                w += cw;
            }
        }
        if w > 0.0 { acc / w } else { Vec3::splat(0.5) }
    }
}
