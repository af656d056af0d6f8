//! Small scalar helpers shared by the layers.

/// Hermite smoothstep: 0 at or below `lo`, 1 at or above `hi`, `3t² − 2t³` between.
pub fn smoothstep(lo: f32, hi: f32, x: f32) -> f32 {
    smooth01((x - lo) / (hi - lo))
}

/// smoothstep(0, 1, x).
pub fn smooth01(x: f32) -> f32 {
    let x = x.clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}
