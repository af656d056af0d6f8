//! End-to-end tests of `agesim hair` (docs/models.md §9): the real binary on real files.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod cli;

use cli::agesim;

use std::path::Path;
use std::process::Output;

fn ok(args: &[&str]) -> Output {
    let out = agesim(args);
    assert!(
        out.status.success(),
        "agesim {args:?} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

fn read_json(dir: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(dir.join("hair.json")).unwrap()).unwrap()
}

fn counts(report: &serde_json::Value) -> Vec<(f64, u64)> {
    report["counts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| (c["t"].as_f64().unwrap(), c["count"].as_u64().unwrap()))
        .collect()
}

/// A 10 cm × 10 cm square in the z = 0 plane, metres, UV over [0,1]².
const SQUARE_OBJ: &str = "v 0 0 0\nv 0.1 0 0\nv 0.1 0.1 0\nv 0 0.1 0\n\
vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n\
f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n";

#[test]
fn default_head_writes_a_16_bit_transition_and_decreasing_counts() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("hair");
    ok(&["hair", "--density", "20", "--out", out.to_str().unwrap()]);
    let png = image::open(out.join("transition.png")).unwrap();
    assert_eq!(png.color(), image::ColorType::L16);
    let grey = png.into_luma16();
    // The three kinds of texel are all there: no hair, receding hair, inner hair.
    assert!(grey.pixels().any(|p| p.0[0] == 0));
    assert!(grey.pixels().any(|p| p.0[0] == 65535));
    assert!(grey.pixels().any(|p| p.0[0] > 0 && p.0[0] < 65535));

    let report = read_json(&out);
    let c = counts(&report);
    assert_eq!(
        c.iter().map(|c| c.0).collect::<Vec<_>>(),
        [0.0, 0.25, 0.5, 0.75, 1.0]
    );
    assert_eq!(c[0].1, report["instances"].as_u64().unwrap());
    assert!(c.windows(2).all(|w| w[1].1 <= w[0].1), "{c:?}");
    assert!(
        c[4].1 > 0 && c[4].1 < c[0].1,
        "inner hair stays, outer goes: {c:?}"
    );
    assert!(
        report["timings_ms"]["transition_and_instances"]
            .as_f64()
            .unwrap()
            >= 0.0
    );
    assert_eq!(report["mesh"], "default head");
}

#[test]
fn custom_mesh_and_masks_of_different_sizes() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = dir.path().join("square.obj");
    std::fs::write(&mesh, SQUARE_OBJ).unwrap();
    // Outer: all white, 64×64. Inner: left half white, 32×16 (another size and aspect).
    let outer = dir.path().join("outer.png");
    image::GrayImage::from_pixel(64, 64, image::Luma([255]))
        .save(&outer)
        .unwrap();
    let inner = dir.path().join("inner.png");
    image::GrayImage::from_fn(32, 16, |x, _| image::Luma([if x < 16 { 255 } else { 0 }]))
        .save(&inner)
        .unwrap();
    let out = dir.path().join("out");
    #[rustfmt::skip]
    ok(&["hair", "--mesh", mesh.to_str().unwrap(), "--metres-per-unit", "1",
        "--outer", outer.to_str().unwrap(),
        "--inner", inner.to_str().unwrap(), "--density", "50", "--metric", "euclidean",
        "--out", out.to_str().unwrap()]);
    let report = read_json(&out);
    assert_eq!(report["size_px"], 64, "the larger side of the masks");
    assert_eq!(report["metric"], "euclidean");
    let c = counts(&report);
    // 100 cm² × 50 /cm² ≈ 5000 hairs, all present at t = 0; the inner half stays,
    // thinned by the project's `hair.thinning` (0.55): 0.5 × 0.45 ≈ 0.225 of them, less
    // the fade of its edge toward the receding half (`hair.taper_mm`, 18 mm of its 50:
    // at most 0.85 × 18 / 50 of it gone).
    assert!((4800..=5200).contains(&c[0].1), "{c:?}");
    let kept = c[4].1 as f64 / c[0].1 as f64;
    let thinned = 0.5 * f64::from(1.0 - agesim_core::layers::hair::DEFAULT_THINNING);
    let faded = 0.85 * f64::from(agesim_core::layers::hair::DEFAULT_TAPER_MM) / 50.0;
    assert!(
        kept > thinned * (1.0 - faded) - 0.01 && kept < thinned,
        "{kept}: {c:?}"
    );
    let grey = image::open(out.join("transition.png"))
        .unwrap()
        .into_luma16();
    assert_eq!(grey.dimensions(), (64, 64));
    // Left half inner (white), right half recedes from the middle outward.
    assert_eq!(grey.get_pixel(10, 30).0[0], 65535);
    assert!(grey.get_pixel(40, 30).0[0] > grey.get_pixel(60, 30).0[0]);
}

