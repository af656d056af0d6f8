//! Height → normal map (docs/models.md §5, [T] §7.1.1, [P] eqs. 12–13).
//!
//! The surface is (u, v, s·h): UV in [0,1], heights h in height units scaled by the
//! strength s. Its normal is n = normalize(−s·∂h/∂u, −s·∂h/∂v, 1), with the derivatives
//! taken by central differences inside and one-sided differences at the borders (wrapped
//! when the map tiles). Derivatives are per UV unit, not per texel, so the same height
//! field gives the same normals at any resolution (docs/models.md §1).
//!
//! n.y points toward +v (up in the image): that is the OpenGL convention ("green up"),
//! the default; DirectX flips the green channel on export.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::base::error::Error;
use crate::base::simd::Level;
use crate::maps::heightmap::HeightMap;

/// Default strength s: the height, in UV units, of one height unit. 0.002 gives moderate
/// relief both for the large-wrinkle layer of a head map (a [0,1] wrinkle stands 0.2 % of
/// the UV range, about 1 mm on an adult head's layout) and for micro-relief on the 50 mm
/// skin patch (one height unit = 0.1 mm). [T]'s dispScale 0.005 is the same idea for POM.
pub const DEFAULT_STRENGTH: f32 = 0.002;
/// Valid strength range (0 gives a flat normal map).
pub const STRENGTH_RANGE: (f32, f32) = (0.0, 1000.0);

/// Which way the green channel points in an exported normal map.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Convention {
    /// +Y = +v, green up (Blender, Maya, OpenGL engines). The default.
    #[default]
    OpenGl,
    /// +Y = −v, green down (Unreal, 3ds Max, DirectX engines).
    DirectX,
}

/// How to turn heights into normals.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct NormalSettings {
    /// s: UV units per height unit, in [0, 1000].
    pub strength: f32,
    pub convention: Convention,
    /// Wrap the differences around the edges (for tileable maps).
    pub tiling: bool,
}

impl Default for NormalSettings {
    fn default() -> Self {
        Self {
            strength: DEFAULT_STRENGTH,
            convention: Convention::OpenGl,
            tiling: false,
        }
    }
}

impl NormalSettings {
    pub(crate) fn validate(&self) -> Result<(), Error> {
        let s = self.strength;
        if s.is_finite() && (STRENGTH_RANGE.0..=STRENGTH_RANGE.1).contains(&s) {
            Ok(())
        } else {
            Err(Error::InvalidValue {
                what: "normal strength".into(),
                value: s.to_string(),
                expected: format!("a number in [{}, {}]", STRENGTH_RANGE.0, STRENGTH_RANGE.1),
            })
        }
    }
}

/// Index of the neighbours of `i` in 0..n and the UV-step factor of their difference:
/// (lower, upper, factor) with ∂h ≈ (h[upper] − h[lower])·factor·n.
#[inline]
fn neighbours(i: usize, n: usize, tiling: bool) -> (usize, usize, f32) {
    if n == 1 {
        return (0, 0, 0.0);
    }
    if tiling {
        return ((i + n - 1) % n, (i + 1) % n, 0.5);
    }
    match i {
        0 => (0, 1, 1.0),
        _ if i == n - 1 => (n - 2, n - 1, 1.0),
        _ => (i - 1, i + 1, 0.5),
    }
}

/// Calls `emit(x, n)` for every pixel of row `y` with its unit normal n (OpenGL frame).
#[inline]
fn row_normals(
    map: &HeightMap,
    y: usize,
    settings: &NormalSettings,
    mut emit: impl FnMut(usize, [f32; 3]),
) {
    let (w, h) = (map.width_px() as usize, map.height_px() as usize);
    let data = map.data();
    // Row y − 1 is toward +v (the row above), y + 1 toward −v.
    let (below_v, above_v, fy) = {
        let (lo, hi, f) = neighbours(y, h, settings.tiling);
        (hi, lo, f) // index order flips because rows grow downward
    };
    let row = &data[y * w..(y + 1) * w];
    let above = &data[above_v * w..(above_v + 1) * w];
    let below = &data[below_v * w..(below_v + 1) * w];
    let su = settings.strength * w as f32;
    let sv = settings.strength * h as f32 * fy;
    let normal = unit_normal;
    // The interior is a plain central difference, without the border rule's branches.
    let half_su = 0.5 * su;
    for x in 1..w.saturating_sub(1) {
        emit(
            x,
            normal(
                (row[x + 1] - row[x - 1]) * half_su,
                (above[x] - below[x]) * sv,
            ),
        );
    }
    // The borders need the one-sided (or wrapped) rule.
    for x in [0, w - 1].into_iter().take(w.min(2)) {
        let (xl, xr, fx) = neighbours(x, w, settings.tiling);
        emit(
            x,
            normal((row[xr] - row[xl]) * fx * su, (above[x] - below[x]) * sv),
        );
    }
}

