//! Grey-scale masks in UV space (docs/models.md §2 "Mask", §6 hair masks).
//!
//! A mask is any image, any size, read as luminance in [0,1] and sampled bilinearly in UV
//! (docs/models.md §1 conventions: v up, row 0 at the top), clamped at the borders.

use std::path::Path;

use crate::base::error::Error;

/// Decodes an image file in memory within the limits of [`crate::base::limits`]: the header is
/// checked before any pixel is decoded, so a small file declaring 20000×20000 pixels is
/// refused, not allocated. `path` names the file in errors.
pub fn decode_image(bytes: &[u8], path: &Path) -> Result<image::DynamicImage, Error> {
    let fail = |message: String| Error::Image {
        path: path.to_owned(),
        message,
    };
    // The format from the content, else from the name: a TGA (the usual format of game
    // art) has no signature to guess it by.
    let reader_of = || -> Result<_, Error> {
        let mut reader = image::ImageReader::new(std::io::Cursor::new(bytes))
            .with_guessed_format()
            .map_err(|e| fail(e.to_string()))?;
        if reader.format().is_none()
            && let Ok(format) = image::ImageFormat::from_path(path)
        {
            reader.set_format(format);
        }
        Ok(reader)
    };
    let (w, h) = reader_of()?
        .into_dimensions()
        .map_err(|e| fail(e.to_string()))?;
    let max = crate::base::limits::MAX_IMAGE_SIDE_PX;
    if w > max || h > max {
        return Err(fail(format!(
            "the image declares {w}×{h} pixels, more than the limit of {max} on a side"
        )));
    }
    let mut reader = reader_of()?;
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(max);
    limits.max_image_height = Some(max);
    limits.max_alloc = Some(crate::base::limits::MAX_IMAGE_DECODE_BYTES);
    reader.limits(limits);
    reader.decode().map_err(|e| fail(e.to_string()))
}

/// What a picture's values are: a colour (stored sRGB-encoded) or data (a normal map's
/// linear values).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Encoding {
    Colour,
    Data,
}

/// An RGBA8 picture over a head's own UVs, row 0 at the top (docs/models.md §1): its
/// base colour map (sRGB) or its tangent-space normal map (linear).
#[derive(Clone, Debug, PartialEq)]
pub struct HeadImage {
    pub width_px: u32,
    pub height_px: u32,
    /// RGBA, 4 bytes a texel (sRGB-encoded for a colour map).
    pub rgba: Vec<u8>,
}

impl HeadImage {
    /// Reads a colour map in any format `image` decodes, as 8-bit sRGB RGBA; `flip_v`
    /// turns it upside down (a head whose UVs use the other v convention than its picture).
    pub fn load(path: &Path, flip_v: bool) -> Result<Self, Error> {
        Self::load_as(path, flip_v, Encoding::Colour)
    }

    /// [`HeadImage::load`] of a colour map or of a data map (a normal map).
    pub fn load_as(path: &Path, flip_v: bool, encoding: Encoding) -> Result<Self, Error> {
        let bytes =
            crate::base::limits::read_file(path, crate::base::limits::MAX_IMAGE_FILE_BYTES)?;
        let mut img = Self::decode_as(&bytes, path, encoding)?;
        if flip_v {
            let row = img.width_px as usize * 4;
            let rows: Vec<&[u8]> = img.rgba.chunks_exact(row).rev().collect();
            img.rgba = rows.concat();
        }
        Ok(img)
    }

    /// Decodes a colour map in memory (a picture embedded in a GLB); `path` names it in
    /// errors.
    pub fn decode(bytes: &[u8], path: &Path) -> Result<Self, Error> {
        Self::decode_as(bytes, path, Encoding::Colour)
    }