#[test]
fn same_seed_same_files_other_seed_other_hairs() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = dir.path().join("square.obj");
    std::fs::write(&mesh, SQUARE_OBJ).unwrap();
    let run = |name: &str, seed: &str| {
        let out = dir.path().join(name);
        #[rustfmt::skip]
        ok(&["hair", "--mesh", mesh.to_str().unwrap(), "--metres-per-unit", "1",
            "--density", "30", "--seed", seed,
            "--size", "256", "--out", out.to_str().unwrap()]);
        (
            std::fs::read(out.join("transition.png")).unwrap(),
            counts(&read_json(&out)),
        )
    };
    let a = run("a", "5");
    let b = run("b", "5");
    assert_eq!(a, b);
    let c = run("c", "6");
    assert_eq!(a.0, c.0, "the texture does not depend on the seed");
}

#[test]
fn bad_inputs_fail_with_a_message_naming_them() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let missing = dir.path().join("no-such-mask.png");
    let o = agesim(&[
        "hair",
        "--outer",
        missing.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("no-such-mask.png"));
    let o = agesim(&[
        "hair",
        "--metric",
        "manhattan",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("manhattan"));
    let o = agesim(&["hair", "--density=-3", "--out", out.to_str().unwrap()]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("density"));
}

#[test]
fn an_empty_outer_mask_is_an_error_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let black = dir.path().join("black.png");
    image::GrayImage::new(16, 16).save(&black).unwrap();
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_agesim"))
        .args(["hair", "--outer", black.to_str().unwrap(), "--out"])
        .arg(dir.path().join("out"))
        .output()
        .unwrap();
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && e.contains("black.png") && e.contains("empty"),
        "{e}"
    );
}

/// The default head written as OBJ, its positions × `scale` (100: centimetres).
fn default_head_obj(scale: f32) -> String {
    agesim_core::head::mesh::obj::to_obj(&agesim_core::head::default::default_head(), |p| p * scale)
}

/// A head in centimetres or millimetres is measured, not taken for metres: the same
/// hairs as the head in metres (it used to ask for billions of hairs and fail).
#[test]
fn a_head_in_centimetres_or_millimetres_gets_the_hair_of_the_head_in_metres() {
    let dir = tempfile::tempdir().unwrap();
    let run = |name: &str, scale: f32| {
        let mesh = dir.path().join(format!("{name}.obj"));
        std::fs::write(&mesh, default_head_obj(scale)).unwrap();
        let out = dir.path().join(name);
        let o = ok(&[
            "hair",
            "--mesh",
            mesh.to_str().unwrap(),
            "--density",
            "5",
            "--size",
            "256",
            "--out",
            out.to_str().unwrap(),
        ]);
        let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
        let report = read_json(&out);
        (
            report["metres_per_unit"].as_f64().unwrap(),
            report["instances"].as_u64().unwrap(),
            stdout,
        )
    };
    let (m, hairs_m, _) = run("m", 1.0);
    let (cm, hairs_cm, said) = run("cm", 100.0);
    let (mm, hairs_mm, _) = run("mm", 1000.0);
    assert_eq!((m, cm as f32, mm as f32), (1.0, 0.01, 0.001));
    assert!(
        said.contains("metres per unit: 0.01 (centimetres"),
        "{said}"
    );
    for hairs in [hairs_cm, hairs_mm] {
        let ratio = hairs as f64 / hairs_m as f64;
        assert!((0.98..1.02).contains(&ratio), "{hairs} vs {hairs_m}");
    }
}

/// `--set hair.loss=…` on `hair`: the female pattern keeps more of the default head's hair
/// at t = 1 than the male (nothing recedes); a bad value names the field and its choices.
#[test]
fn the_hair_loss_pattern_is_set_on_the_command_line() {
    let at_one = |loss: &str| {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().display().to_string();
        let set = format!("hair.loss={loss}");
        ok(&["hair", "--density", "20", "--set", &set, "--out", &out]);
        let c = counts(&read_json(dir.path()));
        let at = |t: f64| c.iter().rev().find(|(ct, _)| *ct <= t).map_or(0, |x| x.1);
        (at(0.0), at(1.0))
    };
    let (female_0, female_1) = at_one("female");
    let (male_0, male_1) = at_one("male");
    assert!(female_1 * 2 >= female_0, "{female_1} of {female_0}");
    assert!(
        male_1 < female_1,
        "male {male_1}, female {female_1} at t = 1 (of {male_0}, {female_0})"
    );
    let bad = agesim(&["hair", "--set", "hair.loss=bald", "--out", "/nonexistent"]);
    assert!(!bad.status.success());
    let e = String::from_utf8_lossy(&bad.stderr);
    assert!(e.contains("hair.loss") && e.contains("female"), "{e}");
}

