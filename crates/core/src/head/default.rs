//! The default head and the skin patch, as the engine uses them.
//!
//! - [`default_head`]: the shipped mesh `assets/meshes/default-head.glb`, built into the
//!   binary (≈ 0.9 MB; a few ms to read, `benches/head.rs` in the app): the Lee Perry-Smith
//!   scan ("Infinite, 3D Head Scan by Lee Perry-Smith, licensed under CC BY 3.0, based on a
//!   work at triplegangers.com"), converted by `agesim gen-assets` (the app's `assets`
//!   module: the engine only reads the result), with the scan's colour and normal maps
//!   embedded ([`default_head_textures`]). It is also the template every other head
//!   is fitted to (`fit::template`).
//! - [`skin_patch`]: a flat 5 cm square for close-ups of micro-relief, generated here in a
//!   few ms (its exact tangent frame is cheap).
//!
//! # Units and axes
//! Metres (glTF convention), +Y up, the face looking along +Z, the subject's left on
//! +X; x = 0 the face's midline, y = 0 the outer eye corners' height, z = 0 the left
//! tragion. Crown at y ≈ 0.12 m, chin at ≈ −0.11 m, the neck cut at −0.18 m.
//!
//! # UV layout of the default head
//! The scan's own single chart (docs/models.md §7, `assets/README.md` tabulates it): the
//! face in the middle of the square and magnified (outer eye corners at u ≈ 0.40 / 0.60,
//! v ≈ 0.70; mouth corners at v ≈ 0.535; forehead v ≈ 0.76–0.86), the scalp above, the ears
//! at the sides (u ≈ 0.29 / 0.72), the back of the head split down the left and right
//! edges, the neck below the chin (v ≈ 0.2–0.38 in front). Two parts: the skin, and the
//! insides of the eye sockets behind the closed lids (the discs in the top corners), which
//! is not skin.

use std::path::Path;

use glam::{Vec2, Vec3, Vec4};

use crate::base::error::Error;
use crate::head::mesh::{Mesh, MeshPart, MeshReport, RawMesh, TangentSource, gltf};

/// Edge length of the skin patch, metres (5 cm, like [P]'s close-up figures).
pub const SKIN_PATCH_SIZE_M: f32 = 0.05;
/// Quads per side of the skin patch (2 triangles each).
pub const SKIN_PATCH_QUADS: u32 = 256;

/// Where `agesim gen-assets` writes the converted default head as GLB
/// ([`gltf::write_glb`]), relative to the assets folder.
pub const DEFAULT_HEAD_ASSET: &str = "meshes/default-head.glb";

/// Where `agesim gen-assets` writes the default head's landmarks (metres), relative to the
/// assets folder: the template's ([`crate::head::fit::TEMPLATE_LANDMARKS_JSON`]).
pub const DEFAULT_HEAD_LANDMARKS_ASSET: &str = "meshes/default-head.landmarks.json";

/// The shipped default head, `assets/meshes/default-head.glb` built into the binary: what
/// `agesim gen-assets` wrote the last time the assets were regenerated (≈ 0.9 MB:
/// positions, normals, tangents, UVs as `f32`, `u32` indices, the scan's two JPEG maps).
/// The app's `assets` tests check that it still matches a fresh conversion.
pub const DEFAULT_HEAD_GLB: &[u8] = include_bytes!("../../../../assets/meshes/default-head.glb");

/// The default head (see the module docs): 16 186 triangles, normals outward, UVs in
/// [0,1] with the layout documented above, tangents from MikkTSpace.
///
/// Read from the shipped file [`DEFAULT_HEAD_GLB`] ([`shipped_default_head`], a few ms).
/// Should the built-in file ever be unreadable (a bug the tests catch), a single
/// triangle stands in: a visible wrong picture beats a panic in the editor.
pub fn default_head() -> Mesh {
    shipped_default_head().unwrap_or_else(|_| Mesh::single_triangle())
}

/// Reads the default head from [`DEFAULT_HEAD_GLB`]. Equal to the app's conversion up to
/// a few ulps of rounding in the file round trip (tested corner by corner: positions to
/// 1 µm, UVs to 1e-6, normals and tangents to 1e-5 rad).
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

/// The built-in default head's own colour and normal maps (the scan's, embedded in
/// [`DEFAULT_HEAD_GLB`]), decoded once.
pub fn default_head_textures() -> std::sync::Arc<crate::head::mesh::textures::MeshTextures> {
    static TEXTURES: std::sync::OnceLock<
        std::sync::Arc<crate::head::mesh::textures::MeshTextures>,
    > = std::sync::OnceLock::new();
    TEXTURES
        .get_or_init(|| {
            let name = format!("{} (built in)", DEFAULT_HEAD_ASSET);
            // Checked by the tests; unreadable, the head is drawn in the skin colour.
            std::sync::Arc::new(
                crate::head::mesh::textures::load_glb_bytes(DEFAULT_HEAD_GLB, Path::new(&name))
                    .unwrap_or_default(),
            )
        })
        .clone()
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
        // The converted scan: about 8 500 vertices, in metres, with its maps embedded.
        assert!(m.vertex_count() > 8_000, "{}", m.vertex_count());
        assert!(
            (0.28..0.32).contains(&m.bounds().size().y),
            "{:?}",
            m.bounds()
        );
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