    /// Decodes a colour map or a data map in memory. A floating-point picture (OpenEXR,
    /// half or float) holds linear values: a colour map's are sRGB-encoded to 8 bits as
    /// every other colour map is stored, a data map's (a normal map's, in [0, 1]) are
    /// kept linear; values beyond [0, 1] are clamped.
    pub fn decode_as(bytes: &[u8], path: &Path, encoding: Encoding) -> Result<Self, Error> {
        let img = decode_image(bytes, path)?;
        let float = matches!(
            img,
            image::DynamicImage::ImageRgb32F(_) | image::DynamicImage::ImageRgba32F(_)
        );
        let img = if float && encoding == Encoding::Colour {
            let mut rgba = img.into_rgba32f();
            for p in rgba.pixels_mut() {
                for c in &mut p.0[..3] {
                    *c = linear_to_srgb(c.clamp(0.0, 1.0));
                }
            }
            image::DynamicImage::ImageRgba32F(rgba).into_rgba8()
        } else {
            img.into_rgba8()
        };
        let (width_px, height_px) = img.dimensions();
        Ok(Self {
            width_px,
            height_px,
            rgba: img.into_raw(),
        })
    }

    /// The colour at (u, v), 0–255 per channel, bilinear between texel centres, u
    /// wrapping and v clamped (as the view's surface sampler reads a head's pictures).
    pub fn rgb_at(&self, u: f32, v: f32) -> glam::Vec3 {
        let (w, h) = (self.width_px as i64, self.height_px as i64);
        let x = u * w as f32 - 0.5;
        let y = (1.0 - v) * h as f32 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let at = |xi: i64, yi: i64| {
            let i = ((yi.clamp(0, h - 1) * w + xi.rem_euclid(w)) * 4) as usize;
            glam::Vec3::new(
                f32::from(self.rgba[i]),
                f32::from(self.rgba[i + 1]),
                f32::from(self.rgba[i + 2]),
            )
        };
        let (x0, y0) = (x0 as i64, y0 as i64);
        let top = at(x0, y0).lerp(at(x0 + 1, y0), fx);
        let bottom = at(x0, y0 + 1).lerp(at(x0 + 1, y0 + 1), fx);
        top.lerp(bottom, fy)
    }

    /// The tangent-space normal at (u, v) ([`HeadImage::rgb_at`]) of a normal map, OpenGL
    /// convention (green = +v) unless `green_down` (DirectX).
    pub fn normal_at(&self, u: f32, v: f32, green_down: bool) -> glam::Vec3 {
        let mut n = self.rgb_at(u, v) / 255.0 * 2.0 - glam::Vec3::ONE;
        if green_down {
            n.y = -n.y;
        }
        n.normalize_or(glam::Vec3::Z)
    }
}

/// The sRGB transfer function undone: an encoded value in [0, 1] to linear light.
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// The sRGB transfer function: linear light in [0, 1] to its encoded value.
pub fn linear_to_srgb(l: f32) -> f32 {
    if l <= 0.003_130_8 {
        l * 12.92
    } else {
        1.055 * l.powf(1.0 / 2.4) - 0.055
    }
}

/// A grey-scale image with values in [0,1], sampled in UV.
#[derive(Clone, Debug, PartialEq)]
pub struct Mask {
    width_px: u32,
    height_px: u32,
    values: Vec<f32>,
}

impl Mask {
    /// Builds a mask from row-major values (row 0 at the top); values are clamped to [0,1]
    /// and NaN becomes 0.
    pub fn from_values(width_px: u32, height_px: u32, mut values: Vec<f32>) -> Result<Self, Error> {
        if width_px == 0 || height_px == 0 || values.len() != width_px as usize * height_px as usize
        {
            return Err(Error::InvalidValue {
                what: "mask size".into(),
                value: format!("{width_px}×{height_px} with {} values", values.len()),
                expected: "a non-empty image with width×height values".into(),
            });
        }
        for v in &mut values {
            *v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
        }
        Ok(Self {
            width_px,
            height_px,
            values,
        })
    }

    /// Reads any image `image` can decode (PNG, JPEG, TIFF, BMP, TGA; 8 or 16 bit) as
    /// luminance. Colour images are converted with Rec. 709 weights; alpha is ignored.
    pub fn load(path: &Path) -> Result<Self, Error> {
        let bytes =
            crate::base::limits::read_file(path, crate::base::limits::MAX_IMAGE_FILE_BYTES)?;
        Self::decode(&bytes, path)
    }

