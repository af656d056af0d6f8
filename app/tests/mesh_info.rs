//! `agesim mesh-info` end to end: the built binary on the default head, an OBJ and a
//! glTF written by the test, and on bad input.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod cli;

use cli::{agesim, stderr, stdout};

use std::process::{Command, Output};

fn mesh_info(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_agesim"))
        .arg("mesh-info")
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn reports_the_default_head() {
    for args in [&[][..], &["--default-head"][..]] {
        let out = mesh_info(args);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = stdout(&out);
        assert!(text.contains("default head"), "{text}");
        let triangles: usize = text
            .lines()
            .find_map(|l| l.strip_prefix("triangles:"))
            .unwrap()
            .trim()
            .parse()
            .unwrap();
        // The converted scan: 16 186 triangles, its skin and its eye sockets.
        assert!((10_000..=200_000).contains(&triangles), "{text}");
        assert!(text.contains("tangents:  from the file"), "{text}");
        assert!(
            text.contains("eye sockets (inside the closed lids)"),
            "{text}"
        );
        assert!(text.contains("not skin"), "{text}");
        // The same GLB read from disk reports the same provenance (all but the name line).
        let from_disk = Command::new(env!("CARGO_BIN_EXE_agesim"))
            .args([
                "mesh-info",
                concat!(
                    env!("CARGO_MANIFEST_DIR"),
                    "/../assets/meshes/default-head.glb"
                ),
            ])
            .output()
            .unwrap();
        let disk = stdout(&from_disk);
        // The mesh's own lines (a file's units and layout are then measured, not given).
        let mesh_lines = |t: &str| -> Vec<String> {
            t.lines()
                .skip(1)
                .take_while(|l| !l.starts_with("metres per unit"))
                .map(str::to_owned)
                .collect()
        };
        assert_eq!(mesh_lines(&text), mesh_lines(&disk));
    }
}

#[test]
fn reports_an_obj_without_normals_and_uvs() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("tet.obj");
    // A tetrahedron of 2 m, plus a degenerate face.
    std::fs::write(
        &path,
        "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 2\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\nf 1 1 2\n",
    )
    .unwrap();
    let out = mesh_info(&[path.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = stdout(&out);
    assert!(text.contains("triangles: 4"), "{text}");
    assert!(
        text.contains("size:      2.0000 × 2.0000 × 2.0000"),
        "{text}"
    );
    assert!(text.contains("normals:   generated"), "{text}");
    assert!(
        text.contains("uvs:       generated (inverse spherical mapping"),
        "{text}"
    );
    assert!(text.contains("dropped 1 degenerate triangles"), "{text}");
}

#[test]
fn reports_a_gltf_with_a_node_transform() {
    let dir = tempfile::tempdir().unwrap();
    // One triangle, positions as little-endian f32, scaled by 3 by its node.
    let positions: [f32; 9] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
    let bytes: Vec<u8> = positions.iter().flat_map(|f| f.to_le_bytes()).collect();
    std::fs::write(dir.path().join("tri.bin"), &bytes).unwrap();
    let json = r#"{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
        "nodes":[{"name":"big","mesh":0,"scale":[3,3,3]}],
        "meshes":[{"name":"tri","primitives":[{"attributes":{"POSITION":0}}]}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],
        "bufferViews":[{"buffer":0,"byteLength":36}],
        "buffers":[{"byteLength":36,"uri":"tri.bin"}]}"#;
    let path = dir.path().join("tri.gltf");
    std::fs::write(&path, json).unwrap();
    let out = mesh_info(&[path.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = stdout(&out);
    assert!(text.contains("triangles: 1"), "{text}");
    assert!(
        text.contains("size:      3.0000 × 3.0000 × 0.0000"),
        "{text}"
    );
    assert!(
        text.contains(r#"mesh "tri" primitive 0 (node "big")"#),
        "{text}"
    );
}

#[test]
fn fails_with_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing.obj");
    let out = mesh_info(&[missing.to_str().unwrap()]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("missing.obj"), "{err}");
    // The OS reason once: the core error carries it, the app's chain must not repeat it.
    let os_message = std::fs::read(&missing).unwrap_err().to_string();
    assert_eq!(err.matches(os_message.as_str()).count(), 1, "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");

    let stl = dir.path().join("head.stl");
    std::fs::write(&stl, "solid x").unwrap();
    let out = mesh_info(&[stl.to_str().unwrap()]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("unsupported mesh format"));
}

/// `mesh-info` says how long a unit is and how it decided: from the size, or from the
/// outer eye corners of a landmark file.
#[test]
fn mesh_info_prints_the_units_and_how_they_were_decided() {
    let out = agesim(&["mesh-info"]);
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        text.contains("metres per unit: 1 (metres: a built-in mesh)"),
        "{text}"
    );
    assert!(text.contains("axes:      up +Y, forward +Z"), "{text}");
    // The default head in centimetres, with its own landmarks: the units from the eye
    // corners, the axes from the face, the template fitted by the file.
    let dir = tempfile::tempdir().unwrap();
    let head = agesim_core::head::default::default_head();
    let obj = dir.path().join("head.obj");
    std::fs::write(
        &obj,
        agesim_core::head::mesh::obj::to_obj(&head, |p| p * 100.0),
    )
    .unwrap();
    let mut marks = agesim_core::head::landmarks::Landmarks::default();
    let template = &agesim_core::head::fit::template().landmarks;
    for name in agesim_core::head::landmarks::NAMES {
        marks
            .set(name, template.get(name).unwrap() * 100.0)
            .unwrap();
    }
    let landmarks = dir.path().join("l.json");
    std::fs::write(&landmarks, marks.to_json_pretty()).unwrap();
    let file = obj.to_str().unwrap();
    let out = agesim(&[
        "mesh-info",
        file,
        "--landmarks",
        landmarks.to_str().unwrap(),
    ]);
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        text.contains("metres per unit: 0.01 (centimetres: outer eye corners 9.5"),
        "{text}"
    );
    assert!(
        text.contains("up +Y, forward +Z (from the landmarks)"),
        "{text}"
    );
    assert!(
        text.contains("layout:    the template fitted by the landmark file: 16 landmarks"),
        "{text}"
    );
    // Without landmarks: found on the head, and the units from them.
    let out = agesim(&["mesh-info", file]);
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        text.contains("layout:    the template fitted by landmarks found automatically"),
        "{text}"
    );
    assert!(
        text.contains("metres per unit: 0.01 (centimetres: outer eye corners"),
        "{text}"
    );
    // A bad landmark file is refused with its name and the point at fault.
    std::fs::write(&landmarks, r#"{"landmarks": {"nose": [0, 0, 0]}}"#).unwrap();
    let out = agesim(&[
        "mesh-info",
        file,
        "--landmarks",
        landmarks.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(
        !out.status.success() && err.contains("l.json") && err.contains("`nose`"),
        "{err}"
    );
}

/// The person: on the African man's panel head with his colour map, `mesh-info` prints his
/// skin tone with its ITA° group, his measured hair colour (dark) and brows, and the hair
/// loss guessed from his face, the curl guessed from his skin, his facial contrast; without the map, the hair colour is the
/// default and says so, and there is no contrast to measure.
#[test]
fn prints_the_persons_measured_colours_and_hair_loss() {
    let panel = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/heads/panel");
    let head = panel.join("african-male.obj").display().to_string();
    let map = panel
        .join("middleage_darkskinned_male_diffuse.jpg")
        .display()
        .to_string();
    let out = mesh_info(&[&head, "--colour-map", &map]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = stdout(&out);
    let line = |start: &str| {
        text.lines()
            .find(|l| l.starts_with(start))
            .unwrap_or_else(|| panic!("no `{start}` in {text}"))
            .to_owned()
    };
    assert!(line("skin tone: #").contains(": dark"), "{text}");
    let hair = line("hair colour: #");
    assert!(
        hair.contains("measured on the colour map's scalp"),
        "{hair}"
    );
    let l_star: f32 = hair
        .split("L* ")
        .nth(1)
        .and_then(|s| s.split(',').next())
        .and_then(|s| s.trim().parse().ok())
        .unwrap();
    assert!(l_star < 30.0, "{hair}");
    assert!(
        line("hair loss: ").contains("male (guessed from the face"),
        "{text}"
    );
    assert!(
        line("hair curl: ").starts_with("hair curl: coiled 1.0 (guessed from the skin's tone"),
        "{text}"
    );
    // His brows and lips are darker than his cheeks (0.12 each).
    let contrast = line("facial contrast: brows 0.");
    assert!(contrast.contains(", lips 0.1"), "{contrast}");
    let bare = stdout(&mesh_info(&[&head]));
    assert!(
        bare.contains("hair colour: #3f2c1f (a dark brown"),
        "{bare}"
    );
    assert!(
        bare.contains("facial contrast: no colour map to measure"),
        "{bare}"
    );
    // Without the map, his skin is the project's light default: straight hair.
    assert!(bare.contains("hair curl: straight 0.0 (guessed"), "{bare}");
    // --landmarks describes a mesh: without one it is refused, naming the flag.
    let e = mesh_info(&["--landmarks", &map]);
    assert!(!e.status.success());
    assert!(stderr(&e).contains("--landmarks"), "{}", stderr(&e));
}

/// With an age, `mesh-info` says how many of the head's hairs are there then: fewer at 75
/// than at 25 (the default head recedes and thins).
#[test]
fn the_age_flags_say_how_many_hairs_are_left() {
    let hairs = |years: &str| {
        let out = stdout(&mesh_info(&["--age-years", years]));
        let line = out
            .lines()
            .find(|l| l.starts_with(&format!("at {years} years: ")))
            .unwrap_or_else(|| panic!("no hair line at {years}:\n{out}"))
            .to_owned();
        let words: Vec<&str> = line.split_whitespace().collect();
        let (now, all): (u64, u64) = (words[3].parse().unwrap(), words[5].parse().unwrap());
        (now, all)
    };
    let (young, all) = hairs("25");
    let (old, all_old) = hairs("75");
    assert_eq!(all, all_old);
    assert!(old < young && young <= all, "{young} → {old} of {all}");
}
