//! Writing maps to disk (docs/models.md §5): 16-bit grey PNG and 32-bit float OpenEXR heights,
//! 8-bit RGB PNG normals.
//!
//! Every file is written to a temporary name in the target's directory, flushed to disk
//! and then renamed over the final name, so an interrupted export never leaves a
//! truncated file under the final name (rename is atomic within a directory on POSIX and
//! on NTFS).
//!
//! A set of outputs (a bake's maps and its `bake.json`) goes through an [`OutputSet`]: every
//! file is written to its temporary first — concurrently — and only when all succeeded are
//! they renamed into place, in the order staged (so `bake.json`, staged last, always
//! describes the files beside it), through a commit journal, so that even a process
//! killed half way leaves the old set or the new one, never a mix (`base::output_set` docs). On
//! any error, and on drop without commit, the temporaries are removed;
//! [`remove_temporaries_on_signals`] also removes them when the process is killed by
//! SIGINT or SIGTERM.

use std::path::Path;

use crate::base::error::Error;
use crate::maps::heightmap::HeightMap;

mod openexr;

// The mechanism lives in `base` (the layers write their own files with it); the export is
// its face for the maps.
pub use crate::base::output_set::{
    OutputSet, finish_interrupted_commit, kill_at_step_for_tests, remove_temporaries_on_signals,
    write_atomically,
};
pub use crate::base::png::{PngPixels, encode_png, encode_png_rows};

/// Heights → 16-bit values: p = round((h − lo)/(hi − lo)·65535), so that
/// h = lo + (hi − lo)·p/65535. A flat map (hi = lo) is all 0.
pub fn quantize_u16(map: &HeightMap, range: (f32, f32)) -> Vec<u16> {
    let scale = quantize_scale(range);
    map.data()
        .iter()
        .map(|&h| quantize(h, range.0, scale))
        .collect()
}

/// 65535/(hi − lo), or 0 for a flat map.
fn quantize_scale((lo, hi): (f32, f32)) -> f64 {
    if hi > lo {
        65535.0 / (hi as f64 - lo as f64)
    } else {
        0.0
    }
}

/// Heights → big-endian 16-bit samples ([`quantize`]), compiled per CPU level so the
/// rounding is inlined (without SSE4.1 `f64::round` is a libm call per pixel).
struct QuantizeBe<'a> {
    rows: &'a [f32],
    lo: f32,
    scale: f64,
    out: &'a mut [u8],
}

impl crate::base::simd::Kernel for QuantizeBe<'_> {
    type Output = ();
    #[inline(always)]
    fn run(self) {
        for (o, &h) in self.out.chunks_exact_mut(2).zip(self.rows) {
            o.copy_from_slice(&quantize(h, self.lo, self.scale).to_be_bytes());
        }
    }
}

/// One height → its 16-bit value ([`quantize_u16`]).
#[inline(always)]
fn quantize(h: f32, lo: f32, scale: f64) -> u16 {
    (((h as f64 - lo as f64) * scale).round()).clamp(0.0, 65535.0) as u16
}

/// Writes the height map as a 16-bit grey PNG spanning its own [min, max]; returns the
/// range (lo, hi) with height = lo + (hi − lo)·p/65535 for a PNG value p.
pub fn write_height_png16(path: &Path, map: &HeightMap) -> Result<(f32, f32), Error> {
    let set = OutputSet::new();
    let range = stage_height_png16(&set, path, map)?;
    set.commit()?;
    Ok(range)
}

/// [`write_height_png16`] into an [`OutputSet`].
pub fn stage_height_png16(
    set: &OutputSet,
    path: &Path,
    map: &HeightMap,
) -> Result<(f32, f32), Error> {
    stage_height_png16_in(set, path, map, map.min_max())
}

