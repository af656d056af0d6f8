use super::test_util::*;
use super::*;

fn quad(uvs: bool) -> RawMesh {
    RawMesh {
        positions: vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ],
        uvs: uvs.then(|| {
            vec![
                Vec2::new(0.0, 0.0),
                Vec2::new(1.0, 0.0),
                Vec2::new(1.0, 1.0),
                Vec2::new(0.0, 1.0),
            ]
        }),
        indices: vec![0, 1, 2, 0, 2, 3],
        ..RawMesh::default()
    }
}

/// Eyes that come with a head (MakeHuman's `eye_l`) are not skin: no hair on them.
#[test]
fn eyes_teeth_and_lashes_are_left_out_of_the_skin() {
    let mut raw = quad(true);
    raw.positions.extend([
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(3.0, 0.0, 0.0),
        Vec3::new(2.0, 1.0, 0.0),
    ]);
    raw.uvs
        .as_mut()
        .unwrap()
        .extend([Vec2::ZERO, Vec2::X, Vec2::Y]);
    raw.indices.extend([4, 5, 6]);
    let part = |name: &str, first, count| MeshPart {
        name: name.into(),
        first_triangle: first,
        triangle_count: count,
    };
    raw.parts = vec![
        part("object \"head\"", 0, 2),
        part("object \"eye_l\"", 2, 1),
    ];
    let m = Mesh::build(raw, "head with an eye").unwrap();
    let names: Vec<&str> = m.skin_parts().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["object \"head\""]);
    assert_eq!(m.skin_indices().len(), 6);
    assert!(
        !MeshPart {
            name: "CC_Base_Teeth".into(),
            ..part("", 0, 0)
        }
        .is_skin()
    );
    // A head of one part keeps every triangle, uncopied.
    let whole = Mesh::build(quad(true), "quad").unwrap();
    assert!(matches!(
        whole.skin_indices(),
        std::borrow::Cow::Borrowed(_)
    ));
}

#[test]
fn a_clean_quad_keeps_everything_and_gets_normals_and_tangents() {
    let m = Mesh::build(quad(true), "quad").unwrap();
    assert_eq!(m.vertex_count(), 4);
    assert_eq!(m.triangle_count(), 2);
    assert!(m.report().normals_generated);
    assert!(!m.report().uvs_generated);
    assert_eq!(m.report().tangent_source, Some(TangentSource::MikkTSpace));
    assert!(m.report().warnings.is_empty(), "{:?}", m.report().warnings);
    for (n, t) in m.normals().iter().zip(m.tangents()) {
        assert_vec_close(*n, Vec3::Z, 1e-6, "normal");
        assert_vec_close(t.truncate(), Vec3::X, 1e-6, "tangent");
        assert_close(t.w, 1.0, 0.0, "handedness");
    }
    assert_eq!(m.bounds().size(), Vec3::new(1.0, 1.0, 0.0));
}

#[test]
fn bad_triangles_are_dropped_and_counted_and_the_rest_survives() {
    let mut raw = quad(true);
    raw.positions.push(Vec3::new(f32::NAN, 0.0, 0.0)); // 4
    raw.uvs.as_mut().unwrap().push(Vec2::ZERO);
    raw.indices.extend_from_slice(&[0, 1, 4]); // non-finite
    raw.indices.extend_from_slice(&[0, 1, 99]); // out of range
    raw.indices.extend_from_slice(&[0, 0, 1]); // repeated index
    raw.indices.extend_from_slice(&[0, 1, 1]); // repeated index
    let m = Mesh::build(raw, "bad").unwrap();
    assert_eq!(m.triangle_count(), 2);
    let w = &m.report().warnings;
    assert!(w.contains(&MeshWarning::NonFiniteTriangles(1)), "{w:?}");
    assert!(w.contains(&MeshWarning::OutOfRangeTriangles(1)), "{w:?}");
    assert!(w.contains(&MeshWarning::DegenerateTriangles(2)), "{w:?}");
    assert!(w.contains(&MeshWarning::UnusedVertices(1)), "{w:?}");
    assert_eq!(m.vertex_count(), 4);
    assert!(m.bounds().min.is_finite());
    assert_eq!(
        MeshWarning::DegenerateTriangles(12).to_string(),
        "dropped 12 degenerate triangles"
    );
}

#[test]
fn a_mesh_with_nothing_usable_is_an_error_that_says_why() {
    let raw = RawMesh {
        positions: vec![Vec3::ZERO; 3],
        indices: vec![0, 1, 2],
        ..RawMesh::default()
    };
    let err = Mesh::build(raw, "flat.obj").unwrap_err().to_string();
    assert!(
        err.contains("flat.obj") && err.contains("degenerate"),
        "{err}"
    );
    let err = Mesh::build(RawMesh::default(), "empty.obj")
        .unwrap_err()
        .to_string();
    assert!(err.contains("no triangles"), "{err}");
}

#[test]
fn degenerate_uvs_are_counted_but_the_mesh_is_kept() {
    let mut raw = quad(true);
    raw.uvs = Some(vec![Vec2::splat(0.25); 4]);
    let m = Mesh::build(raw, "uv").unwrap();
    assert!(
        m.report()
            .warnings
            .contains(&MeshWarning::DegenerateUvTriangles(2)),
        "{:?}",
        m.report().warnings
    );
    assert!(m.tangents().iter().all(|t| t.is_finite()));
}

#[test]
fn inconsistent_array_lengths_are_refused() {
    let mut raw = quad(true);
    raw.normals = Some(vec![Vec3::Z; 3]);
    assert!(Mesh::build(raw, "x").is_err());
}

#[test]
fn missing_uvs_are_generated_and_reported() {
    let m = Mesh::build(quad(false), "q").unwrap();
    assert!(m.report().uvs_generated);
    assert!(m.uvs().iter().all(|uv| uv.is_finite()));
}
