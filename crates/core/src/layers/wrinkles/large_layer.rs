//! The large-wrinkle layer kept between bakes (`docs/models.md` "Large wrinkles", "Age"):
//! each fibre's heights h_i over its own bounding rectangle, so that
//! - an age change only re-weights: H(p) = Σ_i c_i(t)·h_i(p), summed in fibre order, then
//!   normalised by the maximum at full age (every c_i = 1) and flattened by γ;
//! - moving one fibre re-rasterises that fibre's rectangle, not the others.
//!
//! With every c_i = 1 the sums are those of [`muscle::accumulate`] bit for bit (x·1 = x,
//! same order), so the fully aged layer equals [`muscle::rasterize`]'s.

use rayon::prelude::*;

use crate::base::cancel::CancelToken;
use crate::base::error::Error;
use crate::layers::wrinkles::muscle::{self, Fibre, LargeWrinkleSettings, MaskValues};
use crate::maps::heightmap::{HeightMap, pixel_to_u, pixel_to_v};

/// Largest total area of all fibres' rectangles, pixels (4 bytes each: 1 GiB). A project
/// beyond it (hundreds of thousands of fibres, or huge ones at 16384²) is refused with a
/// message naming the figure, instead of exhausting memory.
pub const MAX_TOTAL_AREA_PX: u64 = 1 << 28;
/// Largest number of fibres in one layer.
pub const MAX_FIBRES: usize = 100_000;

/// One fibre's heights over its rectangle `[x0, y0, x1, y1)`.
#[derive(Clone, Debug)]
struct Stamp {
    fibre: Fibre,
    rect: [u32; 4],
    heights: Vec<f32>,
}

/// The per-fibre heights of one map size. See the module docs.
#[derive(Clone, Debug, Default)]
pub struct LargeLayer {
    width_px: u32,
    height_px: u32,
    stamps: Vec<Option<Stamp>>,
    fibres: Vec<Fibre>,
    /// max_p Σ_i h_i(p): the normaliser of every age.
    full_max: f32,
}

impl LargeLayer {
    /// The fibres the layer holds, in order.
    pub fn fibres(&self) -> &[Fibre] {
        &self.fibres
    }

    /// (width, height) of the maps it makes.
    pub fn size_px(&self) -> (u32, u32) {
        (self.width_px, self.height_px)
    }

    /// The maximum of the unnormalised sum at full age.
    pub fn full_max(&self) -> f32 {
        self.full_max
    }

    /// Makes the layer hold `fibres` at `width_px × height_px`, re-rasterising only fibres
    /// it does not already hold (compared by value, in any position). Returns how many
    /// were rasterised. On error or cancellation the layer is unchanged.
    pub fn update(
        &mut self,
        fibres: &[Fibre],
        width_px: u32,
        height_px: u32,
        cancel: &CancelToken,
    ) -> Result<usize, Error> {
        check_total_area(fibres, width_px, height_px)?;
        let same_size = (width_px, height_px) == (self.width_px, self.height_px);
        let mut old = if same_size {
            std::mem::take(&mut self.stamps)
        } else {
            Vec::new()
        };
        // Plan first (fallible work only), then move the kept stamps: on an error the
        // layer gets its stamps back untouched.
        let mut used = vec![false; old.len()];
        let mut plan: Vec<Result<usize, Option<Stamp>>> = Vec::with_capacity(fibres.len());
        let mut rasterised = 0;
        for fibre in fibres {
            let found = old
                .iter()
                .enumerate()
                .position(|(j, s)| !used[j] && s.as_ref().is_some_and(|s| s.fibre == *fibre));
            match found {
                Some(j) => {
                    used[j] = true;
                    plan.push(Ok(j));
                }
                None => {
                    let fresh = cancel
                        .check()
                        .and_then(|()| rasterise(fibre, width_px, height_px, cancel));
                    match fresh {
                        Ok(stamp) => plan.push(Err(stamp)),
                        Err(e) => {
                            if same_size {
                                self.stamps = old;
                            }
                            return Err(e);
                        }
                    }
                    rasterised += 1;
                }
            }
        }
        let refs: Vec<&Stamp> = plan
            .iter()
            .filter_map(|p| match p {
                Ok(j) => old[*j].as_ref(),
                Err(stamp) => stamp.as_ref(),
            })
            .collect();
        let full_max = max_of_sum(&refs, width_px, height_px, cancel);
        drop(refs);
        if let Err(e) = cancel.check() {
            if same_size {
                self.stamps = old;
            }
            return Err(e);
        }
        let stamps: Vec<Option<Stamp>> = plan
            .into_iter()
            .map(|p| match p {
                Ok(j) => old[j].take(),
                Err(stamp) => stamp,
            })
            .collect();
        *self = Self {
            width_px,
            height_px,
            stamps,
            fibres: fibres.to_vec(),
            full_max,
        };
        Ok(rasterised)
    }

