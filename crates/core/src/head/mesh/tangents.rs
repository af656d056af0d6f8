//! Tangent frames from positions, normals and UVs (docs/models.md §6) with MikkTSpace.
//!
//! We use `bevy_mikktspace` (a safe, dependency-free Rust port of Mikkelsen's reference
//! code, byte-identical to it on x86), because MikkTSpace is what Blender, Substance,
//! xNormal and glTF viewers bake and read normal maps against: a normal map baked there
//! shows without seams here. It is Lengyel's per-triangle tangent (docs/models.md §6) averaged
//! over vertices with angle weights, split where UV charts or mirroring disagree.
//!
//! MikkTSpace gives a tangent per triangle corner. Where two corners of one vertex get
//! different frames (a mirrored UV island meeting its original, a hard UV seam), the
//! vertex is duplicated so that each triangle keeps its own frame.

use std::collections::HashMap;

use bevy_mikktspace::{Geometry, TangentSpace};
use glam::{Vec2, Vec3, Vec4};

/// Tangents for every vertex, and the vertices that had to be duplicated.
#[derive(Clone, Debug)]
pub struct TangentFrames {
    /// One tangent per vertex of the input followed by one per duplicate: xyz unit,
    /// orthogonal to the normal, w = ±1 (bitangent = w · normal × tangent).
    pub tangents: Vec<Vec4>,
    /// For each duplicate vertex (appended after the input's), the vertex it copies.
    pub duplicated_from: Vec<u32>,
    /// The triangle list with corners re-pointed at duplicates where needed.
    pub indices: Vec<u32>,
}

/// One piece of the mesh as MikkTSpace sees it: the triangles `faces` (indices into
/// `indices` / 3, in the mesh's order), their corners' frames written to `out`.
struct Corners<'a> {
    positions: &'a [Vec3],
    normals: &'a [Vec3],
    uvs: &'a [Vec2],
    indices: &'a [u32],
    faces: &'a [u32],
    out: Vec<Option<Vec4>>,
}

impl Corners<'_> {
    fn vertex(&self, face: usize, vert: usize) -> usize {
        self.indices[self.faces[face] as usize * 3 + vert] as usize
    }
}

impl Geometry for Corners<'_> {
    fn num_faces(&self) -> usize {
        self.faces.len()
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.positions[self.vertex(face, vert)].to_array()
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        self.normals[self.vertex(face, vert)].to_array()
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        self.uvs[self.vertex(face, vert)].to_array()
    }

    fn set_tangent(&mut self, tangent_space: Option<TangentSpace>, face: usize, vert: usize) {
        self.out[face * 3 + vert] = tangent_space.map(|t| Vec4::from_array(t.tangent_encoded()));
    }
}

/// Triangles in one piece of the mesh that MikkTSpace runs on by itself, the pieces side
/// by side. A fixed count (not the thread count): the frames are the same on any machine.
const PIECE_TRIANGLES: usize = 1 << 15;

/// MikkTSpace's frame of every triangle corner (`None` where it gives none), the mesh cut
/// into pieces of [`PIECE_TRIANGLES`] that run in parallel. A corner's frame depends only
/// on the triangles around its vertex (MikkTSpace averages over the vertex's fan, welding
/// vertices of one position), so each piece runs with its triangles and every triangle
/// that touches one of their positions, in the mesh's order, and keeps its own corners:
/// the frames are those of one run over the whole mesh (tested).
fn corner_frames(
    positions: &[Vec3],
    normals: &[Vec3],
    uvs: &[Vec2],
    indices: &[u32],
) -> Vec<Option<Vec4>> {
    corner_frames_in(positions, normals, uvs, indices, PIECE_TRIANGLES)
}

