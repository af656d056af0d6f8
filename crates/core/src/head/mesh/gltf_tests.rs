//! Tests of the glTF loader and the GLB writer.
//! Fixtures are written by the tests: small glTF files with `data:` buffers, an
//! external `.bin`, and a GLB.
use super::*;
use crate::head::mesh::test_util::{assert_close, assert_vec_close};
use crate::head::mesh::{Mesh, TangentSource};

/// One primitive's data for a fixture.
struct Prim {
    positions: Vec<[f32; 3]>,
    normals: Option<Vec<[f32; 3]>>,
    uvs: Option<Vec<[f32; 2]>>,
    indices: Vec<u16>,
}

fn quad_prim(normals: bool, uvs: bool) -> Prim {
    Prim {
        positions: vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
        normals: normals.then(|| vec![[0.0, 0.0, 1.0]; 4]),
        // glTF v down: the top edge (y = 1) has v = 0.
        uvs: uvs.then(|| vec![[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]]),
        indices: vec![0, 1, 2, 0, 2, 3],
    }
}

/// Builds the JSON (and the binary buffer) of a file with one mesh per entry of
/// `meshes` (each a list of primitives) and the given `nodes` JSON.
fn fixture(meshes: &[Vec<Prim>], nodes: &str) -> (String, Vec<u8>) {
    let mut bin = Vec::new();
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    // One buffer view and its accessor: `kind` is the accessor's componentType, type
    // and count (and bounds), `VIEW` standing for the view's index.
    let mut push = |bytes: &[u8], kind: String| {
        let view = super::super::glb_write::push_view(&mut bin, &mut views, bytes, "");
        accessors.push(format!(r#"{{"bufferView":{view},{kind}}}"#));
        accessors.len() - 1
    };
    let floats =
        |count: usize, ty: &str| format!(r#""componentType":5126,"count":{count},"type":"{ty}""#);
    let mut mesh_json = Vec::new();
    for prims in meshes {
        let mut prim_json = Vec::new();
        for p in prims {
            let mut attrs = Vec::new();
            let (lo, hi) =
                p.positions
                    .iter()
                    .fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), q| {
                        (
                            [lo[0].min(q[0]), lo[1].min(q[1]), lo[2].min(q[2])],
                            [hi[0].max(q[0]), hi[1].max(q[1]), hi[2].max(q[2])],
                        )
                    });
            let bounds = format!(r#","min":{lo:?},"max":{hi:?}"#);
            let a = push(
                bytemuck::cast_slice(&p.positions),
                floats(p.positions.len(), "VEC3") + &bounds,
            );
            attrs.push(format!(r#""POSITION":{a}"#));
            if let Some(n) = &p.normals {
                let a = push(bytemuck::cast_slice(n), floats(n.len(), "VEC3"));
                attrs.push(format!(r#""NORMAL":{a}"#));
            }
            if let Some(t) = &p.uvs {
                let a = push(bytemuck::cast_slice(t), floats(t.len(), "VEC2"));
                attrs.push(format!(r#""TEXCOORD_0":{a}"#));
            }
            let i = push(
                bytemuck::cast_slice(&p.indices),
                format!(
                    r#""componentType":5123,"count":{},"type":"SCALAR""#,
                    p.indices.len()
                ),
            );
            prim_json.push(format!(
                r#"{{"attributes":{{{}}},"indices":{i}}}"#,
                attrs.join(",")
            ));
        }
        mesh_json.push(format!(
            r#"{{"name":"m{}","primitives":[{}]}}"#,
            mesh_json.len(),
            prim_json.join(",")
        ));
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":{nodes},"meshes":[{}],"accessors":[{}],"bufferViews":[{}],"buffers":[{{"byteLength":{},"uri":"URI"}}]}}"#,
        mesh_json.join(","),
        accessors.join(","),
        views.join(","),
        bin.len()
    );
    (json, bin)
}

fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for c in bytes.chunks(3) {
        let b = [c[0], *c.get(1).unwrap_or(&0), *c.get(2).unwrap_or(&0)];
        let n = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
        for k in 0..4 {
            if k <= c.len() {
                out.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

fn write_embedded(dir: &Path, name: &str, json: &str, bin: &[u8]) -> std::path::PathBuf {
    let path = dir.join(name);
    let uri = format!("data:application/octet-stream;base64,{}", base64(bin));
    std::fs::write(&path, json.replace("URI", &uri)).unwrap();
    path
}

fn write_glb(dir: &Path, name: &str, json: &str, bin: &[u8]) -> std::path::PathBuf {
    // GLB: the buffer has no uri.
    let json = json.replace(r#","uri":"URI""#, "");
    let path = dir.join(name);
    std::fs::write(&path, glb_container(json.as_bytes(), bin)).unwrap();
    path
}

/// Two meshes: "m0" with two primitives (a quad with normals and UVs, a quad with
/// UVs only), "m1" one quad; node 0 translates by (10, 0, 0) and has a child scaling
/// by 2 that holds m1.
fn two_level_fixture() -> (String, Vec<u8>) {
    fixture(
        &[
            vec![quad_prim(true, true), quad_prim(false, true)],
            vec![quad_prim(true, true)],
        ],
        r#"[{"name":"root","mesh":0,"translation":[10,0,0],"children":[1]},{"name":"child","mesh":1,"scale":[2,2,2]}]"#,
    )
}

fn check_two_level(m: &Mesh) {
    assert_eq!(m.triangle_count(), 6);
    assert_eq!(m.parts().len(), 3, "{:?}", m.parts());
    assert!(
        m.parts()[0].name.contains("m0") && m.parts()[0].name.contains("root"),
        "{:?}",
        m.parts()
    );
    assert!(m.parts()[2].name.contains("child"));
    // Node transforms: m0 at x ∈ [10, 11]; m1 under translate·scale at x ∈ [10, 12].
    assert_vec_close(m.bounds().min, Vec3::new(10.0, 0.0, 0.0), 1e-6, "min");
    assert_vec_close(m.bounds().max, Vec3::new(12.0, 2.0, 0.0), 1e-6, "max");
    // v flipped: the vertex at y = 1 of the first quad (glTF v = 0) has v = 1.
    for part in m.parts() {
        let scale = if part.name.contains("child") {
            2.0
        } else {
            1.0
        };
        let first = part.first_triangle as usize * 3;
        for &v in &m.indices()[first..first + part.triangle_count as usize * 3] {
            let (p, uv) = (m.positions()[v as usize], m.uvs()[v as usize]);
            assert_close(uv.y, p.y / scale, 1e-6, "v up");
        }
    }
    // The primitive without normals got computed ones; all face +z.
    for n in m.normals() {
        assert_vec_close(*n, Vec3::Z, 1e-6, "normal");
    }
    assert!(!m.report().uvs_generated);
    assert_eq!(m.report().tangent_source, Some(TangentSource::MikkTSpace));
    for t in m.tangents() {
        assert_vec_close(t.truncate(), Vec3::X, 1e-5, "tangent");
    }
}

#[test]
fn write_glb_reads_back_the_same_mesh_part_by_part() {
    // Two parts sharing the middle edge (vertices 1 and 4); part 1 is the right quad.
    let positions = vec![
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(2.0, 0.0, 0.5),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(2.0, 1.0, 0.5),
    ];
    let uvs = positions
        .iter()
        .map(|p| Vec2::new(0.3 * p.x, 0.7 * p.y + 0.1))
        .collect();
    let raw = RawMesh {
        positions,
        uvs: Some(uvs),
        indices: vec![0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4],
        parts: vec![
            MeshPart {
                name: "left \"L\"".to_owned(),
                first_triangle: 0,
                triangle_count: 2,
            },
            MeshPart {
                name: "right".to_owned(),
                first_triangle: 2,
                triangle_count: 2,
            },
        ],
        ..RawMesh::default()
    };
    let original = Mesh::build(raw, "two quads").unwrap();
    let glb = super::write_glb(&original);
    assert_eq!(&glb[..4], b"glTF");
    assert_eq!(glb, super::write_glb(&original), "deterministic");
    let back = Mesh::build(load_bytes(&glb, Path::new("x.glb")).unwrap(), "x.glb").unwrap();
    assert!(
        back.report().warnings.is_empty(),
        "{:?}",
        back.report().warnings
    );
    assert_eq!(back.report().tangent_source, Some(TangentSource::File));
    assert_eq!(back.parts().len(), 2);
    assert!(
        back.parts()[0].name.contains(r#""left "L"""#),
        "{:?}",
        back.parts()
    );
    // Each part carries its own vertices: the shared edge is written twice.
    assert_eq!(back.vertex_count(), 8);
    assert_eq!(back.triangle_count(), original.triangle_count());
    for (a, b) in original.indices().iter().zip(back.indices()) {
        let (a, b) = (*a as usize, *b as usize);
        assert_vec_close(
            original.positions()[a],
            back.positions()[b],
            0.0,
            "position",
        );
        assert_vec_close(original.normals()[a], back.normals()[b], 1e-6, "normal");
        let (ta, tb) = (original.tangents()[a], back.tangents()[b]);
        assert_vec_close(ta.truncate(), tb.truncate(), 1e-6, "tangent");
        assert_close(ta.w, tb.w, 0.0, "handedness");
        let (ua, ub) = (original.uvs()[a], back.uvs()[b]);
        assert_close(ua.x, ub.x, 0.0, "u");
        assert_close(ua.y, ub.y, 1e-6, "v (flipped twice)");
    }
}

#[test]
fn a_material_with_an_embedded_normal_map_is_valid_gltf() {
    let original = crate::head::mesh::Mesh::build(
        RawMesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            uvs: Some(vec![Vec2::ZERO, Vec2::X, Vec2::Y]),
            indices: vec![0, 1, 2],
            ..RawMesh::default()
        },
        "triangle",
    )
    .unwrap();
    // A 1×1 PNG: the importer only needs valid bytes in the chunk.
    let mut png = Vec::new();
    image::RgbImage::from_pixel(1, 1, image::Rgb([128, 128, 255]))
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    let material = GlbMaterial {
        name: "aged skin".into(),
        base_colour: [0.6, 0.4, 0.3, 1.0],
        base_colour_png: None,
        roughness: 0.45,
        metallic: 0.0,
        normal_png: Some(png.clone()),
        orm_png: None,
        extras: serde_json::json!({"age_years": 70.0}),
    };
    let glb = write_glb_with_material(&original, Some(&material));
    let gltf = ::gltf::Gltf::from_slice(&glb).expect("a valid GLB");
    let m = gltf.materials().next().expect("one material");
    assert_eq!(m.name(), Some("aged skin"));
    let pbr = m.pbr_metallic_roughness();
    assert_eq!(pbr.base_color_factor(), [0.6, 0.4, 0.3, 1.0]);
    assert_eq!(pbr.roughness_factor(), 0.45);
    let normal = m.normal_texture().expect("a normal texture");
    let ::gltf::image::Source::View { view, mime_type } = normal.texture().source().source() else {
        panic!("the image is embedded");
    };
    assert_eq!(mime_type, "image/png");
    let blob = gltf.blob.as_deref().unwrap();
    let start = view.offset();
    assert_eq!(&blob[start..start + view.length()], png.as_slice());
    let prim = gltf.meshes().next().unwrap().primitives().next().unwrap();
    assert_eq!(prim.material().index(), Some(0));
    assert!(prim.get(&::gltf::Semantic::Tangents).is_some());
    assert_eq!(gltf.materials().count(), 1, "all skin: one material");
    // And it still loads as a mesh.
    load_bytes(&glb, Path::new("x.glb")).unwrap();

    // A part that is not skin (an eye) gets a plain material, without our maps.
    let two = Mesh::load(Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/heads/makehuman/mh_head.obj"
    )))
    .unwrap();
    let glb = write_glb_with_material(&two, Some(&material));
    let gltf = ::gltf::Gltf::from_slice(&glb).expect("a valid GLB");
    assert_eq!(gltf.materials().count(), 2);
    for (k, mesh) in gltf.meshes().enumerate() {
        let prim = mesh.primitives().next().unwrap();
        let skin = two.part_is_skin(k, &two.parts()[k]);
        assert_eq!(
            prim.material().index(),
            Some(usize::from(!skin)),
            "{:?}",
            mesh.name()
        );
        assert_eq!(prim.material().normal_texture().is_some(), skin);
    }
}

#[test]
fn embedded_buffers_several_primitives_node_transforms_and_v_flip() {
    let dir = tempfile::tempdir().unwrap();
    let (json, bin) = two_level_fixture();
    let m = Mesh::load(&write_embedded(dir.path(), "a.gltf", &json, &bin)).unwrap();
    check_two_level(&m);
    assert!(
        m.report()
            .warnings
            .iter()
            .any(|w| matches!(w, MeshWarning::BadNormalsReplaced(4))),
        "the normals of the second primitive were computed: {:?}",
        m.report().warnings
    );
}

#[test]
fn glb_and_external_buffers_load_the_same() {
    let dir = tempfile::tempdir().unwrap();
    let (json, bin) = two_level_fixture();
    let glb = Mesh::load(&write_glb(dir.path(), "a.glb", &json, &bin)).unwrap();
    check_two_level(&glb);
    std::fs::write(dir.path().join("a.bin"), &bin).unwrap();
    let path = dir.path().join("b.gltf");
    std::fs::write(&path, json.replace("URI", "a.bin")).unwrap();
    let ext = Mesh::load(&path).unwrap();
    assert_eq!(ext.positions(), glb.positions());
    // A missing external buffer is an error naming the file.
    std::fs::remove_file(dir.path().join("a.bin")).unwrap();
    let err = Mesh::load(&path).unwrap_err().to_string();
    assert!(err.contains("b.gltf") && err.contains("buffer"), "{err}");
}

#[test]
fn without_normals_and_uvs_both_are_generated() {
    let dir = tempfile::tempdir().unwrap();
    let (json, bin) = fixture(&[vec![quad_prim(false, false)]], r#"[{"mesh":0}]"#);
    let m = Mesh::load(&write_embedded(dir.path(), "bare.gltf", &json, &bin)).unwrap();
    assert!(m.report().normals_generated && m.report().uvs_generated);
    assert!(m.uvs().iter().all(|uv| uv.is_finite()));
}

#[test]
fn a_mirroring_node_keeps_faces_outward() {
    let dir = tempfile::tempdir().unwrap();
    let (json, bin) = fixture(
        &[vec![quad_prim(true, true)]],
        r#"[{"mesh":0,"scale":[-1,1,1]}]"#,
    );
    let m = Mesh::load(&write_embedded(dir.path(), "mirror.gltf", &json, &bin)).unwrap();
    for t in m.triangles() {
        let [a, b, c] = t.map(|i| m.positions()[i as usize]);
        assert!(
            (b - a).cross(c - a).z > 0.0,
            "winding flipped back to face +z"
        );
    }
    for n in m.normals() {
        assert_vec_close(*n, Vec3::Z, 1e-6, "normal");
    }
    // u now runs along −x: the tangent follows it, handedness flips.
    for t in m.tangents() {
        assert_vec_close(t.truncate(), Vec3::NEG_X, 1e-5, "tangent");
        assert_close(t.w, -1.0, 0.0, "w");
    }
}

#[test]
fn quantized_positions_are_refused_clearly() {
    let dir = tempfile::tempdir().unwrap();
    let (json, bin) = fixture(&[vec![quad_prim(true, true)]], r#"[{"mesh":0}]"#);
    // Re-type the position accessor as normalized shorts (KHR_mesh_quantization).
    let json = json.replacen(
        r#""componentType":5126,"count":4,"type":"VEC3""#,
        r#""componentType":5122,"normalized":true,"count":4,"type":"VEC3""#,
        1,
    );
    let err = Mesh::load(&write_embedded(dir.path(), "q.gltf", &json, &bin))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("KHR_mesh_quantization") && err.contains("Positions"),
        "{err}"
    );
}

#[test]
fn out_of_range_indices_are_dropped_and_the_rest_kept() {
    let dir = tempfile::tempdir().unwrap();
    let mut prim = quad_prim(true, true);
    prim.indices = vec![0, 1, 2, 0, 2, 9];
    let (json, bin) = fixture(&[vec![prim]], r#"[{"mesh":0}]"#);
    let m = Mesh::load(&write_embedded(dir.path(), "oob.gltf", &json, &bin)).unwrap();
    assert_eq!(m.triangle_count(), 1);
    assert!(
        m.report()
            .warnings
            .contains(&MeshWarning::OutOfRangeTriangles(1))
    );
}

#[test]
fn buffer_uris_outside_the_folder_are_refused() {
    for (uri, ok) in [
        ("data:application/octet-stream;base64,AAAA", true),
        ("mesh.bin", true),
        ("sub/mesh%20a.bin", true),
        ("../../../../etc/passwd", false),
        ("sub/../../x.bin", false),
        ("%2e%2e/x.bin", false),
        ("/etc/passwd", false),
        ("file:///etc/passwd", false),
        ("C:\\x.bin", false),
    ] {
        assert_eq!(check_uri(uri).is_ok(), ok, "{uri}");
    }
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("escape.gltf");
    std::fs::write(
        &path,
        r#"{"asset":{"version":"2.0"},"buffers":[{"byteLength":4,"uri":"../../../../etc/passwd"}]}"#,
    )
    .unwrap();
    let e = load(&path).unwrap_err().to_string();
    assert!(e.contains("escape.gltf") && e.contains("climbs out"), "{e}");
}

#[test]
fn garbage_is_an_error_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("x.glb");
    std::fs::write(&path, b"glTF\x02\0\0\0garbage").unwrap();
    assert!(Mesh::load(&path).is_err());
    let path = dir.path().join("x.gltf");
    std::fs::write(&path, b"{}").unwrap();
    assert!(Mesh::load(&path).is_err());
}

#[test]
fn strips_and_fans_become_lists() {
    assert_eq!(
        triangulate(Mode::TriangleStrip, &[0, 1, 2, 3]),
        vec![0, 1, 2, 2, 1, 3]
    );
    assert_eq!(
        triangulate(Mode::TriangleFan, &[0, 1, 2, 3]),
        vec![0, 1, 2, 0, 2, 3]
    );
    assert_eq!(triangulate(Mode::Triangles, &[0, 1, 2, 3]), vec![0, 1, 2]);
}