    /// Decodes an image file already in memory, as [`Mask::load`] does; `path` only names
    /// it in errors (e.g. a mask built into the binary).
    pub fn decode(bytes: &[u8], path: &Path) -> Result<Self, Error> {
        let img = decode_image(bytes, path)?;
        let grey = img.into_luma16();
        let (w, h) = grey.dimensions();
        let values = grey
            .into_raw()
            .into_iter()
            .map(|p| p as f32 / 65535.0)
            .collect();
        Self::from_values(w, h, values)
    }

    pub fn width_px(&self) -> u32 {
        self.width_px
    }

    pub fn height_px(&self) -> u32 {
        self.height_px
    }

    /// Row-major values in [0,1], row 0 at the top.
    pub fn values(&self) -> &[f32] {
        &self.values
    }

    /// Bilinear sample at (u, v), clamped to the border texels.
    pub fn sample(&self, u: f32, v: f32) -> f32 {
        self.sample_taps(self.tap_u(u), self.tap_v(v))
    }

    /// The texel pair and weight along x for `u` (continuous pixel coordinates whose
    /// integer points are texel centres, clamped to the border).
    #[inline]
    pub(crate) fn tap_u(&self, u: f32) -> (usize, usize, f32) {
        let w = self.width_px as usize;
        let fx = (u * w as f32 - 0.5).clamp(0.0, (w - 1) as f32);
        let x0 = fx.floor() as usize;
        (x0, (x0 + 1).min(w - 1), fx - x0 as f32)
    }

    /// The texel-row pair and weight along y for `v` (row 0 at the top, v up).
    #[inline]
    pub(crate) fn tap_v(&self, v: f32) -> (usize, usize, f32) {
        let h = self.height_px as usize;
        let fy = ((1.0 - v) * h as f32 - 0.5).clamp(0.0, (h - 1) as f32);
        let y0 = fy.floor() as usize;
        (y0, (y0 + 1).min(h - 1), fy - y0 as f32)
    }

    /// The bilinear sample between two taps: [`Mask::sample`] with the taps made once per
    /// column and per row when a whole grid is sampled (same bytes, no floor per pixel).
    #[inline]
    pub(crate) fn sample_taps(
        &self,
        (x0, x1, tx): (usize, usize, f32),
        (y0, y1, ty): (usize, usize, f32),
    ) -> f32 {
        let w = self.width_px as usize;
        let at = |x: usize, y: usize| self.values[y * w + x];
        let top = at(x0, y0) + (at(x1, y0) - at(x0, y0)) * tx;
        let bottom = at(x0, y1) + (at(x1, y1) - at(x0, y1)) * tx;
        top + (bottom - top) * ty
    }

