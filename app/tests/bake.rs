//! End-to-end tests of `agesim bake`: the real binary on real files.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod cli;

use cli::{agesim, stderr};

use std::path::Path;
use std::process::Command;

/// The bake.json written into `out`.
fn bake_json(out: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(out.join("bake.json")).unwrap()).unwrap()
}

#[test]
fn default_bake_writes_the_texture_set() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("maps");
    let o = agesim(&[
        "bake",
        "--size",
        "256",
        "--age",
        "1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    for f in [
        "head_Height.png",
        "head_Height.exr",
        "head_Normal.png",
        "head_BaseColor.png",
        "head_Roughness.png",
        "head_AO.png",
        "bake.json",
    ] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    // The aged base colour at the maps' size.
    let albedo = image::open(out.join("head_BaseColor.png")).unwrap();
    assert_eq!((albedo.width(), albedo.height()), (256, 256));
    let report: serde_json::Value = bake_json(&out);
    assert!(
        report["outputs"]
            .as_array()
            .unwrap()
            .contains(&serde_json::json!("head_BaseColor.png")),
        "{report}"
    );
    let range = report["height_range"].as_array().unwrap();
    let (lo, hi) = (range[0].as_f64().unwrap(), range[1].as_f64().unwrap());
    // Cut in: the deepest point of the normalised depth at full age is −1; the folds'
    // raised cheek sides the only heights above the skin.
    // (The normalisation multiplies by 1/depth: −1 within f32 rounding.)
    assert!(
        (lo + 1.0).abs() < 1e-6,
        "large wrinkles at full age are normalised to a depth of 1: {lo}"
    );
    assert!((0.0..0.6).contains(&hi), "raised fold sides up to {hi}");
    assert_eq!(report["inputs"]["age_t"], 1.0);
    assert_eq!(report["inputs"]["size"], 256);
    assert_eq!(report["inputs"]["gamma"], 0.7);
    assert!(report["timings_ms"]["bake"].as_f64().unwrap() >= 0.0);
    assert_eq!(report["inputs"]["layers"], serde_json::json!(["large"]));
    assert!(
        report["inputs"]["wrinkles"][0]["file"]
            .as_str()
            .unwrap()
            .contains("forehead.wrk")
    );

    let height = image::open(out.join("head_Height.png")).unwrap();
    assert_eq!(height.color(), image::ColorType::L16);
    assert_eq!((height.width(), height.height()), (256, 256));
    let normal = image::open(out.join("head_Normal.png")).unwrap();
    assert_eq!(normal.color(), image::ColorType::Rgb8);
    // The default files are the default head's: every wrinkle group, with its mask.
    assert_eq!(report["inputs"]["wrinkles"].as_array().unwrap().len(), 8);
    assert_eq!(report["inputs"]["mask"], "assets/masks/wrinkles.png");
    // Wrinkles on the forehead (u 0.43–0.56, v 0.76–0.82 on the default head's layout),
    // none on the back of the head (u < 0.1).
    let h = height.into_luma16();
    let at = |u: f32, v: f32| h.get_pixel((u * 256.0) as u32, ((1.0 - v) * 256.0) as u32)[0];
    // Unwrinkled skin is height 0, the wrinkles below it.
    let skin = at(0.05, 0.1);
    let forehead = (0..20)
        .flat_map(|i| {
            [0.765, 0.772, 0.78, 0.788, 0.796, 0.804].map(|v| (0.43 + i as f32 * 0.006, v))
        })
        .map(|(u, v)| at(u, v) as u32)
        .min()
        .unwrap();
    assert!(
        forehead + 20000 < u32::from(skin),
        "forehead crease {forehead}, skin {skin}"
    );
    assert!((0..50).all(|i| at(0.05, 0.1 + i as f32 * 0.016) == skin));
}

