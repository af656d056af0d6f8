//! Which way the skin faces (docs/models.md §13 "Only skin that faces out moves along its
//! normal").

use glam::Vec3;

use crate::base::math::smoothstep;

/// The middle of the skull in the face frame ([`crate::head::frame::Regions::relative`]): behind the eyes,
/// between the ears.
pub const SKULL_CENTRE: Vec3 = Vec3::new(0.0, 0.3, -1.3);

/// How much skin at `q` (face frame) whose normal is `normal` (the head's axes, as the
/// template's: up +y, forward +z) faces out of the head, 0–1: 1 from 0.2 of a right angle
/// out of the direction from [`SKULL_CENTRE`], 0 from 0.2 in. A move along the normal (a
/// deflation, a bulge, a roll) is made only as much as the skin faces out: the mouth's
/// inside, mapped to the lips' region, moved forward along its own normal, which points
/// back, and came through the lower lip at 80, read blind as "a red dot in the lower lip",
/// "a pinhole under the lip" (rounds 17–18).
pub fn facing_out(q: Vec3, normal: Vec3) -> f32 {
    smoothstep(
        -0.2,
        0.2,
        normal.dot((q - SKULL_CENTRE).normalize_or_zero()),
    )
}