/// [`stage_height_png16`] over a given `range` (the tiles of a UDIM head share one).
fn stage_height_png16_in(
    set: &OutputSet,
    path: &Path,
    map: &HeightMap,
    range: (f32, f32),
) -> Result<(f32, f32), Error> {
    let scale = quantize_scale(range);
    let width = map.width_px() as usize;
    set.stage(path, |w| {
        encode_png_rows(
            w,
            map.width_px(),
            map.height_px(),
            PngPixels::Grey16,
            |first, count, buf| {
                let rows = &map.data()[first as usize * width..][..count as usize * width];
                buf.resize(rows.len() * 2, 0);
                let kernel = QuantizeBe {
                    rows,
                    lo: range.0,
                    scale,
                    out: buf,
                };
                crate::base::simd::dispatch_at(crate::base::simd::Level::detect(), kernel);
                Ok(())
            },
        )
    })?;
    Ok(range)
}

/// Writes the raw f32 heights as a single-channel (`Y`) OpenEXR file.
pub fn write_height_exr(path: &Path, map: &HeightMap) -> Result<(), Error> {
    let set = OutputSet::new();
    stage_height_exr(&set, path, map)?;
    set.commit()
}

/// How the height EXR is compressed; every choice is lossless.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ExrCompression {
    /// Run-length, one scan line per block, the lines coded on all cores: fast, and small
    /// on smooth maps (it gains little on noisy heights).
    #[default]
    Rle,
    /// None: 4 bytes per pixel on disk; the least work, but the most bytes to write.
    None,
    /// ZIP, 16 scan lines per block (the `exr` crate, one core): the smallest files, the
    /// slowest to write.
    Zip,
}

/// [`write_height_exr`] into an [`OutputSet`] (RLE).
pub fn stage_height_exr(set: &OutputSet, path: &Path, map: &HeightMap) -> Result<(), Error> {
    stage_height_exr_with(set, path, map, ExrCompression::Rle)
}

/// [`stage_height_exr`] with a chosen compression.
pub fn stage_height_exr_with(
    set: &OutputSet,
    path: &Path,
    map: &HeightMap,
    compression: ExrCompression,
) -> Result<(), Error> {
    let (w, h) = (map.width_px() as usize, map.height_px() as usize);
    let data = map.data();
    let blocks = match compression {
        ExrCompression::None => openexr::Blocks::Uncompressed,
        ExrCompression::Rle => openexr::Blocks::Rle,
        ExrCompression::Zip => {
            use exr::prelude::*;
            let channels = SpecificChannels::build()
                .with_channel("Y")
                .with_pixel_fn(|pos: Vec2<usize>| (data[pos.y() * w + pos.x()],));
            let image = Image::from_encoded_channels((w, h), Encoding::SMALL_LOSSLESS, channels);
            return set.stage(path, |out| {
                // `out` is already buffered (and seekable, which exr needs for its offset
                // table).
                image
                    .write()
                    .to_unbuffered(out)
                    .map_err(|e| std::io::Error::other(format!("OpenEXR encoding failed: {e}")))
            });
        }
    };
    set.stage(path, |out| openexr::write_y_f32(out, w, h, data, blocks))
}

/// The normal map of `map` (`docs/models.md` "Normal maps") as an 8-bit RGB PNG, into an
/// [`OutputSet`]: computed band by band as the encoder takes it, so no map-sized RGB
/// buffer is made (at 4096² that is 48 MB of fresh memory and a pass over it). The same
/// pixels as [`crate::maps::normal_map::encode_rgb8`] written with [`stage_rgb8_png`].
pub fn stage_normal_png(
    set: &OutputSet,
    path: &Path,
    map: &HeightMap,
    settings: &crate::maps::normal_map::NormalSettings,
) -> Result<(), Error> {
    settings.validate()?;
    let width = map.width_px() as usize;
    set.stage(path, |w| {
        encode_png_rows(
            w,
            map.width_px(),
            map.height_px(),
            PngPixels::Rgb8,
            |first, count, buf| {
                buf.resize(3 * width * count as usize, 0);
                crate::maps::normal_map::encode_rgb8_rows(map, settings, first as usize, buf)
                    .map_err(std::io::Error::other)
            },
        )
    })
}