#[test]
fn thesis_example_is_cut_into_its_forehead() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("maps");
    let wrk = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/wrinkles/thesis-forehead.wrk"
    );
    let o = agesim(&[
        "bake",
        "--wrinkles",
        wrk,
        "--size",
        "256",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let report: serde_json::Value = bake_json(&out);
    assert_eq!(
        report["inputs"]["mask"],
        serde_json::Value::Null,
        "own files: no default mask"
    );
    let h = image::open(out.join("head_Height.png"))
        .unwrap()
        .into_luma16();
    // The deepest point (0: the wrinkles are cut in) lies on the forehead.
    let deepest = (0..256u32)
        .flat_map(|x| (0..256u32).map(move |y| (x, y)))
        .filter(|&(x, y)| h.get_pixel(x, y)[0] == 0)
        .map(|(x, y)| ((x as f32 + 0.5) / 256.0, 1.0 - (y as f32 + 0.5) / 256.0))
        .next()
        .unwrap();
    assert!(
        (0.4..0.6).contains(&deepest.0) && (0.76..0.86).contains(&deepest.1),
        "deepest at {deepest:?}"
    );
}

#[test]
fn mask_limits_the_wrinkles() {
    let dir = tempfile::tempdir().unwrap();
    // A black mask: nothing survives.
    let mask = dir.path().join("black.png");
    image::GrayImage::new(8, 8).save(&mask).unwrap();
    let out = dir.path().join("maps");
    let o = agesim(&[
        "bake",
        "--size",
        "64",
        "--mask",
        mask.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let exr = exr::prelude::read_first_flat_layer_from_file(out.join("head_Height.exr")).unwrap();
    assert!(
        exr.layer_data.channel_data.list[0]
            .sample_data
            .values_as_f32()
            .all(|h| h == 0.0)
    );
    assert!(Path::new(&out.join("head_Normal.png")).is_file());
}

#[test]
fn help_lists_the_subcommands() {
    let o = agesim(&["--help"]);
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).contains("bake"));
}

/// The f32 heights of a bake's head_Height.exr.
fn exr_heights(dir: &Path) -> Vec<f32> {
    let exr = exr::prelude::read_first_flat_layer_from_file(dir.join("head_Height.exr")).unwrap();
    exr.layer_data.channel_data.list[0]
        .sample_data
        .values_as_f32()
        .collect()
}

#[test]
fn every_preset_bakes_micro_relief() {
    let dir = tempfile::tempdir().unwrap();
    for preset in ["fine", "rough", "goose-skin", "deep-pores", "article-fig14"] {
        let out = dir.path().join(preset);
        let o = agesim(&[
            "bake",
            "--preset",
            preset,
            "--size",
            "128",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{preset}: {}", stderr(&o));
        let report: serde_json::Value = bake_json(&out);
        let layers = report["inputs"]["layers"].as_array().unwrap();
        assert!(
            layers.contains(&"pores".into()) && !layers.contains(&"large".into()),
            "{preset}: {layers:?}"
        );
        let h = exr_heights(&out);
        let (lo, hi) = h
            .iter()
            .fold((f32::MAX, f32::MIN), |(lo, hi), &v| (lo.min(v), hi.max(v)));
        assert!(hi - lo > 0.1, "{preset}: flat map {lo}..{hi}");
        if preset == "goose-skin" {
            assert!(hi > 0.1, "goose skin has raised bumps: max {hi}");
        } else {
            assert!(lo < -0.5, "{preset}: pores go into the skin: min {lo}");
        }
    }
}

#[test]
fn bake_json_alone_reproduces_the_bake() {
    let dir = tempfile::tempdir().unwrap();
    let first = dir.path().join("first");
    let o = agesim(&[
        "bake",
        "--preset",
        "rough",
        "--layers",
        "all",
        "--set",
        "pores.count=300",
        "--seed",
        "7",
        "--size",
        "96",
        "--out",
        first.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let report: serde_json::Value = bake_json(&first);
    assert_eq!(report["seed"], 7);
    assert_eq!(report["project"]["pores"]["count"], 300);
    assert_eq!(report["project"]["large"]["enabled"], true);
    let project = dir.path().join("again.agesim.json");
    std::fs::write(&project, serde_json::to_string(&report["project"]).unwrap()).unwrap();
    let second = dir.path().join("second");
    let o = agesim(&[
        "bake",
        "--project",
        project.to_str().unwrap(),
        "--size",
        "96",
        "--out",
        second.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        std::fs::read(first.join("head_Height.exr")).unwrap(),
        std::fs::read(second.join("head_Height.exr")).unwrap()
    );
    assert_eq!(
        std::fs::read(first.join("head_Normal.png")).unwrap(),
        std::fs::read(second.join("head_Normal.png")).unwrap()
    );
}

#[test]
fn layers_select_what_is_baked() {
    let dir = tempfile::tempdir().unwrap();
    let bake = |layers: &str| {
        let out = dir.path().join(layers);
        let o = agesim(&[
            "bake",
            "--layers",
            layers,
            "--size",
            "64",
            "--set",
            "pores.count=200",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        exr_heights(&out)
    };
    let (large, micro, all) = (bake("large"), bake("micro"), bake("all"));
    // all = micro + depth·large, pixel for pixel (large.depth defaults to 1).
    for ((a, m), l) in all.iter().zip(&micro).zip(&large) {
        assert!((a - (m + l)).abs() < 1e-5, "{a} vs {m} + {l}");
    }
    // Large wrinkles are cut in; only the folds' raised sides rise, less than the creases sink.
    let (lo, hi) = large
        .iter()
        .fold((0.0f32, 0.0f32), |(l, h), &x| (l.min(x), h.max(x)));
    assert!(
        lo < -0.5 && hi < 0.6 && hi < -lo,
        "large wrinkles {lo}..{hi}"
    );
    assert!(micro.iter().any(|&h| h < -0.1));
}

#[test]
fn tiled_bake_matches_across_opposite_edges() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("tile");
    let o = agesim(&[
        "bake",
        "--preset",
        "rough",
        "--tile",
        "--size",
        "128",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let h = exr_heights(&out);
    let n = 128;
    // Continuity across the seam: the jump from the last column to the first is no larger
    // than the largest jump between neighbouring columns inside the map.
    let jump = |a: usize, b: usize| {
        (0..n)
            .map(|y| (h[y * n + a] - h[y * n + b]).abs())
            .sum::<f32>()
    };
    let inside = (1..n).map(|x| jump(x - 1, x)).fold(0.0, f32::max);
    assert!(
        jump(n - 1, 0) <= inside,
        "seam jump {} vs largest inner {}",
        jump(n - 1, 0),
        inside
    );
    let rows = |a: usize, b: usize| {
        (0..n)
            .map(|x| (h[a * n + x] - h[b * n + x]).abs())
            .sum::<f32>()
    };
    let inside_rows = (1..n).map(|y| rows(y - 1, y)).fold(0.0, f32::max);
    assert!(rows(n - 1, 0) <= inside_rows);
}

#[test]
fn bake_json_reproduces_the_bake_from_any_directory() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("w")).unwrap();
    std::fs::copy(
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../assets/wrinkles/forehead.wrk"
        ),
        dir.path().join("w/forehead.wrk"),
    )
    .unwrap();
    // A relative --wrinkles, resolved against the working directory.
    let o = Command::new(env!("CARGO_BIN_EXE_agesim"))
        .current_dir(dir.path())
        .args([
            "bake",
            "--wrinkles",
            "w/forehead.wrk",
            "--size",
            "64",
            "--age-years",
            "60",
        ])
        .args(["--out", "first"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("first/bake.json")).unwrap())
            .unwrap();
    let project = dir.path().join("first/again.agesim.json");
    std::fs::write(&project, report["project"].to_string()).unwrap();
    // Baked again from elsewhere, from the saved project alone.
    let o = Command::new(env!("CARGO_BIN_EXE_agesim"))
        .current_dir("/")
        .args([
            "bake",
            "--project",
            project.to_str().unwrap(),
            "--size",
            "64",
        ])
        .args(["--age", &report["inputs"]["age_t"].to_string()])
        .args(["--out", dir.path().join("second").to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    for f in ["head_Height.exr", "head_Height.png", "head_Normal.png"] {
        assert_eq!(
            std::fs::read(dir.path().join("first").join(f)).unwrap(),
            std::fs::read(dir.path().join("second").join(f)).unwrap(),
            "{f} differs"
        );
    }
}

#[test]
fn older_bakes_are_deeper() {
    let dir = tempfile::tempdir().unwrap();
    let range = |years: &str| {
        let out = dir.path().join(years);
        let o = agesim(&[
            "bake",
            "--size",
            "128",
            "--age-years",
            years,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let r: serde_json::Value = bake_json(&out);
        // The deepest point (the heights are cut in: below zero).
        -r["height_range"][0].as_f64().unwrap()
    };
    let (a, b, c) = (range("30"), range("50"), range("80"));
    assert!(a < b && b < c, "{a} {b} {c}");
    // The deepest fold at full depth (to the float's last bit: the map is stored in f32).
    assert!((c - 1.0).abs() < 1e-6, "{c}");
    let o = agesim(&[
        "bake",
        "--age",
        "1.5",
        "--out",
        dir.path().join("x").to_str().unwrap(),
    ]);
    assert!(
        !o.status.success() && stderr(&o).contains("--age 1.5"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn nothing_asked_is_never_dropped_and_nothing_baked_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let empty = dir.path().join("empty.wrk");
    std::fs::write(&empty, "# only a comment\n").unwrap();
    let out = dir.path().join("out");
    let o = agesim(&[
        "bake",
        "--wrinkles",
        empty.to_str().unwrap(),
        "--size",
        "32",
        "--out",
        out.to_str().unwrap(),
    ]);
    let e = stderr(&o);
    assert!(
        !o.status.success() && e.contains("nothing to bake") && e.contains("empty.wrk"),
        "{e}"
    );
    assert!(!out.exists(), "nothing was written");
    // A micro-relief field given with --set bakes the micro-relief (it is not ignored).
    let o = agesim(&[
        "bake",
        "--set",
        "pores.count=50",
        "--size",
        "64",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let r: serde_json::Value = bake_json(&out);
    assert_eq!(r["inputs"]["pores"], 50, "{r}");
    // --wrinkles with a skin-patch preset turns the large layer on.
    let o = agesim(&[
        "bake",
        "--preset",
        "fine",
        "--wrinkles",
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../assets/wrinkles/forehead.wrk"
        ),
        "--size",
        "64",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let r: serde_json::Value = bake_json(&out);
    assert!(
        r["inputs"]["layers"]
            .as_array()
            .unwrap()
            .contains(&serde_json::json!("large")),
        "{r}"
    );
}

/// Files in `dir` and their bytes.
fn snapshot_dir(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .map(|p| {
            let bytes = if p.is_dir() {
                Vec::new()
            } else {
                std::fs::read(&p).unwrap()
            };
            (p.file_name().unwrap().to_string_lossy().into_owned(), bytes)
        })
        .collect();
    v.sort();
    v
}

#[test]
fn an_output_set_is_all_old_or_all_new() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("maps");
    let o = agesim(&["bake", "--size", "64", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let old = snapshot_dir(&out);
    assert_eq!(old.len(), 7);

    // A later output that cannot be written (head_Normal.png is a directory): nothing changes.
    std::fs::remove_file(out.join("head_Normal.png")).unwrap();
    std::fs::create_dir(out.join("head_Normal.png")).unwrap();
    let before = snapshot_dir(&out.join("..").join("maps"));
    let o = agesim(&["bake", "--size", "96", "--out", out.to_str().unwrap()]);
    assert!(!o.status.success());
    let after: Vec<(String, Vec<u8>)> = snapshot_dir(&out);
    assert_eq!(
        before
            .iter()
            .filter(|(n, _)| n != "head_Normal.png")
            .count(),
        6
    );
    for (name, bytes) in before.iter().filter(|(n, _)| n != "head_Normal.png") {
        let now = after.iter().find(|(n, _)| n == name).unwrap();
        assert_eq!(&now.1, bytes, "{name} was replaced although the set failed");
    }
    assert!(
        after.iter().all(|(n, _)| !n.ends_with(".tmp")),
        "{:?}",
        after.iter().map(|x| &x.0).collect::<Vec<_>>()
    );
    std::fs::remove_dir(out.join("head_Normal.png")).unwrap();
    std::fs::write(
        out.join("head_Normal.png"),
        &old.iter().find(|(n, _)| n == "head_Normal.png").unwrap().1,
    )
    .unwrap();

    // SIGINT while the maps are being written: the old set stays, no temporary is left.
    #[cfg(target_os = "linux")]
    {
        let mut child = Command::new(env!("CARGO_BIN_EXE_agesim"))
            .args(["bake", "--size", "8192", "--out", out.to_str().unwrap()])
            .stderr(std::process::Stdio::null())
            .stdout(std::process::Stdio::null())
            .spawn()
            .unwrap();
        let start = std::time::Instant::now();
        let mut interrupted = false;
        while start.elapsed() < std::time::Duration::from_secs(120) {
            let tmp = std::fs::read_dir(&out)
                .unwrap()
                .any(|e| e.unwrap().file_name().to_string_lossy().ends_with(".tmp"));
            if tmp {
                // SAFETY: sending a signal to our own child process.
                unsafe { libc::kill(child.id() as i32, libc::SIGINT) };
                interrupted = true;
                break;
            }
            if child.try_wait().unwrap().is_some() {
                break;
            }
            std::thread::sleep(std::time::Duration::from_millis(2));
        }
        let status = child.wait().unwrap();
        assert!(
            interrupted,
            "the bake finished before it could be interrupted"
        );
        assert!(!status.success());
        assert_eq!(
            snapshot_dir(&out),
            old,
            "the old set must be intact, with no temporary"
        );
    }
}

#[test]
fn every_exr_compression_reads_back_the_same_heights() {
    let dir = tempfile::tempdir().unwrap();
    let mut heights = Vec::new();
    for c in ["rle", "none", "zip"] {
        let out = dir.path().join(c);
        let o = agesim(&[
            "bake",
            "--size",
            "96",
            "--exr-compression",
            c,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        assert_eq!(bake_json(&out)["inputs"]["exr_compression"], c);
        let exr =
            exr::prelude::read_first_flat_layer_from_file(out.join("head_Height.exr")).unwrap();
        heights.push(
            exr.layer_data.channel_data.list[0]
                .sample_data
                .values_as_f32()
                .collect::<Vec<f32>>(),
        );
    }
    assert!(heights[0].iter().any(|&h| h != 0.0));
    assert_eq!(heights[0], heights[1], "none is lossless");
    assert_eq!(heights[0], heights[2], "zip is lossless");
}

/// The maps are named as a texture set (`<set>_BaseColor.png`, …) or with agesim's own
/// names; a set name with a folder in it is refused before anything is written.
#[test]
fn the_maps_are_named_as_a_texture_set_or_as_agesim_named_them() {
    let dir = tempfile::tempdir().unwrap();
    let names = |extra: &[&str]| {
        let out = dir.path().join(extra.join("-"));
        let mut args = vec!["bake", "--size", "64", "--out", out.to_str().unwrap()];
        args.extend(extra);
        let o = agesim(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let mut files: Vec<String> = std::fs::read_dir(&out)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        files.sort();
        files
    };
    assert_eq!(
        names(&["--texture-set", "face"]),
        [
            "bake.json",
            "face_AO.png",
            "face_BaseColor.png",
            "face_Height.exr",
            "face_Height.png",
            "face_Normal.png",
            "face_Roughness.png"
        ]
    );
    assert_eq!(
        names(&["--names", "agesim"]),
        [
            "albedo.png",
            "ao.png",
            "bake.json",
            "height.exr",
            "height.png",
            "normal.png",
            "roughness.png"
        ]
    );
    let out = dir.path().join("bad");
    let o = agesim(&[
        "bake",
        "--texture-set",
        "a/b",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("--texture-set `a/b`"), "{}", stderr(&o));
    assert!(!out.exists());
}

/// The roughness map: the skin's roughness at the age (old skin is drier: rougher at 80
/// than at 25), rougher still on the floors of the creases, where the occlusion map is
/// dark.
#[test]
fn the_roughness_map_dries_with_age_and_follows_the_creases() {
    let dir = tempfile::tempdir().unwrap();
    let bake = |years: &str| {
        let out = dir.path().join(years);
        let o = agesim(&[
            "bake",
            "--size",
            "256",
            "--age-years",
            years,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let grey = |name: &str| image::open(out.join(name)).unwrap().into_luma8().into_raw();
        (grey("head_Roughness.png"), grey("head_AO.png"))
    };
    let median = |v: &[u8]| {
        let mut v = v.to_vec();
        v.sort_unstable();
        v[v.len() / 2]
    };
    let (young, _) = bake("25");
    let (old, ao) = bake("80");
    assert!(
        median(&old) > median(&young) + 15,
        "{} → {}",
        median(&young),
        median(&old)
    );
    let open = median(&old);
    let creases: Vec<u8> = old
        .iter()
        .zip(&ao)
        .filter(|(_, a)| **a < 200)
        .map(|(r, _)| *r)
        .collect();
    assert!(creases.len() > 30, "{} crease texels", creases.len());
    assert!(
        creases.iter().all(|&r| r > open),
        "crease roughness {creases:?} against {open}"
    );
}
