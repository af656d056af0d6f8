//! A small CPU rasteriser for looking at meshes without a GPU: orthographic camera,
//! z-buffer, per-pixel interpolated normals, Lambert shading with a key and a fill light.
//! Used by `agesim gen-assets` for the pictures in `assets/docs/` and by tests.

use glam::{Mat3, Vec2, Vec3};
use image::RgbImage;

use agesim_core::Mesh;

/// How to look at a mesh: turn it by `yaw_deg` around +Y (0 = the +Z side, the face,
/// toward the camera; 90 = the subject's left, +X, toward the camera) and tilt by
/// `pitch_deg` (positive = seen from above).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    pub yaw_deg: f32,
    pub pitch_deg: f32,
}

impl View {
    pub const FRONT: Self = Self {
        yaw_deg: 0.0,
        pitch_deg: 0.0,
    };
    pub const THREE_QUARTER: Self = Self {
        yaw_deg: 35.0,
        pitch_deg: 8.0,
    };
    pub const SIDE: Self = Self {
        yaw_deg: 90.0,
        pitch_deg: 0.0,
    };
    pub const BACK: Self = Self {
        yaw_deg: 180.0,
        pitch_deg: 10.0,
    };
}

/// Renders `mesh` into a `size_px²` image, the mesh's bounding sphere filling the frame.
/// `albedo(uv)` gives the surface colour (linear, 0–1) at a UV; use
/// `|_| Vec3::splat(0.8)` for plain clay.
pub fn render(mesh: &Mesh, view: View, size_px: u32, albedo: impl Fn(Vec2) -> Vec3) -> RgbImage {
    let size = size_px.max(1) as usize;
    let bounds = mesh.bounds();
    let centre = bounds.centre();
    let radius = (0.5 * bounds.size().length()).max(1e-12);
    // Camera frame: rotate the model, then look down −Z.
    let rot = Mat3::from_rotation_x(view.pitch_deg.to_radians())
        * Mat3::from_rotation_y(-view.yaw_deg.to_radians());
    let scale = 0.5 * size as f32 / (radius * 1.02);
    let project = |p: Vec3| {
        let q = rot * (p - centre);
        Vec3::new(
            0.5 * size as f32 + q.x * scale,
            0.5 * size as f32 - q.y * scale,
            q.z,
        )
    };
    let screen: Vec<Vec3> = mesh.positions().iter().map(|&p| project(p)).collect();
    let normals: Vec<Vec3> = mesh.normals().iter().map(|&n| rot * n).collect();
    let uvs = mesh.uvs();

    let mut depth = vec![f32::NEG_INFINITY; size * size];
    let mut colour = vec![Vec3::new(0.16, 0.17, 0.19); size * size];
    let key = Vec3::new(-0.45, 0.55, 0.7).normalize();
    let fill = Vec3::new(0.6, -0.1, 0.5).normalize();

    for tri in mesh.triangles() {
        let [a, b, c] = tri.map(|i| screen[i as usize]);
        let area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        // Screen y points down: front faces (counter-clockwise in the model) have area < 0.
        if area >= 0.0 {
            continue;
        }
        let min_x = a.x.min(b.x).min(c.x).floor().max(0.0) as usize;
        let max_x = (a.x.max(b.x).max(c.x).ceil() as usize).min(size - 1);
        let min_y = a.y.min(b.y).min(c.y).floor().max(0.0) as usize;
        let max_y = (a.y.max(b.y).max(c.y).ceil() as usize).min(size - 1);
        for y in min_y..=max_y {
            for x in min_x..=max_x {
                let (px, py) = (x as f32 + 0.5, y as f32 + 0.5);
                let w0 = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) / area;
                let w1 = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
                let w2 = 1.0 - w0 - w1;
                if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                    continue;
                }
                let z = w0 * a.z + w1 * b.z + w2 * c.z;
                let k = y * size + x;
                if z <= depth[k] {
                    continue;
                }
                depth[k] = z;
                let [ia, ib, ic] = tri.map(|i| i as usize);
                let n =
                    (w0 * normals[ia] + w1 * normals[ib] + w2 * normals[ic]).normalize_or_zero();
                let uv = w0 * uvs[ia] + w1 * uvs[ib] + w2 * uvs[ic];
                let light = 0.12 + 0.75 * n.dot(key).max(0.0) + 0.25 * n.dot(fill).max(0.0);
                colour[k] = albedo(uv) * light;
            }
        }
    }
    let mut img = RgbImage::new(size as u32, size as u32);
    for (pixel, c) in img.pixels_mut().zip(&colour) {
        // Linear → sRGB-ish display gamma.
        let s = c.clamp(Vec3::ZERO, Vec3::ONE).powf(1.0 / 2.2) * 255.0 + 0.5;
        pixel.0 = [s.x as u8, s.y as u8, s.z as u8];
    }
    img
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn a_patch_seen_from_the_front_fills_the_middle_and_its_back_is_culled() {
        let patch = agesim_core::head::default::skin_patch();
        let img = render(&patch, View::FRONT, 64, |_| Vec3::ONE);
        let bg = img.get_pixel(0, 0).0;
        let mid = img.get_pixel(32, 32).0;
        assert_ne!(mid, bg, "front face drawn");
        let back = render(
            &patch,
            View {
                yaw_deg: 180.0,
                pitch_deg: 0.0,
            },
            64,
            |_| Vec3::ONE,
        );
        assert_eq!(back.get_pixel(32, 32).0, bg, "back face culled");
    }
}
