//! Random and mutated inputs to every parser of user files: the wrinkle-file parser, the
//! project loader, the landmark files, the mesh loaders (OBJ, glTF/GLB) and
//! `Mesh::build` — a real GLB mutated in its JSON chunk and in its binary chunk, an OBJ
//! with objects, groups, materials and polygons — and the image loaders of masks and
//! head pictures (PNG, JPEG). Each must return
//! `Ok` or an error, never panic. Not part of the default `cargo test` (they are
//! `#[ignore]`d); the dedicated run, 100,000 cases per target by default:
//!
//! ```sh
//! cargo test --release -p agesim-core --test fuzz -- --ignored
//! PROPTEST_CASES=1000000 cargo test --release -p agesim-core --test fuzz -- --ignored
//! ```
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;

use agesim_core::head::landmarks::Landmarks;
use agesim_core::head::mesh::{Mesh, gltf, obj, units};
use agesim_core::layers::wrinkles::wrinkle_file;
use agesim_core::project::Project;
use proptest::prelude::*;

fn config() -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(100_000);
    ProptestConfig {
        cases,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// A valid wrinkle file to mutate.
const WRK: &str = include_str!("../../../assets/wrinkles/forehead.wrk");
/// A valid project to mutate.
const PROJECT: &str = include_str!("../../../assets/presets/rough.agesim.json");
/// A valid landmark file to mutate.
const LANDMARKS: &str = r#"{"landmarks": {"exocanthion_r": [-4.7, 0, 0],
    "exocanthion_l": [4.7, 0, 0], "pogonion": [0, -8, 1], "glabella": [0, 3, 1],
    "pronasale": [0, -2, 4]}}"#;
/// A small valid OBJ to mutate.
const OBJ: &str =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\n";

/// An OBJ as tools write them: objects, groups, smoothing, materials, polygons, negative
/// indices, a missing material library.
const REAL_OBJ: &str = "# exported\nmtllib head.mtl\no Head\nv -1 0 0\nv 1 0 0\nv 1 2 0\nv -1 2 0\nv 0 3 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 1\nvn 0 0 1\ng skin\nusemtl Skin\ns 1\nf 1/1/1 2/2/1 3/3/1 4/4/1\nf -2/-2/1 -3/-3/1 5/5/1\no eye_l\ng eye\nusemtl Eye\ns off\nf 1//1 2//1 5//1\nl 1 2\n";

/// A real GLB: two parts with normals, UVs and indices, a material with an embedded PNG.
fn real_glb() -> Vec<u8> {
    use agesim_core::head::mesh::{MeshPart, RawMesh};
    use glam::{Vec2, Vec3};
    let n = 6u32;
    let mut raw = RawMesh::default();
    let mut uvs = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (u, v) = (i as f32 / n as f32, j as f32 / n as f32);
            raw.positions.push(Vec3::new(u, v, (u * 3.0).sin() * 0.2));
            uvs.push(Vec2::new(u, v));
        }
    }
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            raw.indices
                .extend_from_slice(&[a, a + 1, a + n + 2, a, a + n + 2, a + n + 1]);
        }
    }
    raw.uvs = Some(uvs);
    let half = n * n;
    raw.parts = vec![
        MeshPart {
            name: "skin".into(),
            first_triangle: 0,
            triangle_count: half,
        },
        MeshPart {
            name: "eye".into(),
            first_triangle: half,
            triangle_count: half,
        },
    ];
    let mesh = Mesh::build(raw, "fuzz base").unwrap();
    let material = gltf::GlbMaterial {
        name: "m".into(),
        base_colour: [1.0; 4],
        base_colour_png: Some(png()),
        roughness: 0.5,
        metallic: 0.0,
        normal_png: None,
        orm_png: None,
        extras: serde_json::Value::Null,
    };
    gltf::write_glb_with_material(&mesh, Some(&material))
}

/// A small PNG and JPEG.
fn png() -> Vec<u8> {
    let img = image::RgbImage::from_fn(8, 6, |x, y| image::Rgb([x as u8 * 30, y as u8 * 40, 90]));
    let mut out = Vec::new();
    img.write_to(&mut std::io::Cursor::new(&mut out), image::ImageFormat::Png)
        .unwrap();
    out
}

fn jpeg() -> Vec<u8> {
    let img = image::RgbImage::from_fn(8, 6, |x, y| image::Rgb([x as u8 * 30, y as u8 * 40, 90]));
    let mut out = Vec::new();
    img.write_to(
        &mut std::io::Cursor::new(&mut out),
        image::ImageFormat::Jpeg,
    )
    .unwrap();
    out
}