    /// Resamples to `width_px × height_px` by bilinear sampling at the new pixel centres.
    pub fn resampled(&self, width_px: u32, height_px: u32) -> Result<Self, Error> {
        if width_px == self.width_px && height_px == self.height_px {
            return Ok(self.clone());
        }
        crate::maps::heightmap::check_size(width_px, height_px)?;
        let mut values = Vec::with_capacity(width_px as usize * height_px as usize);
        for y in 0..height_px {
            let v = crate::maps::heightmap::pixel_to_v(y, height_px);
            for x in 0..width_px {
                values.push(self.sample(crate::maps::heightmap::pixel_to_u(x, width_px), v));
            }
        }
        Self::from_values(width_px, height_px, values)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every format an artist's colour map comes in reads to the same texels: PNG (8 and
    /// 16 bit), JPEG (within its loss), TIFF (8 and 16 bit), BMP and TGA; a file no decoder
    /// knows is refused with its name.
    #[test]
    fn every_input_format_reads_to_the_same_texels() {
        use image::{DynamicImage, ImageFormat, Rgb, RgbImage};
        // 4×2: the top row red, green, blue, white; the bottom row a gray ramp.
        let colours = [
            [255, 0, 0],
            [0, 255, 0],
            [0, 0, 255],
            [255, 255, 255],
            [0, 0, 0],
            [85, 85, 85],
            [170, 170, 170],
            [255, 255, 255],
        ];
        let rgb = RgbImage::from_fn(4, 2, |x, y| Rgb(colours[(y * 4 + x) as usize]));
        let encode = |img: DynamicImage, format: ImageFormat| {
            let mut bytes = std::io::Cursor::new(Vec::new());
            img.write_to(&mut bytes, format).unwrap();
            bytes.into_inner()
        };
        let eight = DynamicImage::ImageRgb8(rgb.clone());
        let sixteen = DynamicImage::ImageRgb16(eight.to_rgb16());
        let cases = [
            ("map.png", encode(eight.clone(), ImageFormat::Png), 0),
            ("map16.png", encode(sixteen.clone(), ImageFormat::Png), 0),
            ("map.jpg", encode(eight.clone(), ImageFormat::Jpeg), 60),
            ("map.tif", encode(eight.clone(), ImageFormat::Tiff), 0),
            ("map16.tiff", encode(sixteen, ImageFormat::Tiff), 0),
            ("map.bmp", encode(eight.clone(), ImageFormat::Bmp), 0),
            ("map.tga", encode(eight.clone(), ImageFormat::Tga), 0),
            // OpenEXR holds linear light: float and half, sRGB-encoded as colour maps are.
            (
                "map.exr",
                encode(linear_float(&eight), ImageFormat::OpenExr),
                1,
            ),
            ("map-half.exr", half_exr(&eight), 1),
        ];
        for (name, bytes, tolerance) in cases {
            let img = HeadImage::decode(&bytes, Path::new(name))
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!((img.width_px, img.height_px), (4, 2), "{name}");
            for (i, c) in colours.iter().enumerate() {
                let got = &img.rgba[4 * i..4 * i + 3];
                for k in 0..3 {
                    assert!(
                        got[k].abs_diff(c[k]) <= tolerance,
                        "{name}: texel {i} is {got:?}, not {c:?}"
                    );
                }
            }
        }
        let e = HeadImage::decode(b"not an image at all", Path::new("map.webp")).unwrap_err();
        assert!(e.to_string().contains("map.webp"), "{e}");
        // A normal map in EXR is data: its values as they are, not sRGB-encoded.
        let normal = DynamicImage::ImageRgb32F(image::Rgb32FImage::from_pixel(
            2,
            2,
            image::Rgb([0.5, 0.5, 1.0]),
        ));
        let bytes = encode(normal, ImageFormat::OpenExr);
        let data = HeadImage::decode_as(&bytes, Path::new("n.exr"), Encoding::Data).unwrap();
        assert_eq!(&data.rgba[..4], &[128, 128, 255, 255]);
        let colour = HeadImage::decode(&bytes, Path::new("n.exr")).unwrap();
        assert_eq!(
            &colour.rgba[..3],
            &[188, 188, 255],
            "0.5 linear is 188 in sRGB"
        );
    }

    /// `img`'s sRGB colours as linear floats (what an OpenEXR colour map holds).
    fn linear_float(img: &image::DynamicImage) -> image::DynamicImage {
        let mut f = img.to_rgb32f();
        for p in f.pixels_mut() {
            for c in &mut p.0 {
                *c = srgb_to_linear(*c);
            }
        }
        image::DynamicImage::ImageRgb32F(f)
    }

    /// `img` as a half-float OpenEXR file of linear light, written by the `exr` crate.
    fn half_exr(img: &image::DynamicImage) -> Vec<u8> {
        use exr::prelude::*;
        let f = linear_float(img).to_rgb32f();
        let (w, h) = f.dimensions();
        let channels = SpecificChannels::rgb(|p: Vec2<usize>| {
            let c = f.get_pixel(p.x() as u32, p.y() as u32).0;
            (
                f16::from_f32(c[0]),
                f16::from_f32(c[1]),
                f16::from_f32(c[2]),
            )
        });
        let image = Image::from_channels((w as usize, h as usize), channels);
        let mut bytes = std::io::Cursor::new(Vec::new());
        image.write().to_buffered(&mut bytes).unwrap();
        bytes.into_inner()
    }

    /// A TGA (no signature: its format comes from its name) with its origin at the
    /// bottom-left, the format's default, reads right side up; the same bytes under
    /// another name are refused with the file named.
    #[test]
    fn a_tga_with_its_origin_at_the_bottom_left_reads_right_side_up() {
        // 2×2, 24-bit, uncompressed true colour, descriptor 0 (origin bottom-left): the
        // file's first row is the picture's bottom (blue), its second the top (red).
        let mut tga = vec![0u8, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 2, 0, 24, 0];
        tga.extend_from_slice(&[255, 0, 0, 255, 0, 0]); // bottom row, BGR: blue
        tga.extend_from_slice(&[0, 0, 255, 0, 0, 255]); // top row, BGR: red
        let img = HeadImage::decode(&tga, Path::new("head_diffuse.tga")).unwrap();
        assert_eq!((img.width_px, img.height_px), (2, 2));
        assert_eq!(&img.rgba[0..4], &[255, 0, 0, 255], "row 0 is the top: red");
        assert_eq!(
            &img.rgba[8..12],
            &[0, 0, 255, 255],
            "row 1 is the bottom: blue"
        );
        let e = HeadImage::decode(&tga, Path::new("head_diffuse.dat")).unwrap_err();
        assert!(e.to_string().contains("head_diffuse.dat"), "{e}");
    }

    #[test]
    fn samples_texel_centres_exactly_and_interpolates_between() {
        // 2×1: left texel 0, right texel 1.
        let m = Mask::from_values(2, 1, vec![0.0, 1.0]).unwrap();
        assert_eq!(m.sample(0.25, 0.5), 0.0);
        assert_eq!(m.sample(0.75, 0.5), 1.0);
        assert!((m.sample(0.5, 0.5) - 0.5).abs() < 1e-6);
        assert_eq!(m.sample(-3.0, 0.5), 0.0, "clamped at the border");
    }

    #[test]
    fn v_is_up() {
        // 1×2: top row 1, bottom row 0 → v near 1 is bright.
        let m = Mask::from_values(1, 2, vec![1.0, 0.0]).unwrap();
        assert_eq!(m.sample(0.5, 0.75), 1.0);
        assert_eq!(m.sample(0.5, 0.25), 0.0);
    }

    #[test]
    fn a_header_bomb_is_refused_before_decoding() {
        // A valid PNG header declaring 20000×20000 pixels, and nothing else.
        let mut png = Vec::new();
        png.extend_from_slice(b"\x89PNG\r\n\x1a\n");
        let mut ihdr = Vec::new();
        ihdr.extend_from_slice(b"IHDR");
        ihdr.extend_from_slice(&20000u32.to_be_bytes());
        ihdr.extend_from_slice(&20000u32.to_be_bytes());
        ihdr.extend_from_slice(&[8, 0, 0, 0, 0]);
        png.extend_from_slice(&13u32.to_be_bytes());
        png.extend_from_slice(&ihdr);
        png.extend_from_slice(&crc32(&ihdr).to_be_bytes());
        for (kind, data) in [
            (&b"IDAT"[..], &b"\x78\x9c\x03\x00\x00\x00\x00\x01"[..]),
            (b"IEND", b""),
        ] {
            let mut chunk = kind.to_vec();
            chunk.extend_from_slice(data);
            png.extend_from_slice(&(data.len() as u32).to_be_bytes());
            png.extend_from_slice(&chunk);
            png.extend_from_slice(&crc32(&chunk).to_be_bytes());
        }
        assert!(png.len() < 100);
        let e = Mask::decode(&png, Path::new("bomb.png"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("bomb.png") && e.contains("20000×20000") && e.contains("16384"),
            "{e}"
        );
    }

    fn crc32(data: &[u8]) -> u32 {
        let mut c = 0xFFFF_FFFFu32;
        for &b in data {
            c ^= b as u32;
            for _ in 0..8 {
                c = if c & 1 != 0 {
                    0xEDB8_8320 ^ (c >> 1)
                } else {
                    c >> 1
                };
            }
        }
        !c
    }

    #[test]
    fn unreadable_image_names_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("broken.png");
        std::fs::write(&p, b"not a png").unwrap();
        let err = Mask::load(&p).unwrap_err().to_string();
        assert!(err.contains("broken.png"), "{err}");
    }
}
