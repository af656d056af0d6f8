//! The default head and the skin patch, as the engine uses them.
//!
//! - [`default_head`]: the shipped mesh `assets/meshes/default-head.glb`, built into the
//!   binary (≈ 4.6 MB; a few tens of ms to read, `benches/head.rs` in the app). It is made
//!   by `agesim gen-assets` from a signed distance function; that generator (and the mask
//!   painter and the CPU preview used for the pictures) lives in the app's `assets`
//!   module, not here: the engine only reads the result.
//! - [`skin_patch`]: a flat 5 cm square for close-ups of micro-relief, generated here in a
//!   few ms (its exact tangent frame is cheap).
//!
//! # Units and axes
//! Metres (glTF convention), +Y up, the face looking along +Z, the subject's left on
//! +X. Chin to crown ≈ 0.23 m; the open neck ends at y = −0.17 m.
//!
//! # UV layout of the default head
//! - u goes around the head: u = 0.5 + φ/2π with φ the longitude from the front
//!   (+Z), positive toward +X. The front of the face is at u = 0.5, the seam at the back
//!   (u = 0 ≡ 1). Looking at the UV image is like looking at the face from the front
//!   (the subject's left, +X, is on the right of the image).
//! - v goes up along each profile, proportional to arc length: v = 0 is the open edge of
//!   the neck, v = 1 the crown.
//! - Regions (measured on this mesh; the tests of the app's `assets` module
//!   check the key ones, `assets/docs/uv-layout.png` shows them):
//!   - face rectangle: u ∈ [0.36, 0.64], v ∈ [0.25, 0.78] — at u = 0.5: under the chin
//!     v ≈ 0.20–0.26, chin front ≈ 0.30, lips ≈ 0.37–0.43, base of the nose ≈ 0.47, nose
//!     tip ≈ 0.50, eyes ≈ 0.555 (centres at u ≈ 0.446 / 0.554), brows ≈ 0.60, front
//!     hairline ≈ 0.78;
//!   - forehead: u ∈ [0.40, 0.60], v ∈ [0.61, 0.77] (the example fibres of docs/models.md §3,
//!     u 0.42–0.56, v 0.64–0.73, lie on it);
//!   - ears: around u ≈ 0.25 and 0.75, v ≈ 0.47–0.60;
//!   - scalp: v > 0.78 at the front, down to v ≈ 0.31 at the nape (u = 0 ≡ 1); exactly
//!     the white of `assets/masks/hair-outer.png`;
//!   - neck: v < 0.24 in front (u ∈ [0.35, 0.65]), up to the hairline at the back.
//!

use std::path::Path;

use glam::{Vec2, Vec3, Vec4};

use crate::error::Error;
use crate::mesh::{Mesh, MeshPart, MeshReport, RawMesh, TangentSource, gltf};

/// Edge length of the skin patch, metres (5 cm, like [P]'s close-up figures).
pub const SKIN_PATCH_SIZE_M: f32 = 0.05;
/// Quads per side of the skin patch (2 triangles each).
pub const SKIN_PATCH_QUADS: u32 = 256;

/// Where `agesim gen-assets` writes the generated default head as GLB
/// ([`gltf::write_glb`]), relative to the assets folder.
pub const DEFAULT_HEAD_ASSET: &str = "meshes/default-head.glb";

/// The shipped default head, `assets/meshes/default-head.glb` built into the binary: what
/// `agesim gen-assets` wrote the last time the assets were regenerated (≈ 4.6 MB:
/// positions, normals, tangents, UVs as `f32`, `u32` indices). The app's `assets`
/// tests check that it still matches a fresh generation.
pub const DEFAULT_HEAD_GLB: &[u8] = include_bytes!("../../../assets/meshes/default-head.glb");

/// The default head (see the module docs): about 128 000 triangles, closed except at
/// the neck, normals outward, UVs in [0,1] with the layout documented above, tangents
/// from MikkTSpace.
///
/// Read from the shipped file [`DEFAULT_HEAD_GLB`] ([`shipped_default_head`], a few ms).
/// Should the built-in file ever be unreadable (a bug the tests catch), a single
/// triangle stands in: a visible wrong picture beats a panic in the editor.
pub fn default_head() -> Mesh {
    shipped_default_head().unwrap_or_else(|_| Mesh::single_triangle())
}

/// Reads the default head from [`DEFAULT_HEAD_GLB`]. Its parts and [`MeshReport`] are
/// those of the generation the file stores (normals generated, tangents from
/// MikkTSpace), not those of reading a file. Equal to the app's generator up to a
/// few ulps of rounding in the file round trip (tested: positions to 1 µm, UVs to 1e-6,
/// normals and tangents to 1e-5 rad, indices exactly).
pub fn shipped_default_head() -> Result<Mesh, Error> {
    // The report is the load's own (normals and tangents from the file), exactly what
    // loading `assets/meshes/default-head.glb` from disk reports: one provenance.
    let name = format!("{DEFAULT_HEAD_ASSET} (built in)");
    let raw = gltf::load_bytes(DEFAULT_HEAD_GLB, Path::new(&name))?;
    Mesh::build(raw, &name)
}

