//! A tiny built-in 5×7 bitmap font for labels on rendered pictures (`render --compare`),
//! so the binary needs no font file or text-rendering dependency.

/// Glyph rows, top to bottom, 5 bits each (bit 4 = leftmost column).
fn glyph(c: char) -> [u8; 7] {
    match c {
        '0' => [0x0e, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0e],
        '1' => [0x04, 0x0c, 0x04, 0x04, 0x04, 0x04, 0x0e],
        '2' => [0x0e, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1f],
        '3' => [0x1f, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0e],
        '4' => [0x02, 0x06, 0x0a, 0x12, 0x1f, 0x02, 0x02],
        '5' => [0x1f, 0x10, 0x1e, 0x01, 0x01, 0x11, 0x0e],
        '6' => [0x06, 0x08, 0x10, 0x1e, 0x11, 0x11, 0x0e],
        '7' => [0x1f, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08],
        '8' => [0x0e, 0x11, 0x11, 0x0e, 0x11, 0x11, 0x0e],
        '9' => [0x0e, 0x11, 0x11, 0x0f, 0x01, 0x02, 0x0c],
        '.' => [0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x0c],
        '=' => [0x00, 0x00, 0x1f, 0x00, 0x1f, 0x00, 0x00],
        'T' => [0x1f, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04],
        'Y' => [0x11, 0x11, 0x0a, 0x04, 0x04, 0x04, 0x04],
        '-' => [0x00, 0x00, 0x00, 0x1f, 0x00, 0x00, 0x00],
        _ => [0; 7],
    }
}

/// Draws `text` with its top-left corner at (x, y), each font pixel `scale`² image
/// pixels, with a one-pixel dark outline so it reads on skin and on the background.
/// Characters outside the font draw as spaces; pixels outside the image are skipped.
pub fn draw_text(
    img: &mut image::RgbaImage,
    x: u32,
    y: u32,
    scale: u32,
    text: &str,
    rgba: [u8; 4],
) {
    let scale = scale.max(1);
    let mut put = |px: i64, py: i64, c: [u8; 4]| {
        if px >= 0 && py >= 0 && (px as u32) < img.width() && (py as u32) < img.height() {
            img.put_pixel(px as u32, py as u32, image::Rgba(c));
        }
    };
    for pass in 0..2 {
        for (i, c) in text.chars().enumerate() {
            let ox = i64::from(x) + i as i64 * 6 * i64::from(scale);
            for (row, bits) in glyph(c).iter().enumerate() {
                for col in 0..5 {
                    if bits & (0x10 >> col) == 0 {
                        continue;
                    }
                    for sy in 0..i64::from(scale) {
                        for sx in 0..i64::from(scale) {
                            let px = ox + col * i64::from(scale) + sx;
                            let py = i64::from(y) + row as i64 * i64::from(scale) + sy;
                            if pass == 0 {
                                for (dx, dy) in [(-1, 0), (1, 0), (0, -1), (0, 1)] {
                                    put(px + dx, py + dy, [0, 0, 0, 255]);
                                }
                            } else {
                                put(px, py, rgba);
                            }
                        }
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_inside_the_image_only() {
        let mut img = image::RgbaImage::new(40, 12);
        draw_text(&mut img, 1, 1, 1, "T=0.5", [255, 255, 255, 255]);
        let white = img.pixels().filter(|p| p.0 == [255, 255, 255, 255]).count();
        assert!(white > 20, "{white}");
        // Off-image text does not panic.
        draw_text(&mut img, 35, 10, 2, "88", [255, 0, 0, 255]);
    }
}