fn corner_frames_in(
    positions: &[Vec3],
    normals: &[Vec3],
    uvs: &[Vec2],
    indices: &[u32],
    piece_triangles: usize,
) -> Vec<Option<Vec4>> {
    use rayon::prelude::*;
    let triangles = indices.len() / 3;
    let run = |faces: &[u32]| {
        let mut corners = Corners {
            positions,
            normals,
            uvs,
            indices,
            faces,
            out: vec![None; faces.len() * 3],
        };
        // The only error is "too many faces for the reference code's int indices"; the
        // caller's fallback frames then cover every corner.
        let _ = bevy_mikktspace::generate_tangents(&mut corners);
        corners.out
    };
    if triangles <= piece_triangles {
        let all: Vec<u32> = (0..triangles as u32).collect();
        return run(&all);
    }
    // Vertices of one position are one key (MikkTSpace welds them); each key's triangles.
    let mut key_of = HashMap::with_capacity(positions.len());
    let keys: Vec<u32> = positions
        .iter()
        .map(|p| {
            let bits = (*p + Vec3::ZERO).to_array().map(f32::to_bits);
            let next = key_of.len() as u32;
            *key_of.entry(bits).or_insert(next)
        })
        .collect();
    let mut start = vec![0u32; key_of.len() + 1];
    for &v in indices {
        start[keys[v as usize] as usize + 1] += 1;
    }
    for k in 1..start.len() {
        start[k] += start[k - 1];
    }
    let mut fill = start.clone();
    let mut around = vec![0u32; indices.len()];
    for (corner, &v) in indices.iter().enumerate() {
        let k = keys[v as usize] as usize;
        around[fill[k] as usize] = (corner / 3) as u32;
        fill[k] += 1;
    }
    let pieces: Vec<Vec<Option<Vec4>>> = (0..triangles.div_ceil(piece_triangles))
        .into_par_iter()
        .map(|piece| {
            let (first, end) = (
                piece * piece_triangles,
                ((piece + 1) * piece_triangles).min(triangles),
            );
            let mut outside: Vec<u32> = indices[first * 3..end * 3]
                .iter()
                .flat_map(|&v| {
                    let k = keys[v as usize] as usize;
                    around[start[k] as usize..start[k + 1] as usize]
                        .iter()
                        .copied()
                })
                .filter(|&t| (t as usize) < first || (t as usize) >= end)
                .collect();
            outside.sort_unstable();
            outside.dedup();
            let split = outside.partition_point(|&t| (t as usize) < first);
            let faces: Vec<u32> = outside[..split]
                .iter()
                .copied()
                .chain(first as u32..end as u32)
                .chain(outside[split..].iter().copied())
                .collect();
            let out = run(&faces);
            out[split * 3..(split + end - first) * 3].to_vec()
        })
        .collect();
    pieces.concat()
}

/// MikkTSpace tangents for a cleaned mesh (indices in range). Corners MikkTSpace leaves
/// without a frame (isolated triangles with degenerate UVs) get an arbitrary frame
/// orthogonal to the normal, so that the result is always finite.
pub fn mikktspace(
    positions: &[Vec3],
    normals: &[Vec3],
    uvs: &[Vec2],
    indices: &[u32],
) -> TangentFrames {
    let frames = corner_frames(positions, normals, uvs, indices);

    let mut tangents: Vec<Option<Vec4>> = vec![None; positions.len()];
    let mut duplicated_from = Vec::new();
    let mut out_indices = indices.to_vec();
    // (vertex, quantised frame) → vertex carrying that frame.
    let mut variants: HashMap<(u32, [i32; 4]), u32> = HashMap::new();
    for (corner, &v) in indices.iter().enumerate() {
        let n = normals[v as usize];
        let t = match frames[corner] {
            Some(t) if t.is_finite() && t.truncate().length_squared() > 0.0 => orthonormalise(t, n),
            _ => any_tangent(n),
        };
        let key = (v, quantise(t));
        if let Some(&existing) = variants.get(&key) {
            out_indices[corner] = existing;
            continue;
        }
        let target = if tangents[v as usize].is_none() {
            tangents[v as usize] = Some(t);
            v
        } else {
            duplicated_from.push(v);
            tangents.push(Some(t));
            (tangents.len() - 1) as u32
        };
        variants.insert(key, target);
        out_indices[corner] = target;
    }
    TangentFrames {
        tangents: tangents
            .into_iter()
            .enumerate()
            .map(|(i, t)| {
                t.unwrap_or_else(|| any_tangent(normals.get(i).copied().unwrap_or(Vec3::Z)))
            })
            .collect(),
        duplicated_from,
        indices: out_indices,
    }
}

/// Makes `t.xyz` a unit vector orthogonal to `normal` (Gram–Schmidt) and `t.w` exactly
/// ±1. A tangent parallel to the normal is replaced by an arbitrary orthogonal one.
pub fn orthonormalise(t: Vec4, normal: Vec3) -> Vec4 {
    let w = if t.w < 0.0 { -1.0 } else { 1.0 };
    let xyz = t.truncate();
    match (xyz - normal * normal.dot(xyz)).try_normalize() {
        Some(xyz) => xyz.extend(w),
        None => any_tangent(normal).truncate().extend(w),
    }
}