fn exr() -> Vec<u8> {
    let img = image::Rgb32FImage::from_fn(8, 6, |x, y| {
        image::Rgb([x as f32 * 0.1, y as f32 * 0.15, 0.35])
    });
    let mut out = Vec::new();
    image::DynamicImage::ImageRgb32F(img)
        .write_to(
            &mut std::io::Cursor::new(&mut out),
            image::ImageFormat::OpenExr,
        )
        .unwrap();
    out
}

fn leak(v: Vec<u8>) -> &'static [u8] {
    Box::leak(v.into_boxed_slice())
}

/// The GLB's chunks: (JSON, binary).
fn chunks(glb: &[u8]) -> (Vec<u8>, Vec<u8>) {
    let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let json = glb[20..20 + json_len].to_vec();
    let bin = glb[20 + json_len + 8..].to_vec();
    (json, bin)
}

/// A GLB of these chunks, the lengths made right (the loader sees the mutation itself).
fn assemble(json: &[u8], bin: &[u8]) -> Vec<u8> {
    gltf::glb_container(json, bin)
}

/// Loads a GLB's mesh and pictures the way a scene does, from a file (the pictures are
/// read by path).
fn load_glb(bytes: &[u8]) {
    if let Ok(raw) = gltf::load_bytes(bytes, Path::new("fuzz.glb")) {
        let _ = Mesh::build(raw, "fuzz.glb");
    }
    thread_local! {
        static DIR: tempfile::TempDir = tempfile::tempdir().unwrap();
    }
    DIR.with(|d| {
        let path = d.path().join("fuzz.glb");
        std::fs::write(&path, bytes).unwrap();
        let _ = agesim_core::head::mesh::textures::load(&path);
    });
}

/// `base` with a few bytes replaced, inserted or removed at seeded positions.
fn mutated(base: &'static [u8]) -> impl Strategy<Value = Vec<u8>> {
    prop::collection::vec((any::<usize>(), any::<u8>(), 0u8..3), 1..8).prop_map(move |edits| {
        let mut v = base.to_vec();
        for (at, byte, kind) in edits {
            let i = if v.is_empty() { 0 } else { at % v.len() };
            match kind {
                0 if !v.is_empty() => v[i] = byte,
                1 => v.insert(i, byte),
                _ if !v.is_empty() => {
                    v.remove(i);
                }
                _ => v.push(byte),
            }
        }
        v
    })
}

/// Text made of the format's own tokens, so the parsers get past their first checks.
fn token_soup(tokens: &'static [&'static str]) -> impl Strategy<Value = String> {
    prop::collection::vec(prop::sample::select(tokens), 0..60).prop_map(|t| t.concat())
}