/// A flat square of skin, [`SKIN_PATCH_SIZE_M`] wide, in the XY plane facing +Z and
/// centred on the origin, UVs covering [0,1]² (u along +X, v along +Y), finely
/// subdivided ([`SKIN_PATCH_QUADS`]² quads) for close-ups of micro-relief and for
/// displacement as geometry (docs/models.md §10).
///
/// Its tangent frame is exact: UVs are an affine map of the plane, so every vertex has
/// tangent +X, bitangent +Y, w = +1 (docs/models.md §5), which is what MikkTSpace computes there
/// (tested) at a tenth of a percent of the cost. [`MeshReport::tangent_source`] says
/// [`TangentSource::Analytic`]. A few ms: fine at start-up.
pub fn skin_patch() -> Mesh {
    let mut raw = skin_patch_raw();
    raw.tangents = Some(vec![Vec4::new(1.0, 0.0, 0.0, 1.0); raw.positions.len()]);
    match Mesh::build(raw, "skin patch") {
        Ok(mesh) => {
            let parts = mesh.parts().to_vec();
            let report = MeshReport {
                tangent_source: Some(TangentSource::Analytic),
                ..mesh.report().clone()
            };
            mesh.with_provenance(parts, report)
        }
        // Unreachable for this fixed grid (tested); never panic in library code.
        Err(_) => Mesh::single_triangle(),
    }
}

/// The skin patch's grid before [`Mesh::build`]: positions, +Z normals, UVs, indices, no
/// tangents (building it as is gives MikkTSpace tangents, the slow path).
pub fn skin_patch_raw() -> RawMesh {
    let n = SKIN_PATCH_QUADS as usize;
    let mut positions = Vec::with_capacity((n + 1) * (n + 1));
    let mut uvs = Vec::with_capacity(positions.capacity());
    for j in 0..=n {
        for i in 0..=n {
            let uv = Vec2::new(i as f32 / n as f32, j as f32 / n as f32);
            uvs.push(uv);
            positions.push(((uv - 0.5) * SKIN_PATCH_SIZE_M).extend(0.0));
        }
    }
    let at = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut indices = Vec::with_capacity(n * n * 6);
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            indices.extend_from_slice(&[a, b, c, a, c, d]);
        }
    }
    let triangle_count = (indices.len() / 3) as u32;
    RawMesh {
        normals: Some(vec![Vec3::Z; positions.len()]),
        positions,
        uvs: Some(uvs),
        indices,
        parts: vec![MeshPart {
            name: "skin patch (generated)".to_owned(),
            first_triangle: 0,
            triangle_count,
        }],
        ..RawMesh::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Angle between two directions, radians (robust near 0).
    fn angle(a: Vec3, b: Vec3) -> f32 {
        a.cross(b).length().atan2(a.dot(b))
    }

    #[test]
    fn the_default_head_is_the_shipped_file() {
        let m = default_head();
        assert_eq!(m.report().tangent_source, Some(TangentSource::File));
        assert!(m.vertex_count() > 50_000, "{}", m.vertex_count());
        assert!(shipped_default_head().is_ok());
    }

    #[test]
    fn the_skin_patch_analytic_tangents_are_mikktspace_s() {
        let fast = skin_patch();
        let mikk = Mesh::build(skin_patch_raw(), "skin patch").unwrap();
        assert_eq!(
            mikk.report().tangent_source,
            Some(TangentSource::MikkTSpace)
        );
        assert_eq!(fast.report().tangent_source, Some(TangentSource::Analytic));
        assert_eq!(fast.vertex_count(), mikk.vertex_count());
        assert_eq!(fast.indices(), mikk.indices());
        let mut worst = 0.0f32;
        for (a, b) in fast.tangents().iter().zip(mikk.tangents()) {
            assert_eq!(a.w, b.w);
            worst = worst.max(angle(a.truncate(), b.truncate()));
        }
        assert!(worst <= 1e-5, "tangents differ by {worst} rad");
    }

    #[test]
    fn the_skin_patch_is_flat_5cm_and_fine() {
        let m = skin_patch();
        let size = m.bounds().size();
        assert!((size.x - 0.05).abs() < 1e-6 && (size.y - 0.05).abs() < 1e-6 && size.z == 0.0);
        assert_eq!(m.triangle_count(), 2 * 256 * 256);
        assert!(m.normals().iter().all(|n| *n == Vec3::Z));
        assert!(m.report().warnings.is_empty());
    }
}
