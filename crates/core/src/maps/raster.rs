//! The UV rasteriser: the texels of a map a UV triangle covers, with barycentric weights
//! and a guard band (docs/models.md §1 pixel centres). Every per-texel bake goes through it.

use glam::Vec2;

/// How far below 0 a guard texel's barycentric weight may go (1: one triangle's width
/// beyond the edge).
const MAX_GUARD_WEIGHT: f32 = 1.0;

/// Visits the texels of a `size`² map (docs/models.md §1: rows from the top, v up) whose
/// centres lie in the UV triangle `uv` or within `guard` pixels of it (and no farther than
/// its own width beyond an edge: a sliver's guard band is thinner): `visit(x, y,
/// barycentric weights (extrapolated outside), distance outside in pixels)`. A triangle
/// with no UV area visits nothing.
pub fn raster_uv(
    uv: [Vec2; 3],
    size: u32,
    guard: f32,
    mut visit: impl FnMut(usize, usize, [f32; 3], f32),
) {
    let s = size as f32;
    // Continuous pixel coordinates: texel (x, y) has its centre at (x + ½, y + ½).
    let px = |uv: Vec2| Vec2::new(uv.x * s, (1.0 - uv.y) * s);
    let (pa, pb, pc) = (px(uv[0]), px(uv[1]), px(uv[2]));
    let area = (pb - pa).perp_dot(pc - pa);
    if area.abs() < 1e-12 || !area.is_finite() {
        return;
    }
    let lo = (pa.min(pb).min(pc) - guard).floor().max(Vec2::ZERO);
    let hi = (pa.max(pb).max(pc) + guard).ceil().min(Vec2::splat(s));
    let edge_len = [(pc - pb).length(), (pa - pc).length(), (pb - pa).length()];
    for y in lo.y as usize..hi.y as usize {
        for x in lo.x as usize..hi.x as usize {
            let p = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            let w0 = (pc - pb).perp_dot(p - pb) / area;
            let w1 = (pa - pc).perp_dot(p - pc) / area;
            let w2 = 1.0 - w0 - w1;
            // Distance outside the triangle, pixels (0 inside).
            let outside = [w0, w1, w2]
                .iter()
                .zip(edge_len)
                .map(|(w, len)| (-w).max(0.0) * area.abs() / len.max(1e-12))
                .fold(0.0f32, f32::max);
            // Beyond a sliver's edge the weights blow up (a point far off the surface):
            // only a guard texel whose weights stay near the triangle is visited.
            let sane = outside == 0.0 || w0.min(w1).min(w2) >= -MAX_GUARD_WEIGHT;
            if outside <= guard && sane {
                visit(x, y, [w0, w1, w2], outside);
            }
        }
    }
}