proptest! {
    #![proptest_config(config())]

    #[test]
    #[ignore]
    fn wrinkle_files_never_panic(
        bytes in prop_oneof![
            prop::collection::vec(any::<u8>(), 0..400),
            mutated(WRK.as_bytes()),
            token_soup(&["!\n", "ma=", "mb=", "n=", "relWidth=", "maxAngle=", "omegaLow=",
                "profile=", "depth=", "ageOnset=", "ageFull=", "ageShape=", "0.5", ";", "-1",
                "1e39", "nan", "3", "\n", "#", " ", "abs_sin", "\r\n", "\u{feff}"])
                .prop_map(String::into_bytes),
        ]
    ) {
        let _ = wrinkle_file::parse_bytes(&bytes, Path::new("fuzz.wrk"));
    }

    #[test]
    #[ignore]
    fn projects_never_panic(
        text in prop_oneof![
            ".{0,300}",
            mutated(PROJECT.as_bytes()).prop_map(|b| String::from_utf8_lossy(&b).into_owned()),
            token_soup(&["{", "}", "[", "]", ",", ":", "\"pores\"", "\"count\"", "\"noise\"",
                "\"details\"", "\"version\"", "\"age\"", "\"t\"", "\"large\"", "\"wrinkles\"",
                "1", "-1", "1e300", "null", "true", "\"x\"", "0.5", "2"]),
        ]
    ) {
        if let Ok(p) = Project::from_json_str(&text, "fuzz.agesim.json") {
            // Whatever loads must also round-trip and give micro settings or an error.
            let _ = p.micro_settings();
            Project::from_json_str(&p.to_json_pretty(), "again").unwrap();
        }
    }

    #[test]
    #[ignore]
    fn landmark_files_never_panic(
        text in prop_oneof![
            ".{0,200}",
            mutated(LANDMARKS.as_bytes()).prop_map(|b| String::from_utf8_lossy(&b).into_owned()),
            token_soup(&["{", "}", "[", "]", ",", ":", "\"landmarks\"", "\"pronasale\"",
                "\"exocanthion_r\"", "\"exocanthion_l\"", "\"pogonion\"", "\"nose\"", "1",
                "-1", "1e39", "0", "null", "\"x\""]),
        ]
    ) {
        if let Ok(l) = Landmarks::from_json_str(&text) {
            // What loads writes back the same, and gives units and axes or none.
            prop_assert_eq!(&Landmarks::from_json_str(&l.to_json_pretty()).unwrap(), &l);
            let _ = units::detect(&agesim_core::head::default::default_head().bounds(), Some(&l));
            let _ = units::detect_axes(&l);
        }
    }

    #[test]
    #[ignore]
    fn meshes_never_panic(
        bytes in prop_oneof![
            prop::collection::vec(any::<u8>(), 0..400),
            mutated(OBJ.as_bytes()),
            token_soup(&["v ", "vt ", "vn ", "f ", "1", "2", "3", "/", "-1", "0.5", "nan",
                "1e30", " ", "\n", "o x\n", "g y\n"]).prop_map(String::into_bytes),
        ]
    ) {
        if let Ok(raw) = obj::load_bytes(&bytes, Path::new("fuzz.obj")) {
            let _ = Mesh::build(raw, "fuzz.obj");
        }
        if let Ok(raw) = gltf::load_bytes(&bytes, Path::new("fuzz.gltf")) {
            let _ = Mesh::build(raw, "fuzz.gltf");
        }
    }

    #[test]
    #[ignore]
    fn a_real_obj_mutated_never_panics(bytes in mutated(REAL_OBJ.as_bytes())) {
        if let Ok(raw) = obj::load_bytes(&bytes, Path::new("fuzz.obj")) {
            let _ = Mesh::build(raw, "fuzz.obj");
        }
    }

    #[test]
    #[ignore]
    fn a_real_glb_mutated_in_its_json_never_panics(json in mutated(leak(chunks(&real_glb()).0))) {
        load_glb(&assemble(&json, &chunks(&real_glb()).1));
    }

    #[test]
    #[ignore]
    fn a_real_glb_mutated_in_its_binary_never_panics(bin in mutated(leak(chunks(&real_glb()).1))) {
        load_glb(&assemble(&chunks(&real_glb()).0, &bin));
    }

    #[test]
    #[ignore]
    fn images_never_panic(
        bytes in prop_oneof![
            mutated(leak(png())),
            mutated(leak(jpeg())),
            mutated(leak(exr())),
            prop::collection::vec(any::<u8>(), 0..200),
        ]
    ) {
        let _ = agesim_core::Mask::decode(&bytes, Path::new("fuzz.png"));
        let _ = agesim_core::maps::mask::HeadImage::decode(&bytes, Path::new("fuzz.png"));
        let _ = agesim_core::maps::mask::HeadImage::decode(&bytes, Path::new("fuzz.exr"));
    }
}

#[test]
fn a_few_fuzz_cases_run_in_the_default_test_run_too() {
    // Keeps the harness compiling and working; the big run is the ignored tests above.
    let mut runner = proptest::test_runner::TestRunner::new(ProptestConfig {
        cases: 200,
        failure_persistence: None,
        ..ProptestConfig::default()
    });
    runner
        .run(&mutated(WRK.as_bytes()), |b| {
            let _ = wrinkle_file::parse_bytes(&b, Path::new("fuzz.wrk"));
            Ok(())
        })
        .unwrap();
    runner
        .run(&mutated(LANDMARKS.as_bytes()), |b| {
            let _ = Landmarks::from_json_str(&String::from_utf8_lossy(&b));
            Ok(())
        })
        .unwrap();
    let (json, bin) = chunks(&real_glb());
    runner
        .run(&mutated(leak(json.clone())), |j| {
            load_glb(&assemble(&j, &bin));
            Ok(())
        })
        .unwrap();
    runner
        .run(&mutated(leak(bin.clone())), |b| {
            load_glb(&assemble(&json, &b));
            Ok(())
        })
        .unwrap();
}
