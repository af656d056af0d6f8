//! Cleaning a raw mesh: the triangles kept (degenerate and non-finite ones dropped, each
//! with its warning), the vertices compacted to those used, the parts counted.

use super::*;

pub(super) fn bounds_of(positions: &[Vec3]) -> Aabb {
    Aabb::from_points(positions).unwrap_or(Aabb {
        min: Vec3::ZERO,
        max: Vec3::ZERO,
    })
}

pub(super) fn count_parts_without(
    parts: &[MeshPart],
    indices: &[u32],
    missing: impl Fn(u32) -> bool,
) -> usize {
    parts
        .iter()
        .filter(|p| {
            let first = p.first_triangle as usize * 3;
            let last = first + p.triangle_count as usize * 3;
            indices
                .get(first..last)
                .is_some_and(|ix| ix.iter().any(|&v| missing(v)))
        })
        .count()
}

/// Drops triangles with out-of-range indices, non-finite positions or zero area; the
/// part ranges are rewritten to the surviving triangles.
pub(super) fn clean_triangles(
    positions: &[Vec3],
    indices: &[u32],
    parts: Vec<MeshPart>,
    report: &mut MeshReport,
) -> (Vec<u32>, Vec<MeshPart>) {
    let n = positions.len();
    let tri_count = indices.len() / 3;
    // Parts that cover nothing get one implicit part spanning all triangles.
    let parts = if parts.is_empty() {
        vec![MeshPart {
            name: "mesh".to_owned(),
            first_triangle: 0,
            triangle_count: tri_count as u32,
        }]
    } else {
        parts
    };
    let (mut out_of_range, mut non_finite, mut degenerate) = (0, 0, 0);
    let mut out = Vec::with_capacity(indices.len());
    let mut new_parts = Vec::with_capacity(parts.len());
    for part in parts {
        let first_kept = out.len() / 3;
        let first = part.first_triangle as usize;
        let last = (first + part.triangle_count as usize).min(tri_count);
        for t in first..last {
            let tri = [indices[3 * t], indices[3 * t + 1], indices[3 * t + 2]];
            if tri.iter().any(|&i| i as usize >= n) {
                out_of_range += 1;
                continue;
            }
            let [a, b, c] = tri.map(|i| positions[i as usize]);
            if !(a.is_finite() && b.is_finite() && c.is_finite()) {
                non_finite += 1;
                continue;
            }
            let area2 = (b - a).cross(c - a).length_squared();
            if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] || area2 == 0.0 {
                degenerate += 1;
                continue;
            }
            out.extend_from_slice(&tri);
        }
        let kept = out.len() / 3 - first_kept;
        if kept > 0 {
            new_parts.push(MeshPart {
                name: part.name,
                first_triangle: first_kept as u32,
                triangle_count: kept as u32,
            });
        }
    }
    if !indices.len().is_multiple_of(3) {
        report.warnings.push(MeshWarning::Note(format!(
            "ignored {} trailing indices that do not make a triangle",
            indices.len() % 3
        )));
    }
    for (count, warning) in [
        (
            out_of_range,
            MeshWarning::OutOfRangeTriangles as fn(usize) -> MeshWarning,
        ),
        (non_finite, MeshWarning::NonFiniteTriangles),
        (degenerate, MeshWarning::DegenerateTriangles),
    ] {
        if count > 0 {
            report.warnings.push(warning(count));
        }
    }
    (out, new_parts)
}

pub(super) type Compacted = (
    Vec<Vec3>,
    Option<Vec<Vec3>>,
    Option<Vec<Vec2>>,
    Option<Vec<Vec4>>,
    Vec<u32>,
);

/// Removes vertices no triangle uses (keeping the order of the rest).
pub(super) fn compact_vertices(
    positions: Vec<Vec3>,
    normals: Option<Vec<Vec3>>,
    uvs: Option<Vec<Vec2>>,
    tangents: Option<Vec<Vec4>>,
    mut indices: Vec<u32>,
    report: &mut MeshReport,
) -> Compacted {
    let mut used = vec![false; positions.len()];
    for &i in &indices {
        used[i as usize] = true;
    }
    let unused = used.iter().filter(|&&u| !u).count();
    if unused == 0 {
        return (positions, normals, uvs, tangents, indices);
    }
    report.warnings.push(MeshWarning::UnusedVertices(unused));
    let mut remap = vec![u32::MAX; positions.len()];
    let mut next = 0u32;
    for (i, &u) in used.iter().enumerate() {
        if u {
            remap[i] = next;
            next += 1;
        }
    }
    fn keep<T: Copy>(v: Vec<T>, used: &[bool]) -> Vec<T> {
        v.into_iter()
            .zip(used)
            .filter_map(|(x, &u)| u.then_some(x))
            .collect()
    }
    for i in &mut indices {
        *i = remap[*i as usize];
    }
    (
        keep(positions, &used),
        normals.map(|v| keep(v, &used)),
        uvs.map(|v| keep(v, &used)),
        tangents.map(|v| keep(v, &used)),
        indices,
    )
}
