//! PNG encoding for every map and picture agesim writes, through the `png` crate directly:
//! Paeth filtering (the same sizes as adaptive filtering on our maps, ≈ 25 % faster) and
//! `fdeflate`'s fast lossless deflate. Rows can be streamed, so a 16-bit map is converted
//! to big-endian samples a band at a time instead of in whole-map copies (at 4096² each
//! whole copy is 32 MB of freshly faulted memory).

use std::io::Write;

/// The pixel layouts we write.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PngPixels {
    Grey8,
    /// 16-bit grey, samples big-endian (PNG's byte order).
    Grey16,
    Rgb8,
    Rgba8,
}

impl PngPixels {
    pub fn bytes_per_pixel(self) -> usize {
        match self {
            Self::Grey8 => 1,
            Self::Grey16 => 2,
            Self::Rgb8 => 3,
            Self::Rgba8 => 4,
        }
    }
}

/// Rows converted per band when streaming.
const BAND_ROWS: u32 = 32;

fn encoder<W: Write>(
    w: W,
    width_px: u32,
    height_px: u32,
    pixels: PngPixels,
) -> ::png::Encoder<'static, W> {
    let mut e = ::png::Encoder::new(w, width_px, height_px);
    let (colour, depth) = match pixels {
        PngPixels::Grey8 => (::png::ColorType::Grayscale, ::png::BitDepth::Eight),
        PngPixels::Grey16 => (::png::ColorType::Grayscale, ::png::BitDepth::Sixteen),
        PngPixels::Rgb8 => (::png::ColorType::Rgb, ::png::BitDepth::Eight),
        PngPixels::Rgba8 => (::png::ColorType::Rgba, ::png::BitDepth::Eight),
    };
    e.set_color(colour);
    e.set_depth(depth);
    e.set_compression(::png::Compression::Fast);
    e.set_filter(::png::Filter::Paeth);
    e
}

fn io_error(e: ::png::EncodingError) -> std::io::Error {
    match e {
        ::png::EncodingError::IoError(e) => e,
        e => std::io::Error::other(format!("PNG encoding failed: {e}")),
    }
}

/// Encodes a whole image held in memory (`width × height × bytes per pixel` bytes).
pub fn encode_png<W: Write>(
    w: W,
    width_px: u32,
    height_px: u32,
    pixels: PngPixels,
    data: &[u8],
) -> std::io::Result<()> {
    let expected = width_px as usize * height_px as usize * pixels.bytes_per_pixel();
    if data.len() != expected {
        return Err(std::io::Error::other(format!(
            "PNG encoding failed: {} bytes for a {width_px}×{height_px} image of {expected}",
            data.len()
        )));
    }
    let mut writer = encoder(w, width_px, height_px, pixels)
        .write_header()
        .map_err(io_error)?;
    writer.write_image_data(data).map_err(io_error)?;
    writer.finish().map_err(io_error)
}

/// Encodes an image whose rows are produced band by band: `rows(first_row, row_count, buf)`
/// appends `row_count` rows starting at `first_row` to the empty `buf`; its error ends
/// the encoding with that error.
pub fn encode_png_rows<W: Write>(
    w: W,
    width_px: u32,
    height_px: u32,
    pixels: PngPixels,
    mut rows: impl FnMut(u32, u32, &mut Vec<u8>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let row_bytes = width_px as usize * pixels.bytes_per_pixel();
    let mut writer = encoder(w, width_px, height_px, pixels)
        .write_header()
        .map_err(io_error)?;
    let mut stream = writer
        .stream_writer_with_size(row_bytes * BAND_ROWS as usize)
        .map_err(io_error)?;
    let mut buf = Vec::with_capacity(row_bytes * BAND_ROWS as usize);
    let mut first = 0;
    while first < height_px {
        let count = BAND_ROWS.min(height_px - first);
        buf.clear();
        rows(first, count, &mut buf)?;
        if buf.len() != row_bytes * count as usize {
            return Err(std::io::Error::other(format!(
                "PNG encoding failed: rows {first}.. gave {} bytes, not {}",
                buf.len(),
                row_bytes * count as usize
            )));
        }
        stream.write_all(&buf)?;
        first += count;
    }
    stream.finish().map_err(io_error)?;
    // The image end (IEND): written by `finish`, so that its error is not lost.
    writer.finish().map_err(io_error)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streamed_rows_decode_to_the_same_pixels_as_a_whole_image() {
        let (w, h) = (37u32, 71u32);
        let data: Vec<u8> = (0..w * h * 2).map(|i| (i * 7 % 251) as u8).collect();
        let mut whole = Vec::new();
        encode_png(&mut whole, w, h, PngPixels::Grey16, &data).unwrap();
        let mut streamed = Vec::new();
        let row = (w * 2) as usize;
        encode_png_rows(
            &mut streamed,
            w,
            h,
            PngPixels::Grey16,
            |first, count, buf| {
                let a = first as usize * row;
                buf.extend_from_slice(&data[a..a + count as usize * row]);
                Ok(())
            },
        )
        .unwrap();
        for png in [whole, streamed] {
            let img = image::load_from_memory(&png).unwrap().into_luma16();
            let back: Vec<u8> = img
                .into_raw()
                .iter()
                .flat_map(|v| v.to_be_bytes())
                .collect();
            assert_eq!(back, data);
        }
    }

    #[test]
    fn a_wrong_byte_count_is_an_error_not_a_panic() {
        let mut out = Vec::new();
        assert!(encode_png(&mut out, 4, 4, PngPixels::Rgb8, &[0; 5]).is_err());
        let e = encode_png_rows(&mut out, 4, 4, PngPixels::Grey8, |_, _, buf| {
            buf.push(1);
            Ok(())
        });
        assert!(e.is_err());
        let failing = |_, _, _: &mut Vec<u8>| Err(std::io::Error::other("no rows"));
        let e = encode_png_rows(&mut out, 4, 4, PngPixels::Grey8, failing).unwrap_err();
        assert_eq!(e.to_string(), "no rows");
    }
}
