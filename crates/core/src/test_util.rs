//! Helpers shared by the unit tests of agesim-core.

/// Asserts `|actual − expected| ≤ tol`, printing both values and the difference when not.
#[track_caller]
pub fn close(actual: f32, expected: f32, tol: f32) {
    assert!(
        (actual - expected).abs() <= tol,
        "expected {expected}, got {actual} (difference {}, tolerance {tol})",
        actual - expected
    );
}

/// The largest relative error of `got` against the f64 `want` over `xs`, and where it is
/// (an absolute error where `want` is 0).
pub fn worst_relative_error(
    xs: impl IntoIterator<Item = f32>,
    got: impl Fn(f32) -> f32,
    want: impl Fn(f64) -> f64,
) -> (f64, f32) {
    xs.into_iter().fold((0.0, 0.0), |worst, x| {
        let (g, w) = (got(x) as f64, want(x as f64));
        let e = if w == 0.0 {
            g.abs()
        } else {
            ((g - w) / w).abs()
        };
        if e > worst.0 { (e, x) } else { worst }
    })
}

/// The aged colour's factors with only the brows' gray and the contrast curve set (what
/// the brow hairs and lashes age by).
pub fn eye_hair_factors(brow_gray: f32, contrast: f32) -> crate::age::ColourFactors {
    crate::age::ColourFactors {
        contrast,
        brow_gray,
        ..Default::default()
    }
}

/// A brow hair's or lash's length along its curve's control polygon, mesh units.
pub fn strand_length(s: &crate::layers::hair::brows::BrowStrand) -> f32 {
    use glam::Vec3;
    let (r, m, t) = (Vec3::from(s.root), Vec3::from(s.middle), Vec3::from(s.tip));
    r.distance(m) + m.distance(t)
}

/// Asserts that strands grown on the default head in centimetres are 100 × as long as on
/// it in metres: `young_strands(mesh, template_point, metres_per_unit)` places them (the
/// template points stay in metres) and gives them young.
pub fn assert_strands_in_heads_units(
    young_strands: impl Fn(
        &crate::head::mesh::Mesh,
        &dyn Fn(usize) -> Option<glam::Vec3>,
        f32,
    ) -> Vec<crate::layers::hair::brows::BrowStrand>,
) {
    let template = crate::head::fit::template();
    let positions = template.mesh.positions();
    let point = |v: usize| Some(positions[v]);
    let cm = template.mesh.scaled(100.0);
    let (a, b) = (
        young_strands(&template.mesh, &point, 1.0),
        young_strands(&cm, &point, 0.01),
    );
    assert!(!a.is_empty());
    assert_eq!(a.len(), b.len());
    for (a, b) in a.iter().zip(&b) {
        assert!((strand_length(b) / strand_length(a) - 100.0).abs() < 0.01);
    }
}

/// `mesh` with every triangle split in four at its edges' midpoints (UVs too): a dense
/// head of the same shape, named `name`.
pub fn subdivided(mesh: &crate::Mesh, name: &str) -> crate::Mesh {
    use glam::{Vec2, Vec3};
    use std::collections::HashMap;
    let mut positions = mesh.positions().to_vec();
    let mut uvs = mesh.uvs().to_vec();
    let mut mid: HashMap<(u32, u32), u32> = HashMap::new();
    let mut indices = Vec::new();
    let mut midpoint = |a: u32, b: u32, positions: &mut Vec<Vec3>, uvs: &mut Vec<Vec2>| {
        *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
            let (i, j) = (a as usize, b as usize);
            positions.push(0.5 * (positions[i] + positions[j]));
            uvs.push(0.5 * (uvs[i] + uvs[j]));
            positions.len() as u32 - 1
        })
    };
    for t in mesh.indices().chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]];
        let ab = midpoint(a, b, &mut positions, &mut uvs);
        let bc = midpoint(b, c, &mut positions, &mut uvs);
        let ca = midpoint(c, a, &mut positions, &mut uvs);
        indices.extend([a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca]);
    }
    let raw = crate::head::mesh::RawMesh {
        positions,
        uvs: Some(uvs),
        indices,
        ..Default::default()
    };
    crate::Mesh::build(raw, name).expect("a subdivided mesh builds")
}
