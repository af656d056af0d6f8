//! Writing maps to disk (SPEC §4): 16-bit grey PNG and 32-bit float OpenEXR heights,
//! 8-bit RGB PNG normals.
//!
//! Every file is written to a temporary name in the target's directory, flushed to disk
//! and then renamed over the final name, so an interrupted export never leaves a
//! truncated file under the final name (rename is atomic within a directory on POSIX and
//! on NTFS).

use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use image::ImageEncoder as _;
use image::codecs::png::{CompressionType, FilterType, PngEncoder};

use crate::error::Error;
use crate::heightmap::HeightMap;

/// The temporary sibling of `path`: `.<name>.<pid>.<n>.tmp`, hidden and unique per call.
fn temp_path(path: &Path) -> PathBuf {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let name = path
        .file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.{}.{n}.tmp", std::process::id()))
}

/// Writes a file through `write` to a temporary name beside `path`, syncs it and renames
/// it into place. On any error the temporary file is removed and `path` is untouched.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<File>) -> std::io::Result<()>,
) -> Result<(), Error> {
    let tmp = temp_path(path);
    let result = (|| {
        let file = File::create(&tmp)?;
        let mut w = BufWriter::with_capacity(1 << 20, file);
        write(&mut w)?;
        let file = w.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    result.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        Error::io(path, e)
    })
}

fn png_error(path: &Path, e: image::ImageError) -> std::io::Error {
    std::io::Error::other(format!("PNG encoding of {} failed: {e}", path.display()))
}

/// Heights → 16-bit values: p = round((h − lo)/(hi − lo)·65535), so that
/// h = lo + (hi − lo)·p/65535. A flat map (hi = lo) is all 0.
pub fn quantize_u16(map: &HeightMap, range: (f32, f32)) -> Vec<u16> {
    let (lo, hi) = range;
    let scale = if hi > lo {
        65535.0 / (hi as f64 - lo as f64)
    } else {
        0.0
    };
    map.data()
        .iter()
        .map(|&h| (((h as f64 - lo as f64) * scale).round()).clamp(0.0, 65535.0) as u16)
        .collect()
}

/// Writes the height map as a 16-bit grey PNG spanning its own [min, max]; returns the
/// range (lo, hi) with height = lo + (hi − lo)·p/65535 for a PNG value p.
pub fn write_height_png16(path: &Path, map: &HeightMap) -> Result<(f32, f32), Error> {
    let range = map.min_max();
    let values = quantize_u16(map, range);
    // `image` takes 16-bit samples in native byte order and swaps them for PNG itself.
    let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_ne_bytes()).collect();
    write_atomically(path, |w| {
        PngEncoder::new_with_quality(w, CompressionType::Fast, FilterType::Adaptive)
            .write_image(
                &bytes,
                map.width_px(),
                map.height_px(),
                image::ExtendedColorType::L16,
            )
            .map_err(|e| png_error(path, e))
    })?;
    Ok(range)
}

/// Writes the raw f32 heights as a single-channel (`Y`) OpenEXR file.
pub fn write_height_exr(path: &Path, map: &HeightMap) -> Result<(), Error> {
    use exr::prelude::*;
    let (w, h) = (map.width_px() as usize, map.height_px() as usize);
    let data = map.data();
    let channels = SpecificChannels::build()
        .with_channel("Y")
        .with_pixel_fn(|pos: Vec2<usize>| (data[pos.y() * w + pos.x()],));
    let image = Image::from_channels((w, h), channels);
    write_atomically(path, |out| {
        // `out` is already buffered (and seekable, which exr needs for its offset table).
        image
            .write()
            .to_unbuffered(out)
            .map_err(|e| std::io::Error::other(format!("OpenEXR encoding failed: {e}")))
    })
}

/// Writes 8-bit RGB pixels (`width × height × 3` bytes) as PNG.
pub fn write_rgb8_png(path: &Path, width_px: u32, height_px: u32, rgb: &[u8]) -> Result<(), Error> {
    write_atomically(path, |w| {
        PngEncoder::new_with_quality(w, CompressionType::Fast, FilterType::Adaptive)
            .write_image(rgb, width_px, height_px, image::ExtendedColorType::Rgb8)
            .map_err(|e| png_error(path, e))
    })
}

/// Writes 8-bit grey pixels as PNG (previews, masks).
pub fn write_grey8_png(
    path: &Path,
    width_px: u32,
    height_px: u32,
    grey: &[u8],
) -> Result<(), Error> {
    write_atomically(path, |w| {
        PngEncoder::new_with_quality(w, CompressionType::Fast, FilterType::Adaptive)
            .write_image(grey, width_px, height_px, image::ExtendedColorType::L8)
            .map_err(|e| png_error(path, e))
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