/// Unit normals of every pixel, row-major (OpenGL frame: y toward +v).
pub fn normals(map: &HeightMap, settings: &NormalSettings) -> Result<Vec<[f32; 3]>, Error> {
    settings.validate()?;
    let w = map.width_px() as usize;
    let mut out = vec![[0.0f32; 3]; map.data().len()];
    out.par_chunks_mut(w).enumerate().for_each(|(y, dst)| {
        row_normals(map, y, settings, |x, n| dst[x] = n);
    });
    Ok(out)
}

/// 8-bit encoding of a component in [−1, 1]: round((c·0.5 + 0.5)·255).
#[inline(always)]
pub fn encode_unorm8(c: f32) -> u8 {
    unorm8_i32(c) as u8
}

/// [`encode_unorm8`] as an i32 in 0..=255 (0 for NaN): the same truncation as
/// `clamp(0, 255) as u8`, in the form the vectoriser turns into `cvttps2dq` (a saturating
/// `as` cast does not vectorise). c·127.5 + 128 is (c·0.5 + 0.5)·255 + 0.5 in one
/// multiply-add's worth of operations (two roundings instead of four).
#[inline(always)]
fn unorm8_i32(c: f32) -> i32 {
    // `max` returns 0 for NaN (`clamp` would keep the NaN), so v is a number in [0, 255].
    #[allow(clippy::manual_clamp)]
    let v = (c * 127.5 + 128.0).max(0.0).min(255.0);
    // SAFETY: v is finite and in [0, 255], so it truncates to an i32 without overflow.
    unsafe { v.to_int_unchecked::<i32>() }
}

/// 1/√x for x ≥ 1 (the normals' 1 + |∇h|²), in plain `+ − ×` and integer operations:
/// the classic bit-level first guess and three Newton steps. Relative error below 4e-7
/// (tested), like `1 / x.sqrt()`, at about half the cost of a vector square root and
/// divide; and, like everything here, the same bytes on every instruction set.
#[inline(always)]
pub(crate) fn inv_sqrt(x: f32) -> f32 {
    let y = f32::from_bits(0x5f37_5a86_u32.wrapping_sub(x.to_bits() >> 1));
    let h = 0.5 * x;
    let y = y * (1.5 - h * y * y);
    let y = y * (1.5 - h * y * y);
    y * (1.5 - h * y * y)
}

/// The unit normal (OpenGL frame) for the height derivatives (s·∂h/∂u, s·∂h/∂v).
#[inline(always)]
pub(crate) fn unit_normal(dhu: f32, dhv: f32) -> [f32; 3] {
    let inv = inv_sqrt(dhu * dhu + dhv * dhv + 1.0);
    [-dhu * inv, -dhv * inv, inv]
}

/// The per-row constants of [`encode_row_rgb8`] for row `y` of a `w` × `h` map, and the
/// indices of its (above, below) neighbour rows.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RowRule {
    pub above: usize,
    pub below: usize,
    su: f32,
    sv: f32,
    tiling: bool,
    flip: bool,
}

impl RowRule {
    pub(crate) fn new(y: usize, w: usize, h: usize, settings: &NormalSettings) -> Self {
        // Row y − 1 is toward +v (the row above), y + 1 toward −v.
        let (lo, hi, fy) = neighbours(y, h, settings.tiling);
        Self {
            above: lo,
            below: hi,
            su: settings.strength * w as f32,
            sv: settings.strength * h as f32 * fy,
            tiling: settings.tiling,
            flip: settings.convention == Convention::DirectX,
        }
    }
}

