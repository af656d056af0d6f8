//! A one-channel (`Y`, 32-bit float) scan-line OpenEXR writer for height maps, with no
//! compression or with RLE compression of each line, the lines compressed in parallel.
//!
//! Why our own: the `exr` crate's writer is general (any channels, tiles, levels) and
//! single-threaded here; at 4096² it took 150–420 ms for an uncompressed map and 200–300 ms
//! for RLE, more than everything else `agesim bake` does. This writer streams the f32
//! slice straight into the file (none) or run-length codes the lines on all cores (RLE,
//! lossless like every EXR compression). The files are standard OpenEXR 2.0 single-part
//! scan-line images; the tests read them back with the `exr` crate, which still writes the
//! ZIP variant (`stage_height_exr_with`): a fast deflate (`fdeflate`) is tuned for PNG's
//! filtered bytes and did not shrink EXR's predicted bytes at all.
//!
//! Layout (OpenEXR "Technical Introduction", file layout): magic and version; the header's
//! attributes, then a 0 byte; the offset table (one u64 file position per block); the
//! blocks, each `y: i32, size: i32, data`. RLE data is the line's bytes split into even-
//! and odd-indexed halves, delta-coded (`d = b[i] − b[i−1] + 128`), then run-length coded
//! as OpenEXR's `ImfRle.cpp` does; a line that would not shrink is stored raw, which
//! readers recognise by its full size.

use std::io::{Seek, SeekFrom, Write};

use rayon::prelude::*;

/// How the blocks are stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Blocks {
    /// One line per block, raw little-endian floats.
    Uncompressed,
    /// One line per block, run-length coded after OpenEXR's byte split and predictor.
    Rle,
}

impl Blocks {
    /// The header's `compression` attribute value.
    fn code(self) -> u8 {
        match self {
            Self::Uncompressed => 0,
            Self::Rle => 1,
        }
    }
}

/// Lines compressed per parallel batch (bounds the memory held at once).
const BATCH_LINES: usize = 256;

fn attribute(out: &mut Vec<u8>, name: &str, kind: &str, value: &[u8]) {
    out.extend_from_slice(name.as_bytes());
    out.push(0);
    out.extend_from_slice(kind.as_bytes());
    out.push(0);
    out.extend_from_slice(&(value.len() as i32).to_le_bytes());
    out.extend_from_slice(value);
}

fn header(width: usize, height: usize, blocks: Blocks) -> Vec<u8> {
    let mut h = Vec::with_capacity(400);
    h.extend_from_slice(&20000630i32.to_le_bytes());
    h.extend_from_slice(&[2, 0, 0, 0]);
    // One channel "Y": FLOAT (2), not perceptually linear, sampling 1×1; list ends in 0.
    let mut channels = b"Y\0".to_vec();
    channels.extend_from_slice(&2i32.to_le_bytes());
    channels.extend_from_slice(&[0, 0, 0, 0]);
    channels.extend_from_slice(&1i32.to_le_bytes());
    channels.extend_from_slice(&1i32.to_le_bytes());
    channels.push(0);
    attribute(&mut h, "channels", "chlist", &channels);
    attribute(&mut h, "compression", "compression", &[blocks.code()]);
    let window: Vec<u8> = [0, 0, width as i32 - 1, height as i32 - 1]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    attribute(&mut h, "dataWindow", "box2i", &window);
    attribute(&mut h, "displayWindow", "box2i", &window);
    attribute(&mut h, "lineOrder", "lineOrder", &[0]);
    attribute(&mut h, "pixelAspectRatio", "float", &1f32.to_le_bytes());
    attribute(&mut h, "screenWindowCenter", "v2f", &[0; 8]);
    attribute(&mut h, "screenWindowWidth", "float", &1f32.to_le_bytes());
    h.push(0);
    h
}

/// Appends `values` as little-endian bytes.
fn extend_le(out: &mut Vec<u8>, values: &[f32]) {
    if cfg!(target_endian = "little") {
        out.extend_from_slice(bytemuck::cast_slice(values));
    } else {
        out.extend(values.iter().flat_map(|v| v.to_le_bytes()));
    }
}

/// OpenEXR's byte split and predictor of one line of floats, into `out`: the line's
/// little-endian bytes at even indices, then those at odd ones (bytes 0, 2 then 1, 3 of each
/// float), each replaced by its difference from the one before plus 128 (mod 256).
/// Compiled per CPU level ([`crate::base::simd::dispatch_at`]) so both passes vectorise.
struct Predict<'a> {
    line: &'a [f32],
    split: &'a mut [u8],
    out: &'a mut [u8],
}