/// Where [`stage_maps`] writes a bake's maps; `None` skips that map.
#[derive(Clone, Copy, Debug, Default)]
pub struct MapPaths<'a> {
    pub height_png: Option<&'a Path>,
    pub height_exr: Option<&'a Path>,
    pub normal_png: Option<&'a Path>,
}

/// What [`stage_maps`] did: the 16-bit PNG's height range, and each writer's wall time.
#[derive(Clone, Copy, Debug, Default)]
pub struct MapsStaged {
    /// (lo, hi) of [`stage_height_png16`], when the PNG was written.
    pub height_png_range: Option<(f32, f32)>,
    pub height_png_ms: f64,
    pub height_exr_ms: f64,
    pub normal_png_ms: f64,
}

/// [`stage_maps`] for a head's map over its UDIM atlas (`crate::head::mesh::udim`): each tile's
/// square written as its own files, named by the convention (`height.1001.png`, …;
/// `<UDIM>` in a name is replaced). The 16-bit PNGs share one height range, and the
/// normals are taken over the whole atlas before it is cut. A single-tile layout writes
/// the paths as they are.
pub fn stage_tiled_maps(
    set: &OutputSet,
    paths: MapPaths<'_>,
    height: &HeightMap,
    normal: &crate::maps::normal_map::NormalSettings,
    exr: ExrCompression,
    udim: Option<&crate::head::mesh::udim::Udim>,
) -> Result<MapsStaged, Error> {
    let Some(udim) = udim.filter(|u| u.multi_tile()) else {
        return stage_maps(set, paths, height, normal, exr);
    };
    let atlas_px = height.width_px();
    let range = height.min_max();
    let normals = match paths.normal_png {
        Some(_) => {
            normal.validate()?;
            let mut rgb = vec![0u8; atlas_px as usize * height.height_px() as usize * 3];
            crate::maps::normal_map::encode_rgb8_rows(height, normal, 0, &mut rgb)?;
            rgb
        }
        None => Vec::new(),
    };
    let mut staged = MapsStaged {
        height_png_range: paths.height_png.map(|_| range),
        ..MapsStaged::default()
    };
    let name = |p: &Path, n: u32| crate::head::mesh::udim::Udim::tile_path(p, n);
    for (k, n) in udim.numbers().into_iter().enumerate() {
        let side = udim.tile_rect_px(k, atlas_px).2;
        let tile = HeightMap::from_vec(side, side, udim.crop(k, height.data(), atlas_px, 1))?;
        let start = std::time::Instant::now();
        if let Some(p) = paths.height_png {
            stage_height_png16_in(set, &name(p, n), &tile, range)?;
        }
        let t = std::time::Instant::now();
        if let Some(p) = paths.height_exr {
            stage_height_exr_with(set, &name(p, n), &tile, exr)?;
        }
        let u = std::time::Instant::now();
        if let Some(p) = paths.normal_png {
            let rgb = udim.crop(k, &normals, atlas_px, 3);
            stage_rgb8_png(set, &name(p, n), side, side, &rgb)?;
        }
        staged.height_png_ms += (t - start).as_secs_f64() * 1e3;
        staged.height_exr_ms += (u - t).as_secs_f64() * 1e3;
        staged.normal_png_ms += u.elapsed().as_secs_f64() * 1e3;
    }
    Ok(staged)
}