fn any_tangent(normal: Vec3) -> Vec4 {
    normal.any_orthonormal_vector().extend(1.0)
}

/// Frames closer than ~1e-3 count as the same (MikkTSpace gives one vertex bit-identical
/// frames in every corner of one smooth group; only real splits differ by much more).
fn quantise(t: Vec4) -> [i32; 4] {
    (t * 1024.0).round().to_array().map(|x| x as i32)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::head::mesh::test_util::{assert_close, assert_vec_close};

    /// Bitangent as the shader rebuilds it.
    fn bitangent(n: Vec3, t: Vec4) -> Vec3 {
        t.w * n.cross(t.truncate())
    }

    #[test]
    fn a_plane_with_u_along_x_and_v_along_y_has_the_standard_frame() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
        let uv = [Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y];
        let f = mikktspace(&p, &[Vec3::Z; 4], &uv, &[0, 1, 2, 0, 2, 3]);
        assert!(f.duplicated_from.is_empty());
        for t in &f.tangents {
            assert_vec_close(t.truncate(), Vec3::X, 1e-6, "tangent");
            assert_close(t.w, 1.0, 0.0, "w");
            assert_vec_close(bitangent(Vec3::Z, *t), Vec3::Y, 1e-6, "bitangent");
        }
    }

    #[test]
    fn mirrored_uvs_flip_the_handedness_and_split_the_shared_vertices() {
        // Two quads side by side in x ∈ [0,2]; the right one's UVs mirror the left's
        // (u runs back from 1 to 0), as for a symmetric face sharing one UV island.
        let p = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(2.0, 1.0, 0.0),
        ];
        let uv = [
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(0.0, 0.0),
            Vec2::new(0.0, 1.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(0.0, 1.0),
        ];
        let idx = [0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4];
        let f = mikktspace(&p, &[Vec3::Z; 6], &uv, &idx);
        // The middle column (vertices 1 and 4) is shared by both halves and must split.
        assert_eq!(f.duplicated_from.len(), 2, "{:?}", f.duplicated_from);
        for (tri, t) in f.indices.chunks_exact(3).enumerate() {
            for &v in t {
                let tan = f.tangents[v as usize];
                assert_close(tan.truncate().dot(Vec3::Z), 0.0, 1e-6, "t ⟂ n");
                assert_close(tan.truncate().length(), 1.0, 1e-6, "|t|");
                // +u runs along +x on the left, along −x on the right; +v along +y on both.
                let expected_t = if tri < 2 { Vec3::X } else { Vec3::NEG_X };
                assert_vec_close(tan.truncate(), expected_t, 1e-5, "tangent direction");
                assert_close(tan.w, if tri < 2 { 1.0 } else { -1.0 }, 0.0, "handedness");
                assert_vec_close(bitangent(Vec3::Z, tan), Vec3::Y, 1e-5, "bitangent along +v");
            }
        }
    }

    #[test]
    fn pieces_run_side_by_side_give_the_frames_of_one_run() {
        // The default head (17.7k triangles, UV seams, mirrored islands) in pieces of 1000
        // triangles, and the shape test heads' seams: every corner's frame bit for bit.
        let head = crate::head::default::default_head();
        let (p, n, uv, ix) = (head.positions(), head.normals(), head.uvs(), head.indices());
        let whole = corner_frames_in(p, n, uv, ix, usize::MAX);
        let pieces = corner_frames_in(p, n, uv, ix, 1000);
        assert_eq!(whole.len(), ix.len());
        assert!(whole.iter().filter(|f| f.is_some()).count() > ix.len() * 99 / 100);
        let differ = whole.iter().zip(&pieces).filter(|(a, b)| a != b).count();
        assert_eq!(differ, 0, "{differ} of {} corners differ", whole.len());
    }

    #[test]
    fn orthonormalise_removes_the_normal_component() {
        let t = orthonormalise(Vec4::new(1.0, 0.0, 1.0, -0.3), Vec3::Z);
        assert_eq!(t, Vec4::new(1.0, 0.0, 0.0, -1.0));
        let t = orthonormalise(Vec4::new(0.0, 0.0, 1.0, 1.0), Vec3::Z);
        assert_close(t.truncate().dot(Vec3::Z), 0.0, 1e-6, "fallback ⟂ n");
    }
}