/// Encodes one row of the 8-bit normal map (docs/models.md §5) from the height rows `row`, `above`
/// (toward +v) and `below`: the same IEEE operations as [`normals`] + [`encode_unorm8`], the
/// interior in chunks of 16 pixels that the compiler vectorises. `dst` holds 3·w bytes.
#[inline(always)]
pub(crate) fn encode_row_rgb8(
    above: &[f32],
    row: &[f32],
    below: &[f32],
    rule: &RowRule,
    dst: &mut [u8],
) {
    const L: usize = 16;
    let w = row.len();
    let (above, below, dst) = (&above[..w], &below[..w], &mut dst[..3 * w]);
    let half_su = 0.5 * rule.su;
    let sv = rule.sv;
    let flip = rule.flip;
    // DirectX's green flip folded into the v derivative for the chunks: n.y = −dhv·inv,
    // so negating dhv negates n.y exactly (and dhv² is unchanged), the same bits as
    // flipping afterwards, without a branch in the loop.
    let sv_chunks = if flip { -sv } else { sv };
    #[inline(always)]
    fn normal(dhu: f32, dhv: f32, flip: bool) -> [f32; 3] {
        let [nx, ny, nz] = unit_normal(dhu, dhv);
        [nx, if flip { -ny } else { ny }, nz]
    }
    #[inline(always)]
    fn pixel(dhu: f32, dhv: f32, flip: bool) -> [u8; 3] {
        normal(dhu, dhv, flip).map(encode_unorm8)
    }
    // Interior columns 1..w−1 in chunks, then the interior leftovers, then the borders.
    // Each chunk goes component by component through local arrays (structure of arrays,
    // which vectorises), and leaves as 12 little-endian words of 4 bytes = 16 RGB pixels.
    let interior = w.saturating_sub(2);
    let chunks = interior / L;
    if chunks > 0 {
        let cols = row[..].chunks_exact(L).zip(row[2..].chunks_exact(L));
        let rows = above[1..].chunks_exact(L).zip(below[1..].chunks_exact(L));
        for (((l, r), (a, b)), out) in cols
            .zip(rows)
            .zip(dst[3..].chunks_exact_mut(3 * L))
            .take(chunks)
        {
            crate::base::simd::keep_chunk_loop();
            // The three bytes of a pixel packed in a u32 lane (no narrowing conversions,
            // which the vectoriser handles badly).
            let mut packed = [0u32; L];
            for k in 0..L {
                let n = unit_normal((r[k] - l[k]) * half_su, (a[k] - b[k]) * sv_chunks);
                packed[k] =
                    (unorm8_i32(n[0]) | unorm8_i32(n[1]) << 8 | unorm8_i32(n[2]) << 16) as u32;
            }
            if let Ok(out) = out.try_into() {
                pack_rgb48(&packed, out);
            }
        }
    }
    for x in 1 + chunks * L..1 + interior {
        let p = pixel(
            (row[x + 1] - row[x - 1]) * half_su,
            (above[x] - below[x]) * sv,
            flip,
        );
        dst[3 * x..3 * x + 3].copy_from_slice(&p);
    }
    for x in [0, w - 1].into_iter().take(w.min(2)) {
        let (xl, xr, fx) = neighbours(x, w, rule.tiling);
        let p = pixel(
            (row[xr] - row[xl]) * fx * rule.su,
            (above[x] - below[x]) * sv,
            flip,
        );
        dst[3 * x..3 * x + 3].copy_from_slice(&p);
    }
}

/// Writes 16 pixels packed as `r | g << 8 | b << 16` as 48 bytes of RGB: pixels p0..p3
/// (24 bits each) → little-endian words p0|p1<<24, p1>>8|p2<<16, p2>>16|p3<<8. (Explicit
/// byte shuffles per instruction set were tried: no faster on AVX-512, more instructions
/// on AVX2.)
#[inline(always)]
fn pack_rgb48(packed: &[u32; 16], out: &mut [u8; 48]) {
    let mut words = [0u32; 12];
    for q in 0..4 {
        let [p0, p1, p2, p3] = [0, 1, 2, 3].map(|i| packed[4 * q + i]);
        words[3 * q] = (p0 | p1 << 24).to_le();
        words[3 * q + 1] = (p1 >> 8 | p2 << 16).to_le();
        words[3 * q + 2] = (p2 >> 16 | p3 << 8).to_le();
    }
    out.copy_from_slice(bytemuck::cast_slice(&words));
}

/// The exported normal map: 8-bit RGB, RGB = n·0.5 + 0.5 in the chosen convention.
pub fn encode_rgb8(map: &HeightMap, settings: &NormalSettings) -> Result<Vec<u8>, Error> {
    encode_rgb8_at(map, settings, Level::detect())
}

