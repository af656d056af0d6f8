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
    fn shorten_cuts_on_characters() {
        assert_eq!(shorten("abc", 5), "abc");
        assert_eq!(shorten("ééééé", 2), "éé…");
    }
}