impl crate::base::simd::Kernel for Predict<'_> {
    type Output = ();
    #[inline(always)]
    fn run(self) {
        let half = 2 * self.line.len();
        let (even, odd) = self.split.split_at_mut(half);
        for ((v, e), o) in self
            .line
            .iter()
            .zip(even.chunks_exact_mut(2))
            .zip(odd.chunks_exact_mut(2))
        {
            let b = v.to_le_bytes();
            e.copy_from_slice(&[b[0], b[2]]);
            o.copy_from_slice(&[b[1], b[3]]);
        }
        if let (Some(first), Some(&b)) = (self.out.first_mut(), self.split.first()) {
            *first = b;
        }
        for (d, pair) in self.out[1..].iter_mut().zip(self.split.windows(2)) {
            *d = pair[1].wrapping_sub(pair[0]).wrapping_add(128);
        }
    }
}

fn predict(line: &[f32], split: &mut Vec<u8>, out: &mut Vec<u8>) {
    let n = 4 * line.len();
    split.resize(n, 0);
    out.resize(n, 0);
    let kernel = Predict { line, split, out };
    crate::base::simd::dispatch_at(crate::base::simd::Level::detect(), kernel);
}

/// OpenEXR's run-length code (`ImfRle.cpp`, `rleCompress`): a run of 3–128 equal bytes is
/// `count − 1, byte`; other bytes go in literal groups of up to 127, `−count, bytes…`.
fn run_length(input: &[u8], out: &mut Vec<u8>) {
    const MIN_RUN: usize = 3;
    const MAX_RUN: usize = 127;
    let n = input.len();
    let mut start = 0;
    let mut end = 1;
    while start < n {
        while end < n && input[start] == input[end] && end - start - 1 < MAX_RUN {
            end += 1;
        }
        if end - start >= MIN_RUN {
            out.push((end - start - 1) as u8);
            out.push(input[start]);
            start = end;
        } else {
            while end < n
                && (end + 1 >= n
                    || input[end] != input[end + 1]
                    || end + 2 >= n
                    || input[end + 1] != input[end + 2])
                && end - start < MAX_RUN
            {
                end += 1;
            }
            out.push((-((end - start) as i32)) as i8 as u8);
            out.extend_from_slice(&input[start..end]);
            start = end;
        }
        end += 1;
    }
}

/// One RLE line's stored bytes: coded, or the raw line when that is not smaller.
fn rle_line(line: &[f32], split: &mut Vec<u8>, predicted: &mut Vec<u8>) -> Vec<u8> {
    predict(line, split, predicted);
    let mut packed = Vec::with_capacity(predicted.len() / 4);
    run_length(predicted, &mut packed);
    if packed.len() < predicted.len() {
        packed
    } else {
        let mut raw = Vec::with_capacity(predicted.len());
        extend_le(&mut raw, line);
        raw
    }
}