    /// The layer at an age into `out` (resized to the layer's size): Σ_i c_i·h_i, normalised
    /// by the full-age maximum, γ, mask. `factors[i]` is fibre i's age factor; missing
    /// factors count as 1. On cancellation `out` holds garbage (callers bake into scratch).
    pub fn combine(
        &self,
        factors: &[f32],
        settings: &LargeWrinkleSettings<'_>,
        out: &mut HeightMap,
        cancel: &CancelToken,
    ) -> Result<(), Error> {
        let mask = settings.mask.map_or(MaskValues::None, MaskValues::Sample);
        self.combine_with(factors, settings.gamma, mask, out, cancel)
    }

    /// [`LargeLayer::combine`] with the mask already sampled at this size
    /// ([`muscle::sample_mask`]): the same bytes without a bilinear sample per pixel.
    pub(crate) fn combine_with(
        &self,
        factors: &[f32],
        gamma: f32,
        mask: MaskValues<'_>,
        out: &mut HeightMap,
        cancel: &CancelToken,
    ) -> Result<(), Error> {
        let (w, h) = (self.width_px, self.height_px);
        if out.width_px() != w || out.height_px() != h {
            *out = HeightMap::zeros(w, h)?;
        }
        let stamps: Vec<(&Stamp, f32)> = self
            .stamps
            .iter()
            .enumerate()
            .filter_map(|(i, s)| {
                s.as_ref()
                    .map(|s| (s, factors.get(i).copied().unwrap_or(1.0)))
            })
            .collect();
        out.data_mut()
            .par_chunks_mut(w as usize)
            .enumerate()
            .for_each(|(y, row)| {
                if cancel.is_cancelled() {
                    return;
                }
                row.fill(0.0);
                add_row(&stamps, y as u32, row);
            });
        cancel.check()?;
        muscle::finish_impl(out, gamma, self.full_max, mask, cancel)
    }
}

/// The size, fibre-count and total-area limits ([`MAX_FIBRES`], [`MAX_TOTAL_AREA_PX`]).
fn check_total_area(fibres: &[Fibre], width_px: u32, height_px: u32) -> Result<(), Error> {
    crate::maps::heightmap::check_size(width_px, height_px)?;
    if fibres.len() > MAX_FIBRES {
        return Err(Error::InvalidValue {
            what: "number of wrinkle fibres".into(),
            value: fibres.len().to_string(),
            expected: format!("at most {MAX_FIBRES}"),
        });
    }
    let area: u64 = fibres
        .iter()
        .filter_map(|f| muscle::pixel_bounds(f, width_px, height_px))
        .map(|[x0, y0, x1, y1]| (x1 - x0) as u64 * (y1 - y0) as u64)
        .sum();
    if area > MAX_TOTAL_AREA_PX {
        return Err(Error::InvalidValue {
            what: format!("total area of the wrinkle fibres at {width_px}×{height_px}"),
            value: format!("{area} px"),
            expected: format!(
                "at most {MAX_TOTAL_AREA_PX} px (use fewer or narrower fibres, or a smaller map)"
            ),
        });
    }
    Ok(())
}

