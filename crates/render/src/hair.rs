//! The hair instance buffer's layout: `agesim_core::layers::hair::HairInstance` (32 bytes, docs/models.md
//! §9) read directly as per-instance vertex attributes, so uploads are one memcpy.

use agesim_core::layers::hair::AgeLevel;

/// Quads per hair ribbon (`SEGMENTS`, a pipeline constant of `shaders/hair.wgsl`).
pub(crate) const SEGMENTS: u32 = 4;
/// Quads per ribbon of a sparse frame (`HairShading::sparse`): drawn at a fraction of
/// the resolution, the curve needs fewer, and on a CPU adapter the pass's cost follows
/// its vertices.
pub(crate) const SPARSE_SEGMENTS: u32 = 2;

/// Vertices of one hair's triangle strip of `segments` quads.
pub(crate) const fn vertices_per_hair(segments: u32) -> u32 {
    2 * (segments + 1)
}

pub(crate) const INSTANCE_ATTRIBUTES: [wgpu::VertexAttribute; 6] = wgpu::vertex_attr_array![
    0 => Float32x3, // position
    1 => Float32,   // disappear_age
    2 => Snorm16x2, // direction_oct
    3 => Float32,   // graying_onset
    4 => Unorm16x2, // uv
    5 => Unorm16x2, // random, length factor
];

/// Stride of one instance, bytes.
pub(crate) const INSTANCE_STRIDE: u64 = 32;

/// `agesim_core::layers::hair::brows::BrowStrand` (48 bytes) as vertex attributes.
pub(crate) const BROW_ATTRIBUTES: [wgpu::VertexAttribute; 6] = wgpu::vertex_attr_array![
    0 => Float32x3, // root
    1 => Float32,   // gray
    2 => Float32x3, // middle
    3 => Float32,   // shade
    4 => Float32x3, // tip
    5 => Float32,   // coverage
];

/// Stride of one brow strand, bytes.
pub(crate) const BROW_STRIDE: u64 = 48;

/// count(t) from the cumulative table (the same rule as `HairInstances::count`: hairs
/// with a_k ≥ t), kept here so the renderer needs only the table, not the instances.
pub(crate) fn count_at(levels: &[AgeLevel], t: f32) -> u32 {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let k = levels.partition_point(|l| l.age >= t);
    if k == 0 { 0 } else { levels[k - 1].count }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A core struct of `size` bytes is exactly `stride` bytes of vertex attributes.
    fn assert_layout(size: usize, stride: u64, attributes: &[wgpu::VertexAttribute]) {
        assert_eq!(size as u64, stride);
        let end = attributes.iter().map(|a| a.offset + a.format.size()).max();
        assert_eq!(end, Some(stride));
    }

    #[test]
    fn instance_layout_matches_core() {
        assert_layout(
            std::mem::size_of::<agesim_core::layers::hair::HairInstance>(),
            INSTANCE_STRIDE,
            &INSTANCE_ATTRIBUTES,
        );
    }

    #[test]
    fn brow_layout_matches_core() {
        assert_layout(
            std::mem::size_of::<agesim_core::layers::hair::brows::BrowStrand>(),
            BROW_STRIDE,
            &BROW_ATTRIBUTES,
        );
    }

    #[test]
    fn count_follows_levels() {
        let levels = [
            AgeLevel {
                age: 1.0,
                count: 10,
            },
            AgeLevel {
                age: 0.5,
                count: 30,
            },
            AgeLevel {
                age: 0.2,
                count: 35,
            },
        ];
        assert_eq!(count_at(&levels, 0.0), 35);
        assert_eq!(count_at(&levels, 0.2), 35);
        assert_eq!(count_at(&levels, 0.3), 30);
        assert_eq!(count_at(&levels, 0.9), 10);
        assert_eq!(count_at(&levels, 1.0), 10);
        assert_eq!(count_at(&[], 0.5), 0);
    }
}