/// Writes `data` (`width × height` floats, row-major, row 0 at the top) as an OpenEXR file.
pub fn write_y_f32<W: Write + Seek>(
    out: &mut W,
    width: usize,
    height: usize,
    data: &[f32],
    blocks: Blocks,
) -> std::io::Result<()> {
    if width == 0 || height == 0 || data.len() != width * height || width > i32::MAX as usize {
        return Err(std::io::Error::other(format!(
            "OpenEXR encoding failed: {} values for a {width}×{height} image",
            data.len()
        )));
    }
    let start = out.stream_position()?;
    let header = header(width, height, blocks);
    out.write_all(&header)?;
    let count = height;
    let table_at = start + header.len() as u64;
    let mut offsets = Vec::with_capacity(count);
    let mut at = table_at + 8 * count as u64;
    match blocks {
        Blocks::Uncompressed => {
            let size = 4 * width;
            let table: Vec<u8> = (0..count as u64)
                .flat_map(|k| (at + k * (8 + size as u64)).to_le_bytes())
                .collect();
            out.write_all(&table)?;
            let mut chunk = Vec::with_capacity(8 + size);
            for (y, row) in data.chunks_exact(width).enumerate() {
                chunk.clear();
                chunk.extend_from_slice(&(y as i32).to_le_bytes());
                chunk.extend_from_slice(&(size as i32).to_le_bytes());
                extend_le(&mut chunk, row);
                out.write_all(&chunk)?;
            }
            return Ok(());
        }
        Blocks::Rle => {
            // The table is written after the lines, when their sizes are known.
            out.write_all(&vec![0; 8 * count])?;
            for (b, batch) in data.chunks(BATCH_LINES * width).enumerate() {
                let packed: Vec<Vec<u8>> = batch
                    .par_chunks(width)
                    .map_init(
                        || (Vec::new(), Vec::new()),
                        |(split, predicted), line| rle_line(line, split, predicted),
                    )
                    .collect();
                for (k, line) in packed.iter().enumerate() {
                    let y = b * BATCH_LINES + k;
                    offsets.push(at);
                    out.write_all(&(y as i32).to_le_bytes())?;
                    out.write_all(&(line.len() as i32).to_le_bytes())?;
                    out.write_all(line)?;
                    at += 8 + line.len() as u64;
                }
            }
        }
    }
    let table: Vec<u8> = offsets.iter().flat_map(|o| o.to_le_bytes()).collect();
    out.seek(SeekFrom::Start(table_at))?;
    out.write_all(&table)?;
    out.seek(SeekFrom::Start(at))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read_back(bytes: Vec<u8>) -> (usize, usize, Vec<f32>) {
        use exr::prelude::*;
        let image = read()
            .no_deep_data()
            .largest_resolution_level()
            .all_channels()
            .all_layers()
            .all_attributes()
            .from_buffered(std::io::Cursor::new(bytes))
            .unwrap();
        let layer = &image.layer_data[0];
        let size = layer.size;
        let channel = &layer.channel_data.list[0];
        assert_eq!(channel.name, Text::from("Y"));
        let values = match &channel.sample_data {
            FlatSamples::F32(v) => v.clone(),
            other => panic!("not f32: {other:?}"),
        };
        (size.width(), size.height(), values)
    }

    #[test]
    fn both_block_kinds_read_back_bit_identical_through_the_exr_crate() {
        // Smooth and noisy halves, so some lines compress and some are stored raw.
        let (w, h) = (45, 37);
        let data: Vec<f32> = (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as f32, (i / w) as f32);
                if y < 18.0 {
                    (x * 0.1).sin() + y * 0.01
                } else {
                    f32::from_bits((i as u32).wrapping_mul(2_654_435_761) >> 2)
                }
            })
            .collect();
        for blocks in [Blocks::Uncompressed, Blocks::Rle] {
            let mut file = std::io::Cursor::new(Vec::new());
            write_y_f32(&mut file, w, h, &data, blocks).unwrap();
            let (rw, rh, back) = read_back(file.into_inner());
            assert_eq!((rw, rh), (w, h), "{blocks:?}");
            let same = back
                .iter()
                .zip(&data)
                .all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same, "{blocks:?}: values differ");
        }
    }

    #[test]
    fn rle_lines_do_not_depend_on_the_thread_count() {
        let (w, h) = (64, 200);
        let data: Vec<f32> = (0..w * h).map(|i| (i as f32 * 0.37).sin()).collect();
        let write = |threads| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let mut file = std::io::Cursor::new(Vec::new());
                write_y_f32(&mut file, w, h, &data, Blocks::Rle).unwrap();
                file.into_inner()
            })
        };
        assert_eq!(write(1), write(3));
    }

    /// OpenEXR's decoder (`ImfRle.cpp`, `rleUncompress`), to check the coder on edge cases.
    fn run_length_decode(mut input: &[u8]) -> Vec<u8> {
        let mut out = Vec::new();
        while let Some((&c, rest)) = input.split_first() {
            let c = c as i8;
            if c < 0 {
                let n = (-(c as i32)) as usize;
                out.extend_from_slice(&rest[..n]);
                input = &rest[n..];
            } else {
                out.extend(std::iter::repeat_n(rest[0], c as usize + 1));
                input = &rest[1..];
            }
        }
        out
    }

    #[test]
    fn run_length_code_round_trips_on_edge_cases() {
        let mut cases: Vec<Vec<u8>> = vec![
            vec![7],
            vec![7, 7],
            vec![7, 7, 7],
            vec![1, 2, 2, 2, 3],
            vec![5; 127],
            vec![5; 128],
            vec![5; 129],
            vec![5; 400],
            (0..=255).collect(),
            (0..300).map(|i| (i / 2) as u8).collect(),
        ];
        cases.push(
            (0..1000u32)
                .map(|i| (i.wrapping_mul(2_654_435_761) >> 29) as u8)
                .collect(),
        );
        for case in cases {
            let mut coded = Vec::new();
            run_length(&case, &mut coded);
            assert_eq!(run_length_decode(&coded), case, "{case:?}");
        }
    }

    #[test]
    fn a_size_that_does_not_match_the_data_is_an_error() {
        let mut file = std::io::Cursor::new(Vec::new());
        assert!(write_y_f32(&mut file, 3, 3, &[0.0; 8], Blocks::Rle).is_err());
        assert!(write_y_f32(&mut file, 0, 3, &[], Blocks::Uncompressed).is_err());
    }
}