/// The layer at an age in one pass, keeping nothing (one-off bakes: `agesim bake`, the
/// exports): each fibre is evaluated once per pixel of its rectangle, added to the row's
/// full-age sum Σ_i h_i (for the normaliser) and to the aged sum Σ_i c_i·h_i, in fibre
/// order. The same bytes as [`LargeLayer::update`] + [`LargeLayer::combine_with`] (the
/// same evaluations, additions and order), without a stamp per fibre or a second pass.
pub(crate) fn bake_direct(
    fibres: &[Fibre],
    factors: &[f32],
    gamma: f32,
    mask: MaskValues<'_>,
    out: &mut HeightMap,
    cancel: &CancelToken,
) -> Result<(), Error> {
    let (w, h) = (out.width_px(), out.height_px());
    check_total_area(fibres, w, h)?;
    let covering: Vec<(&Fibre, [u32; 4], f32)> = fibres
        .iter()
        .enumerate()
        .filter_map(|(i, f)| {
            muscle::pixel_bounds(f, w, h).map(|b| (f, b, factors.get(i).copied().unwrap_or(1.0)))
        })
        .collect();
    let us: Vec<f32> = (0..w).map(|x| pixel_to_u(x, w)).collect();
    let full_max = out
        .data_mut()
        .par_chunks_mut(w as usize)
        .enumerate()
        .map_init(
            || vec![0.0f32; w as usize],
            |full, (y, row)| {
                // Cancelled: leave the row (the caller drops the buffer's content), so the
                // rest of the map is not even touched.
                if cancel.is_cancelled() {
                    return 0.0;
                }
                row.fill(0.0);
                full.fill(0.0);
                let y = y as u32;
                let v = pixel_to_v(y, h);
                for &(fibre, [x0, y0, x1, y1], c) in &covering {
                    if y < y0 || y >= y1 {
                        continue;
                    }
                    let span = x0 as usize..x1 as usize;
                    for ((dst, all), &u) in row[span.clone()]
                        .iter_mut()
                        .zip(&mut full[span.clone()])
                        .zip(&us[span])
                    {
                        let height = fibre.height_at(u, v);
                        *all += height;
                        *dst += c * height;
                    }
                }
                full.iter().copied().fold(0.0f32, f32::max)
            },
        )
        .reduce(|| 0.0, f32::max);
    cancel.check()?;
    muscle::finish_impl(out, gamma, full_max, mask, cancel)
}

/// Adds c_i·h_i of every stamp covering row `y`, in stamp order.
fn add_row(stamps: &[(&Stamp, f32)], y: u32, row: &mut [f32]) {
    for (s, c) in stamps {
        let [x0, y0, x1, _] = s.rect;
        if y < y0 || y >= s.rect[3] {
            continue;
        }
        let rw = (x1 - x0) as usize;
        let src = &s.heights[(y - y0) as usize * rw..][..rw];
        for (dst, h) in row[x0 as usize..x1 as usize].iter_mut().zip(src) {
            *dst += c * h;
        }
    }
}

/// The maximum over the map of Σ_i h_i (full age).
fn max_of_sum(stamps: &[&Stamp], w: u32, h: u32, cancel: &CancelToken) -> f32 {
    let all: Vec<(&Stamp, f32)> = stamps.iter().map(|s| (*s, 1.0)).collect();
    (0..h)
        .into_par_iter()
        .map_init(
            || vec![0.0f32; w as usize],
            |row, y| {
                if cancel.is_cancelled() {
                    return 0.0;
                }
                row.fill(0.0);
                add_row(&all, y, row);
                row.iter().copied().fold(0.0f32, f32::max)
            },
        )
        .reduce(|| 0.0, f32::max)
}