/// Stages a bake's three maps at once (each encoder is single-threaded but the EXR's RLE,
/// so they share the cores): the 16-bit height PNG, the float height EXR and the normal
/// map PNG of `height`. The first error, in that order, is returned.
pub fn stage_maps(
    set: &OutputSet,
    paths: MapPaths<'_>,
    height: &HeightMap,
    normal: &crate::maps::normal_map::NormalSettings,
    exr: ExrCompression,
) -> Result<MapsStaged, Error> {
    fn timed<T>(f: impl FnOnce() -> Result<T, Error>) -> Result<(T, f64), Error> {
        let start = std::time::Instant::now();
        f().map(|v| (v, start.elapsed().as_secs_f64() * 1e3))
    }
    let (png, (exr, normal_png)) = rayon::join(
        || {
            timed(|| {
                paths
                    .height_png
                    .map(|p| stage_height_png16(set, p, height))
                    .transpose()
            })
        },
        || {
            rayon::join(
                || {
                    timed(|| match paths.height_exr {
                        Some(p) => stage_height_exr_with(set, p, height, exr),
                        None => Ok(()),
                    })
                },
                || {
                    timed(|| match paths.normal_png {
                        Some(p) => stage_normal_png(set, p, height, normal),
                        None => Ok(()),
                    })
                },
            )
        },
    );
    let (height_png_range, height_png_ms) = png?;
    let ((), height_exr_ms) = exr?;
    let ((), normal_png_ms) = normal_png?;
    Ok(MapsStaged {
        height_png_range,
        height_png_ms,
        height_exr_ms,
        normal_png_ms,
    })
}

/// Writes 8-bit RGB pixels (`width × height × 3` bytes) as PNG.
pub fn write_rgb8_png(path: &Path, width_px: u32, height_px: u32, rgb: &[u8]) -> Result<(), Error> {
    let set = OutputSet::new();
    stage_rgb8_png(&set, path, width_px, height_px, rgb)?;
    set.commit()
}

/// [`write_rgb8_png`] into an [`OutputSet`].
pub fn stage_rgb8_png(
    set: &OutputSet,
    path: &Path,
    width_px: u32,
    height_px: u32,
    rgb: &[u8],
) -> Result<(), Error> {
    set.stage(path, |w| {
        encode_png(w, width_px, height_px, PngPixels::Rgb8, rgb)
    })
}

/// A square picture over the head's UV layout (`side_px`², `pixels` as a PNG stores them:
/// 16-bit values big-endian) as PNG: each UDIM tile's square as its own file
/// (`roughness.1001.png`, …), or the one path for a single-tile head; the files staged.
pub fn stage_tiled_png(
    set: &OutputSet,
    path: &Path,
    data: &[u8],
    side_px: u32,
    pixels: PngPixels,
    udim: Option<&crate::head::mesh::udim::Udim>,
) -> Result<Vec<std::path::PathBuf>, Error> {
    let bytes = pixels.bytes_per_pixel();
    let mut files = Vec::new();
    for (file, side, tile) in crate::head::mesh::udim::Udim::cut(udim, path, data, side_px, bytes) {
        set.stage(&file, |w| encode_png(w, side, side, pixels, &tile))?;
        files.push(file);
    }
    Ok(files)
}

/// An RGBA8 picture over the head's UV layout (the aged base colour) as RGB8 PNG, per
/// UDIM tile ([`stage_tiled_png`]).
pub fn stage_tiled_colour(
    set: &OutputSet,
    path: &Path,
    picture: &crate::maps::mask::HeadImage,
    udim: Option<&crate::head::mesh::udim::Udim>,
) -> Result<(), Error> {
    let rgb: Vec<u8> = picture
        .rgba
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    if udim.is_none_or(|u| !u.multi_tile()) {
        return stage_rgb8_png(set, path, picture.width_px, picture.height_px, &rgb);
    }
    stage_tiled_png(set, path, &rgb, picture.width_px, PngPixels::Rgb8, udim).map(|_| ())
}