/// [`encode_rgb8`] with the kernels compiled for `level` (or the best level below it this
/// CPU has); every level gives the same bytes.
pub(crate) fn encode_rgb8_at(
    map: &HeightMap,
    settings: &NormalSettings,
    level: Level,
) -> Result<Vec<u8>, Error> {
    let mut out = crate::maps::heightmap::zeroed_vec::<u8>(map.data().len() * 3, "normal map")?;
    encode_rgb8_into(map, settings, level, &mut out)?;
    Ok(out)
}

/// [`encode_rgb8_at`] into `out` (resized to 3 bytes per pixel; its allocation is kept).
pub(crate) fn encode_rgb8_into(
    map: &HeightMap,
    settings: &NormalSettings,
    level: Level,
    out: &mut Vec<u8>,
) -> Result<(), Error> {
    settings.validate()?;
    let (w, h) = (map.width_px() as usize, map.height_px() as usize);
    out.resize(map.data().len() * 3, 0);
    let data = map.data();
    out.par_chunks_mut(w * 3 * ROWS_PER_TASK)
        .enumerate()
        .for_each(|(t, dst)| {
            crate::base::simd::dispatch_at(
                level,
                EncodeRows {
                    data,
                    w,
                    h,
                    first_row: t * ROWS_PER_TASK,
                    settings,
                    dst,
                },
            )
        });
    Ok(())
}

/// The RGB bytes of the rows `first_row..` that fit in `dst` (3·width bytes each), on
/// this thread: the same bytes as those rows of [`encode_rgb8`] (for streaming a normal
/// map into an encoder without a map-sized buffer).
pub(crate) fn encode_rgb8_rows(
    map: &HeightMap,
    settings: &NormalSettings,
    first_row: usize,
    dst: &mut [u8],
) -> Result<(), Error> {
    settings.validate()?;
    let (w, h) = (map.width_px() as usize, map.height_px() as usize);
    if !dst.len().is_multiple_of(3 * w) || first_row + dst.len() / (3 * w) > h {
        return Err(Error::InvalidValue {
            what: "normal-map rows".into(),
            value: format!("{} bytes from row {first_row}", dst.len()),
            expected: format!("whole rows of {w}×{h}"),
        });
    }
    crate::base::simd::dispatch_at(
        Level::detect(),
        EncodeRows {
            data: map.data(),
            w,
            h,
            first_row,
            settings,
            dst,
        },
    );
    Ok(())
}

/// Encodes the rows `dst` holds, from `first_row` on (a [`crate::base::simd::Kernel`]).
struct EncodeRows<'a> {
    data: &'a [f32],
    w: usize,
    h: usize,
    first_row: usize,
    settings: &'a NormalSettings,
    dst: &'a mut [u8],
}

impl crate::base::simd::Kernel for EncodeRows<'_> {
    type Output = ();
    #[inline(always)]
    fn run(self) {
        let w = self.w;
        let row = |y: usize| &self.data[y * w..(y + 1) * w];
        for (k, dst) in self.dst.chunks_mut(3 * w).enumerate() {
            let y = self.first_row + k;
            let rule = RowRule::new(y, w, self.h, self.settings);
            encode_row_rgb8(row(rule.above), row(y), row(rule.below), &rule, dst);
        }
    }
}

/// Rows per parallel task of [`encode_rgb8`].
const ROWS_PER_TASK: usize = 16;

/// The renderer's packing of a height map (after [T] §7.1.1, `docs/models.md` "Normal
/// maps"): RGBA8 = (the OpenGL-convention normal-map bytes n·0.5 + 0.5 exactly as
/// [`encode_rgb8`] writes them, whatever the export setting, and h01), h01 being the height
/// mapped from `height_range` = (lo, hi) to [0, 1], so POM reads the height from alpha.
/// **Choice**: [T] stores n.z itself in blue; agesim stores n.z·0.5 + 0.5 like the exported
/// map, so one vectorised kernel serves both (a shader decodes all three channels alike).
pub fn pack_rgba8(
    map: &HeightMap,
    settings: &NormalSettings,
    height_range: (f32, f32),
) -> Result<Vec<u8>, Error> {
    let gl = NormalSettings {
        convention: Convention::OpenGl,
        ..*settings
    };
    let rgb = encode_rgb8(map, &gl)?;
    let w = map.width_px() as usize;
    let (lo, hi) = height_range;
    let inv = if hi > lo { 1.0 / (hi - lo) } else { 0.0 };
    let mut out =
        crate::maps::heightmap::zeroed_vec::<u8>(map.data().len() * 4, "packed normal map")?;
    out.par_chunks_mut(w * 4)
        .zip(rgb.par_chunks(w * 3))
        .zip(map.data().par_chunks(w))
        .for_each(|((dst, src), heights)| {
            for ((d, s), h) in dst
                .chunks_exact_mut(4)
                .zip(src.chunks_exact(3))
                .zip(heights)
            {
                let h01 = ((h - lo) * inv).clamp(0.0, 1.0);
                d.copy_from_slice(&[s[0], s[1], s[2], (h01 * 255.0 + 0.5) as u8]);
            }
        });
    Ok(out)
}

