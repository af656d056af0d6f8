//! End-to-end tests of `agesim bake`: the real binary on real files.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;
use std::process::{Command, Output};

fn agesim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_agesim"))
        .args(args)
        .output()
        .expect("the agesim binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn default_bake_writes_the_four_files() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("maps");
    let o = agesim(&["bake", "--size", "256", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    for f in ["height.png", "height.exr", "normal.png", "bake.json"] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("bake.json")).unwrap()).unwrap();
    let range = report["height_range"].as_array().unwrap();
    let (lo, hi) = (range[0].as_f64().unwrap(), range[1].as_f64().unwrap());
    assert_eq!(
        (lo, hi),
        (0.0, 1.0),
        "large wrinkles are normalised to [0,1]"
    );
    assert_eq!(report["inputs"]["size"], 256);
    assert_eq!(report["inputs"]["gamma"], 0.4);
    assert!(report["timings_ms"]["rasterize"].as_f64().unwrap() >= 0.0);
    assert!(
        report["inputs"]["wrinkles"][0]["file"]
            .as_str()
            .unwrap()
            .contains("thesis-forehead.wrk")
    );

    let height = image::open(out.join("height.png")).unwrap();
    assert_eq!(height.color(), image::ColorType::L16);
    assert_eq!((height.width(), height.height()), (256, 256));
    let normal = image::open(out.join("normal.png")).unwrap();
    assert_eq!(normal.color(), image::ColorType::Rgb8);
    // The forehead wrinkles of the thesis example sit around u 0.42–0.56, v 0.64–0.73.
    let h = height.into_luma16();
    let crest = (0..256u32)
        .flat_map(|x| (0..256u32).map(move |y| (x, y)))
        .filter(|&(x, y)| h.get_pixel(x, y)[0] == 65535)
        .map(|(x, y)| ((x as f32 + 0.5) / 256.0, 1.0 - (y as f32 + 0.5) / 256.0))
        .next()
        .unwrap();
    assert!(
        (0.38..0.6).contains(&crest.0) && (0.6..0.76).contains(&crest.1),
        "crest at {crest:?}"
    );
}

#[test]
fn malformed_wrinkle_file_reports_every_error_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.wrk");
    std::fs::write(
        &bad,
        "!\nma=0.1;0.2\nmb=0.3;0.2\nn=1\nwidth=2\n!\nma=0.5;0.5\n",
    )
    .unwrap();
    let out = dir.path().join("maps");
    let o = agesim(&[
        "bake",
        "--wrinkles",
        bad.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    let err = stderr(&o);
    let b = bad.display();
    assert!(
        err.contains(&format!("{b}:4:3: value out of range")),
        "{err}"
    );
    assert!(err.contains(&format!("{b}:5:1: unknown key")), "{err}");
    assert!(err.contains(&format!("{b}:6:1: missing key")), "{err}");
    assert!(!out.exists(), "no output directory on malformed input");
}

#[test]
fn oversized_maps_are_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("maps");
    let o = agesim(&["bake", "--size", "80000", "--out", out.to_str().unwrap()]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("80000"), "{}", stderr(&o));
    assert!(!out.exists());
}

#[test]
fn unreadable_mask_and_missing_file_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let mask = dir.path().join("mask.png");
    std::fs::write(&mask, b"not an image").unwrap();
    let out = dir.path().join("maps");
    let o = agesim(&[
        "bake",
        "--mask",
        mask.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("mask.png"), "{}", stderr(&o));
    let o = agesim(&[
        "bake",
        "--wrinkles",
        "/no/such.wrk",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("/no/such.wrk"), "{}", stderr(&o));
    assert!(!out.exists());
}

#[test]
fn invalid_numbers_are_refused_before_any_output() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("maps");
    for args in [["--gamma", "0"], ["--normal-strength", "-1"]] {
        let mut all = vec!["bake", "--size", "16", "--out", out.to_str().unwrap()];
        all.extend(args);
        let o = agesim(&all);
        assert!(!o.status.success(), "{args:?} accepted");
        assert!(!out.exists());
    }
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
    let exr = exr::prelude::read_first_flat_layer_from_file(out.join("height.exr")).unwrap();
    assert!(
        exr.layer_data.channel_data.list[0]
            .sample_data
            .values_as_f32()
            .all(|h| h == 0.0)
    );
    assert!(Path::new(&out.join("normal.png")).is_file());
}

#[test]
fn no_subcommand_prints_help() {
    let o = agesim(&[]);
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).contains("bake"));
}
