//! Random and mutated inputs to every parser of user files: the wrinkle-file parser, the
//! project loader, the landmark files, and the mesh loaders (OBJ, glTF/GLB) and
//! `Mesh::build`. Each must return
//! `Ok` or an error, never panic. Not part of the default `cargo test` (they are
//! `#[ignore]`d); the dedicated run, 100,000 cases per target by default:
//!
//! ```sh
//! cargo test --release -p agesim-core --test fuzz -- --ignored
//! PROPTEST_CASES=1000000 cargo test --release -p agesim-core --test fuzz -- --ignored
//! ```
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;

use agesim_core::landmarks::Landmarks;
use agesim_core::mesh::{Mesh, gltf, obj, units};
use agesim_core::project::Project;
use agesim_core::wrinkle_file;
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
            let _ = units::detect(&agesim_core::head::default_head().bounds(), Some(&l));
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
}
