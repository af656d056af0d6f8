//! Small scalar helpers shared by the layers.

/// Hermite smoothstep: 0 at or below `lo`, 1 at or above `hi`, `3t² − 2t³` between.
pub fn smoothstep(lo: f32, hi: f32, x: f32) -> f32 {
    let t = ((x - lo) / (hi - lo)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}
