//! Bounds on what an input can make the program do: file sizes, and message lengths.
//! Every reader of user files goes through [`read_file`], so no input can make agesim read
//! without bound; the limits are documented here and named in the errors.

use std::io::Read as _;
use std::path::Path;

use crate::base::error::Error;

/// Largest text input (project, wrinkle file) read, bytes: 16 MiB. A wrinkle file of that
/// size holds ~200,000 fibres; real ones are a few kilobytes.
pub const MAX_TEXT_FILE_BYTES: u64 = 16 << 20;
/// Largest image file read (masks, tiles), bytes: 256 MiB.
pub const MAX_IMAGE_FILE_BYTES: u64 = 256 << 20;
/// Largest side of a map agesim makes, pixels (a 16384² f32 map is 1 GiB).
pub const MAX_MAP_SIDE_PX: u32 = 16384;
/// Largest side of a decoded image (mask, tile), pixels: the largest map agesim makes.
pub const MAX_IMAGE_SIDE_PX: u32 = MAX_MAP_SIDE_PX;
/// Largest memory an image decode may allocate, bytes: 2 GiB (a 16384² 16-bit RGBA image).
pub const MAX_IMAGE_DECODE_BYTES: u64 = 2 << 30;
/// Largest mesh file read, bytes: 1 GiB.
pub const MAX_MESH_FILE_BYTES: u64 = 1 << 30;

/// Memory a head takes per triangle once read, fitted and measured, bytes: the mesh with
/// its tangents, the fit and its proxy (measured: a 1.13M-triangle head 361 MiB in
/// `mesh-info`, ≈ 320 bytes a triangle; 2.28M, 648 MiB, ≈ 290), with room. Aged in the
/// editor it takes about 1,100 (1.2 GiB for 1.13M): not checked against this.
pub const HEAD_BYTES_PER_TRIANGLE: u64 = 400;

/// The memory the system can still give (`MemAvailable` of /proc/meminfo), where the
/// platform says; `None` elsewhere.
pub fn available_memory_bytes() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Refuses a head of `triangles` that would not fit in `available` bytes
/// ([`HEAD_BYTES_PER_TRIANGLE`] each), naming the file, what it needs and what is free:
/// a scan of millions of triangles is read when the machine can hold it, and refused at
/// once, never left to swap or be killed, when it cannot. `None`: not known, not refused.
pub fn check_head_fits(path: &Path, triangles: usize, available: Option<u64>) -> Result<(), Error> {
    let needed = triangles as u64 * HEAD_BYTES_PER_TRIANGLE;
    match available {
        Some(free) if needed > free => Err(Error::InvalidValue {
            what: format!("{}: a head of {triangles} triangles", path.display()),
            value: format!(
                "about {:.1} GiB to read and fit, with {:.1} GiB free",
                needed as f64 / f64::from(1u32 << 30),
                free as f64 / f64::from(1u32 << 30)
            ),
            expected: format!(
                "at most {} triangles on this machine now: decimate it (Blender's Decimate modifier, ZBrush's Decimation Master) or free memory",
                free / HEAD_BYTES_PER_TRIANGLE
            ),
        }),
        _ => Ok(()),
    }
}

/// Reads at most `limit` bytes of `path`; a longer file (or an endless one such as
/// `/dev/zero`) is an error naming the file and the limit, after reading `limit + 1` bytes.
pub fn read_file(path: &Path, limit: u64) -> Result<Vec<u8>, Error> {
    let file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    let mut bytes = Vec::new();
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| Error::io(path, e))?;
    if bytes.len() as u64 > limit {
        return Err(Error::TooLarge {
            path: path.to_owned(),
            limit_bytes: limit,
        });
    }
    Ok(bytes)
}

/// Long inputs cut for messages (it lives with the diagnostics, which every error uses).
pub use crate::base::diagnostic::shorten;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_are_bounded_even_for_endless_files() {
        let e = read_file(Path::new("/dev/zero"), 1000)
            .unwrap_err()
            .to_string();
        assert!(e.contains("/dev/zero") && e.contains("1000"), "{e}");
    }

    #[test]
    fn a_head_too_large_for_the_memory_is_refused_naming_it() {
        let path = Path::new("scan-5M.obj");
        let e = check_head_fits(path, 5_000_000, Some(1 << 30))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("scan-5M.obj") && e.contains("5000000 triangles") && e.contains("1.9 GiB"),
            "{e}"
        );
        assert!(e.contains("1.0 GiB free") && e.contains("decimate"), "{e}");
        // The same head fits a larger machine; an unknown amount refuses nothing.
        check_head_fits(path, 5_000_000, Some(4 << 30)).unwrap();
        check_head_fits(path, 5_000_000, None).unwrap();
    }

    #[test]
    fn shorten_cuts_on_characters() {
        assert_eq!(shorten("abc", 5), "abc");
        assert_eq!(shorten("ééééé", 2), "éé…");
    }
}
