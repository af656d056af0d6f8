//! The hair instance's packed members: the direction as an octahedral pair of snorm16 (the
//! hair shader's `oct_decode`, shaders/common.wgsl, reads it), UV and length as unorm16.

use glam::Vec3;

/// Octahedral encoding of a unit vector into two snorm16 values.
pub fn oct_encode(n: Vec3) -> [i16; 2] {
    let l1 = n.x.abs() + n.y.abs() + n.z.abs();
    if l1 == 0.0 {
        return [0, 0]; // decodes to +z
    }
    let n = n / l1;
    let (x, y) = if n.z >= 0.0 {
        (n.x, n.y)
    } else {
        (
            (1.0 - n.y.abs()) * n.x.signum(),
            (1.0 - n.x.abs()) * n.y.signum(),
        )
    };
    [snorm16(x), snorm16(y)]
}

/// The inverse of [`oct_encode`], as the hair shader decodes a snorm16 pair.
pub fn oct_decode(e: [i16; 2]) -> Vec3 {
    let (x, y) = (
        (e[0] as f32 / 32767.0).max(-1.0),
        (e[1] as f32 / 32767.0).max(-1.0),
    );
    let z = 1.0 - x.abs() - y.abs();
    let (x, y) = if z < 0.0 {
        ((1.0 - y.abs()) * x.signum(), (1.0 - x.abs()) * y.signum())
    } else {
        (x, y)
    };
    Vec3::new(x, y, z).normalize()
}

fn snorm16(v: f32) -> i16 {
    (v.clamp(-1.0, 1.0) * 32767.0).round() as i16
}

pub(super) fn unorm16(v: f32) -> u16 {
    let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
    (v * 65535.0).round() as u16
}