/// One fibre's heights over its rectangle, evaluated exactly as [`muscle::accumulate`] does.
fn rasterise(fibre: &Fibre, w: u32, h: u32, cancel: &CancelToken) -> Result<Option<Stamp>, Error> {
    let Some(rect) = muscle::pixel_bounds(fibre, w, h) else {
        return Ok(None);
    };
    let [x0, y0, x1, y1] = rect;
    let rw = (x1 - x0) as usize;
    let mut heights =
        crate::maps::heightmap::zeroed_vec::<f32>(rw * (y1 - y0) as usize, "wrinkle fibre")?;
    let us: Vec<f32> = (x0..x1).map(|x| pixel_to_u(x, w)).collect();
    heights
        .par_chunks_mut(rw)
        .enumerate()
        .for_each(|(row_index, row)| {
            if cancel.is_cancelled() {
                return;
            }
            let v = pixel_to_v(y0 + row_index as u32, h);
            for (dst, &u) in row.iter_mut().zip(&us) {
                *dst = fibre.height_at(u, v);
            }
        });
    cancel.check()?;
    Ok(Some(Stamp {
        fibre: fibre.clone(),
        rect,
        heights,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fibres() -> Vec<Fibre> {
        vec![
            Fibre::new([0.42, 0.73], [0.44, 0.64], 3)
                .unwrap()
                .with_rel_width(1.0)
                .unwrap(),
            Fibre::new([0.56, 0.73], [0.54, 0.64], 3)
                .unwrap()
                .with_rel_width(1.0)
                .unwrap(),
            Fibre::new([0.3, 0.3], [0.6, 0.35], 5).unwrap(),
        ]
    }

    #[test]
    fn full_age_equals_the_classic_rasteriser_bit_for_bit() {
        let settings = LargeWrinkleSettings::default();
        let want = muscle::rasterize(&fibres(), 200, 150, &settings).unwrap();
        let mut layer = LargeLayer::default();
        assert_eq!(
            layer
                .update(&fibres(), 200, 150, &CancelToken::never())
                .unwrap(),
            3
        );
        let mut got = HeightMap::zeros(1, 1).unwrap();
        layer
            .combine(&[1.0; 3], &settings, &mut got, &CancelToken::never())
            .unwrap();
        assert_eq!(got.data(), want.data());
    }

    #[test]
    fn moving_one_fibre_rasterises_only_it_and_equals_a_fresh_layer() {
        let never = CancelToken::never();
        let mut layer = LargeLayer::default();
        layer.update(&fibres(), 128, 128, &never).unwrap();
        let mut moved = fibres();
        moved[1] = Fibre::new([0.5, 0.7], [0.52, 0.6], 4).unwrap();
        assert_eq!(layer.update(&moved, 128, 128, &never).unwrap(), 1);
        let mut fresh = LargeLayer::default();
        fresh.update(&moved, 128, 128, &never).unwrap();
        let settings = LargeWrinkleSettings::default();
        let (mut a, mut b) = (
            HeightMap::zeros(1, 1).unwrap(),
            HeightMap::zeros(1, 1).unwrap(),
        );
        let f = [0.3, 0.7, 1.0];
        layer.combine(&f, &settings, &mut a, &never).unwrap();
        fresh.combine(&f, &settings, &mut b, &never).unwrap();
        assert_eq!(a.data(), b.data());
    }

    #[test]
    fn younger_is_shallower_everywhere_and_zero_factors_are_flat() {
        let never = CancelToken::never();
        let mut layer = LargeLayer::default();
        layer.update(&fibres(), 96, 96, &never).unwrap();
        let settings = LargeWrinkleSettings::default();
        let (mut old, mut young, mut none) = (
            HeightMap::zeros(1, 1).unwrap(),
            HeightMap::zeros(1, 1).unwrap(),
            HeightMap::zeros(1, 1).unwrap(),
        );
        layer
            .combine(&[1.0; 3], &settings, &mut old, &never)
            .unwrap();
        layer
            .combine(&[0.4; 3], &settings, &mut young, &never)
            .unwrap();
        layer
            .combine(&[0.0; 3], &settings, &mut none, &never)
            .unwrap();
        assert!(old.data().iter().zip(young.data()).all(|(o, y)| y <= o));
        assert!(young.data().iter().sum::<f32>() < old.data().iter().sum::<f32>());
        assert!(none.data().iter().all(|&v| v == 0.0));
    }

    #[test]
    fn a_cancelled_update_leaves_the_layer_as_it_was() {
        let never = CancelToken::never();
        let mut layer = LargeLayer::default();
        layer.update(&fibres(), 64, 64, &never).unwrap();
        let cancelled = CancelToken::new();
        cancelled.cancel();
        let moved = vec![Fibre::new([0.1, 0.1], [0.2, 0.2], 2).unwrap()];
        assert!(matches!(
            layer.update(&moved, 64, 64, &cancelled),
            Err(Error::Cancelled)
        ));
        assert_eq!(layer.fibres(), fibres().as_slice());
    }
}
