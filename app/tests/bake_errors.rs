//! End-to-end tests of `agesim bake` on bad input: every error names the file, line,
//! field or flag, and nothing is written.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod cli;

use cli::{agesim, stderr};

#[test]
fn malformed_wrinkle_file_reports_every_error_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.wrk");
    std::fs::write(
        &bad,
        "!\nma=0.1;0.2\nmb=0.3;0.2\nn=0\nwidth=2\n!\nma=0.5;0.5\n",
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
    // Each problem said once (not again as the error's cause).
    assert_eq!(err.matches("unknown key").count(), 1, "{err}");
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
fn bad_project_input_names_the_field_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("maps");
    let project = dir.path().join("p.agesim.json");
    std::fs::write(&project, r#"{"version": 1, "pores": {"cuont": 3}}"#).unwrap();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["--project", project.to_str().unwrap()], "pores.cuont"),
        (
            vec!["--set", "pores.radius_mm.mean=7"],
            "pores.radius_mm.mean",
        ),
        (vec!["--set", "noise.octaves=3"], "noise.octaves"),
        (vec!["--set", "nonsense"], "PATH=VALUE"),
        (vec!["--preset", "wrinkly"], "article-fig14"),
        (
            vec!["--project", "/no/such.agesim.json"],
            "/no/such.agesim.json",
        ),
    ];
    for (args, needle) in cases {
        let mut all = vec!["bake", "--size", "32", "--out", out.to_str().unwrap()];
        all.extend(&args);
        let o = agesim(&all);
        assert!(!o.status.success(), "{args:?} accepted");
        assert!(stderr(&o).contains(needle), "{args:?}: {}", stderr(&o));
        assert!(!out.exists(), "{args:?} wrote output");
    }
}

#[test]
fn flag_errors_quote_the_flag_and_the_documented_range() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x");
    let o = agesim(&["bake", "--gamma", "nan", "--out", out.to_str().unwrap()]);
    let e = stderr(&o);
    assert!(
        !o.status.success() && e.contains("--gamma NaN") && !e.contains("null"),
        "{e}"
    );
    let o = agesim(&["bake", "--size=-5", "--out", out.to_str().unwrap()]);
    let e = stderr(&o);
    assert!(!o.status.success() && e.contains("1..=16384"), "{e}");
    assert!(!e.contains("4294967295"), "{e}");
}