/// A square 16-bit grey picture over the head's UV layout (the hair's transition texture)
/// as 16-bit grey PNG, per UDIM tile ([`stage_tiled_png`]); the files staged.
pub fn stage_tiled_grey16(
    set: &OutputSet,
    path: &Path,
    grey: &[u16],
    side_px: u32,
    udim: Option<&crate::head::mesh::udim::Udim>,
) -> Result<Vec<std::path::PathBuf>, Error> {
    let bytes: Vec<u8> = grey.iter().flat_map(|v| v.to_be_bytes()).collect();
    stage_tiled_png(set, path, &bytes, side_px, PngPixels::Grey16, udim)
}

/// Writes 8-bit grey pixels as PNG (previews, masks).
pub fn write_grey8_png(
    path: &Path,
    width_px: u32,
    height_px: u32,
    grey: &[u8],
) -> Result<(), Error> {
    write_atomically(path, |w| {
        encode_png(w, width_px, height_px, PngPixels::Grey8, grey)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write as _;

    fn sample() -> HeightMap {
        HeightMap::from_vec(3, 2, vec![-1.0, 0.0, 1.0, 0.5, 0.25, -0.5]).unwrap()
    }

    #[test]
    fn the_streamed_normal_png_has_the_pixels_of_encode_rgb8() {
        use crate::maps::normal_map::{Convention, NormalSettings};
        let data: Vec<f32> = (0..57 * 45)
            .map(|i| ((i % 57) as f32 * 0.3).sin() + (i / 57) as f32 * 0.05)
            .collect();
        let map = HeightMap::from_vec(57, 45, data).unwrap();
        let settings = NormalSettings {
            strength: 3.0,
            convention: Convention::DirectX,
            tiling: true,
        };
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("normal.png");
        let set = OutputSet::new();
        stage_normal_png(&set, &path, &map, &settings).unwrap();
        set.commit().unwrap();
        let back = image::open(&path).unwrap().into_rgb8().into_raw();
        assert_eq!(
            back,
            crate::maps::normal_map::encode_rgb8(&map, &settings).unwrap()
        );
    }

    #[test]
    fn png16_round_trips_through_the_recorded_range() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("height.png");
        let map = sample();
        let (lo, hi) = write_height_png16(&path, &map).unwrap();
        assert_eq!((lo, hi), (-1.0, 1.0));
        let img = image::open(&path).unwrap().into_luma16();
        assert_eq!(img.dimensions(), (3, 2));
        for (p, h) in img.into_raw().iter().zip(map.data()) {
            let back = lo + (hi - lo) * *p as f32 / 65535.0;
            assert!((back - h).abs() <= (hi - lo) / 65535.0, "{back} vs {h}");
        }
        // Nothing but the final file is left in the directory.
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("height.png")]);
    }

    #[test]
    fn exr_holds_the_raw_values() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("height.exr");
        let map = sample();
        write_height_exr(&path, &map).unwrap();
        use exr::prelude::*;
        let image = read_first_flat_layer_from_file(&path).unwrap();
        let channel = &image.layer_data.channel_data.list[0];
        assert_eq!(channel.name, Text::from("Y"));
        let values: Vec<f32> = channel.sample_data.values_as_f32().collect();
        assert_eq!(values, map.data());
    }

    #[test]
    fn failed_write_leaves_no_file_and_keeps_the_old_one() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("normal.png");
        std::fs::write(&path, b"old").unwrap();
        let err = write_atomically(&path, |w| {
            w.write_all(b"partial")?;
            Err(std::io::Error::other("interrupted"))
        })
        .unwrap_err();
        assert!(err.to_string().contains("normal.png"), "{err}");
        assert_eq!(std::fs::read(&path).unwrap(), b"old");
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            1,
            "temporary file removed"
        );
    }

    #[test]
    fn unwritable_directory_is_a_clear_error() {
        let err =
            write_rgb8_png(Path::new("/nonexistent-dir/x.png"), 1, 1, &[0, 0, 0]).unwrap_err();
        assert!(err.to_string().contains("/nonexistent-dir/x.png"), "{err}");
    }
}