#[cfg(test)]
mod pack_tests {
    use super::*;

    #[test]
    fn packing_is_the_opengl_normal_bytes_plus_the_height_in_alpha() {
        let data: Vec<f32> = (0..48).map(|i| ((i * 7) % 11) as f32 * 0.1).collect();
        let map = HeightMap::from_vec(8, 6, data).unwrap();
        let dx = NormalSettings {
            strength: 0.05,
            convention: Convention::DirectX,
            tiling: false,
        };
        let packed = pack_rgba8(&map, &dx, (0.0, 1.0)).unwrap();
        let gl = encode_rgb8(
            &map,
            &NormalSettings {
                convention: Convention::OpenGl,
                ..dx
            },
        )
        .unwrap();
        for (i, (p, n)) in packed.chunks_exact(4).zip(gl.chunks_exact(3)).enumerate() {
            assert_eq!(&p[..3], n, "pixel {i}");
            let h = map.data()[i].clamp(0.0, 1.0);
            assert_eq!(p[3], (h * 255.0 + 0.5) as u8, "pixel {i}");
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::maps::heightmap::{pixel_to_u, pixel_to_v};
    use crate::test_util::close;

    fn from_fn(w: u32, h: u32, f: impl Fn(f32, f32) -> f32) -> HeightMap {
        let mut data = Vec::new();
        for y in 0..h {
            for x in 0..w {
                data.push(f(pixel_to_u(x, w), pixel_to_v(y, h)));
            }
        }
        HeightMap::from_vec(w, h, data).unwrap()
    }

    fn dome() -> HeightMap {
        from_fn(64, 64, |u, v| {
            let r2 = (u - 0.5).powi(2) + (v - 0.5).powi(2);
            (0.09 - r2).max(0.0)
        })
    }

    #[test]
    fn dome_convention_check_from_spec_4() {
        let settings = NormalSettings {
            strength: 1.0,
            ..Default::default()
        };
        let rgb = encode_rgb8(&dome(), &settings).unwrap();
        let px = |x: usize, y: usize| &rgb[(y * 64 + x) * 3..(y * 64 + x) * 3 + 3];
        // Above the centre (toward +v, smaller row index): green > 0.5 in OpenGL.
        assert!(
            px(32, 20)[1] > 140,
            "green above the dome: {:?}",
            px(32, 20)
        );
        // To the right of it: red > 0.5.
        assert!(
            px(44, 32)[0] > 140,
            "red right of the dome: {:?}",
            px(44, 32)
        );
        // DirectX flips green only.
        let dx = encode_rgb8(
            &dome(),
            &NormalSettings {
                convention: Convention::DirectX,
                ..settings
            },
        )
        .unwrap();
        assert!(dx[(20 * 64 + 32) * 3 + 1] < 115);
        assert_eq!(dx[(32 * 64 + 44) * 3], px(44, 32)[0]);
    }

    #[test]
    fn rgb8_equals_the_encoded_normals_on_every_level() {
        // Steep, varied slopes; widths with and without leftover pixels after the chunks;
        // both conventions, tiled and not; every SIMD level this CPU has.
        for w in [53u32, 200] {
            let map = from_fn(w, 37, |u, v| (u * 40.0).sin() * 0.3 + (v * 23.0).cos() * u);
            for convention in [Convention::OpenGl, Convention::DirectX] {
                for tiling in [false, true] {
                    let settings = NormalSettings {
                        strength: 0.05,
                        convention,
                        tiling,
                    };
                    let want: Vec<u8> = normals(&map, &settings)
                        .unwrap()
                        .iter()
                        .flat_map(|n| {
                            let ny = if convention == Convention::DirectX {
                                -n[1]
                            } else {
                                n[1]
                            };
                            [n[0], ny, n[2]].map(encode_unorm8)
                        })
                        .collect();
                    for level in [Level::Baseline, Level::Avx2, Level::Avx512] {
                        let got = encode_rgb8_at(&map, &settings, level).unwrap();
                        assert!(
                            got == want,
                            "w {w}, {convention:?}, tiling {tiling}, {level:?}: first \
                             difference at byte {:?}",
                            got.iter().zip(&want).position(|(a, b)| a != b)
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn inv_sqrt_is_within_4e7_of_f64() {
        // 1 + |∇h|² from flat to vertical-ish slopes, and a sweep across binades.
        let xs = (0..200_000)
            .map(|i| 1.0 + i as f32 * 0.013)
            .chain((0..120).map(|e| 2.0f32.powf(e as f32 * 0.5)));
        let (e, x) = crate::test_util::worst_relative_error(xs, inv_sqrt, |x| 1.0 / x.sqrt());
        assert!(e < 4e-7, "worst relative error {e} at {x}");
    }

    #[test]
    fn plane_slope_gives_the_analytic_normal() {
        // h = 0.5·u → ∂h/∂u = 0.5; with s = 2: n ∝ (−1, 0, 1).
        let map = from_fn(16, 8, |u, _| 0.5 * u);
        let n = normals(
            &map,
            &NormalSettings {
                strength: 2.0,
                ..Default::default()
            },
        )
        .unwrap();
        for (i, n) in n.iter().enumerate() {
            close(n[0], -std::f32::consts::FRAC_1_SQRT_2, 1e-5);
            close(n[1], 0.0, 1e-6);
            close(n[2], std::f32::consts::FRAC_1_SQRT_2, 1e-5);
            assert!(i < 128);
        }
        // h = v: ∂h/∂v = 1 (the row above is higher) → n.y < 0.
        let map = from_fn(8, 16, |_, v| v);
        let n = normals(
            &map,
            &NormalSettings {
                strength: 1.0,
                ..Default::default()
            },
        )
        .unwrap();
        for n in &n {
            close(n[1], -std::f32::consts::FRAC_1_SQRT_2, 1e-5);
        }
    }

    #[test]
    fn border_differences_are_one_sided_or_wrapped() {
        // A ramp 0, 1, 2, 3 along u: one-sided at the borders gives the same slope.
        let map = HeightMap::from_vec(4, 1, vec![0.0, 1.0, 2.0, 3.0]).unwrap();
        let s = NormalSettings {
            strength: 0.25,
            ..Default::default()
        }; // slope 4·0.25 = 1
        let n = normals(&map, &s).unwrap();
        for n in &n {
            close(n[0], -std::f32::consts::FRAC_1_SQRT_2, 1e-6);
        }
        // Wrapped: at x = 0 the neighbours are x = 3 and x = 1 → ∂h = (1 − 3)·0.5·4·0.25 = −1.
        let n = normals(&map, &NormalSettings { tiling: true, ..s }).unwrap();
        close(n[0][0] / n[0][2], 1.0, 1e-6);
        close(n[1][0] / n[1][2], -1.0, 1e-6);
    }

    #[test]
    fn resolution_independent() {
        let f = |u: f32, v: f32| (u * 6.0).sin() * 0.1 + v * v * 0.2;
        let s = NormalSettings {
            strength: 1.0,
            ..Default::default()
        };
        let a = normals(&from_fn(64, 64, f), &s).unwrap();
        let b = normals(&from_fn(256, 256, f), &s).unwrap();
        // Pixel (10, 20) of 64² has the same centre as the 2×2 block at (41, 81) of 256²...
        // compare at pixel centres that coincide in u: x64 = 10 ↔ u = 10.5/64 = 42/256.
        let na = a[20 * 64 + 10];
        let nb0 = b[81 * 256 + 41];
        let nb1 = b[82 * 256 + 42];
        for k in 0..3 {
            close(na[k], 0.5 * (nb0[k] + nb1[k]), 2e-3);
        }
    }

    #[test]
    fn packing_puts_height_in_alpha() {
        let map = HeightMap::from_vec(2, 1, vec![-1.0, 1.0]).unwrap();
        let px = pack_rgba8(
            &map,
            &NormalSettings {
                strength: 0.0,
                ..Default::default()
            },
            (-1.0, 1.0),
        )
        .unwrap();
        assert_eq!(px, vec![128, 128, 255, 0, 128, 128, 255, 255]);
        assert!(
            normals(
                &map,
                &NormalSettings {
                    strength: f32::NAN,
                    ..Default::default()
                }
            )
            .is_err()
        );
    }
}