/// A UDIM head's transition is written per tile in its own UVs, named like the bakes
/// (`transition.1001.png`, …, each the size asked for): the default head re-cut into two
/// tiles gets, tile by tile, the default head's own transition where that tile's charts
/// lie. The age flags print the count at that age.
#[test]
fn a_udim_head_gets_its_transition_per_tile_in_its_own_uvs() {
    let dir = tempfile::tempdir().unwrap();
    let obj = cli::udim_head(dir.path());
    let (one, tiled) = (dir.path().join("one"), dir.path().join("tiled"));
    let single_obj = single_tile(&obj);
    ok(&[
        "hair",
        "--mesh",
        single_obj.to_str().unwrap(),
        "--size",
        "256",
        "--out",
        one.to_str().unwrap(),
    ]);
    let o = ok(&[
        "hair",
        "--mesh",
        obj.to_str().unwrap(),
        "--size",
        "256",
        "--preview",
        "--age-years",
        "70",
        "--out",
        tiled.to_str().unwrap(),
    ]);
    let printed = cli::stdout(&o);
    assert!(printed.contains("hairs at 70 years"), "{printed}");
    let report = read_json(&tiled);
    assert_eq!(report["udim_tiles"], serde_json::json!([1001, 1002]));
    assert_eq!(
        report["outputs"],
        serde_json::json!([
            "transition.1001.png",
            "transition.1002.png",
            "hair-uv.1001.png",
            "hair-uv.1002.png"
        ])
    );
    assert!(report["at_age"]["count"].as_u64().unwrap() > 0);
    assert!(!tiled.join("transition.png").exists());
    let read = |p: &Path| image::open(p).unwrap().into_luma16();
    let single = read(&one.join("transition.png"));
    let head = agesim_core::head::mesh::Mesh::load(&obj).unwrap();
    let uvs = head.file_uvs();
    assert_eq!(single.dimensions(), (256, 256));
    for n in [1001, 1002] {
        let tile = read(&tiled.join(format!("transition.{n}.png")));
        assert_eq!(tile.dimensions(), (256, 256), "tile {n}");
        // At the middle of each of this tile's triangles, the single-tile head has the
        // same age (elsewhere the tile's texels are filler: no skin of that tile lies there).
        let mut diffs = Vec::new();
        for [a, b, c] in head.triangles() {
            let uv = (uvs[a as usize] + uvs[b as usize] + uvs[c as usize]) / 3.0;
            let tile_of = 1001 + uv.x.floor() as u32 + 10 * uv.y.floor() as u32;
            if tile_of != n {
                continue;
            }
            let local = uv - uv.floor();
            let (x, y) = (
                ((local.x * 256.0) as u32).min(255),
                (((1.0 - local.y) * 256.0) as u32).min(255),
            );
            let (t, s) = (tile.get_pixel(x, y).0[0], single.get_pixel(x, y).0[0]);
            if s > 0 {
                diffs.push((t as f32 - s as f32).abs() / 65535.0);
            }
        }
        assert!(
            diffs.len() > 300,
            "tile {n}: {} hair triangles",
            diffs.len()
        );
        diffs.sort_by(f32::total_cmp);
        let (median, p90) = (diffs[diffs.len() / 2], diffs[diffs.len() * 9 / 10]);
        eprintln!(
            "tile {n}: {} texels, median {median:.4}, 90th {p90:.4}",
            diffs.len()
        );
        assert!(median < 0.02 && p90 < 0.1, "tile {n}: {median} {p90}");
    }
}

/// The UDIM head's OBJ with its second tile moved back onto the first: the same head, its
/// tiles' charts side by side in one tile.
fn single_tile(obj: &Path) -> std::path::PathBuf {
    let text = std::fs::read_to_string(obj).unwrap();
    let lines: Vec<String> = text
        .lines()
        .map(|l| match l.strip_prefix("vt ") {
            Some(rest) => {
                let mut p = rest.split_whitespace().map(|v| v.parse::<f32>().unwrap());
                let (u, v) = (p.next().unwrap(), p.next().unwrap());
                format!("vt {} {v}", if u >= 1.0 { u - 1.0 } else { u })
            }
            None => l.to_owned(),
        })
        .collect();
    let path = obj.with_file_name("single.obj");
    std::fs::write(&path, lines.join("\n")).unwrap();
    path
}
