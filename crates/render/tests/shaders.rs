//! Every `shaders/*.wgsl` parses and validates with naga (all failures reported at once),
//! and the Rust uniform struct has the size naga computes for `struct Frame` in each.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use agesim_render::{FrameUniform, shaders};

fn parse_and_validate(name: &str, source: &str) -> Result<naga::Module, String> {
    let module = naga::front::wgsl::parse_str(source)
        .map_err(|e| format!("{name}: parse error:\n{}", e.emit_to_string(source)))?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .map_err(|e| format!("{name}: validation error:\n{}", e.emit_to_string(source)))?;
    Ok(module)
}

#[test]
fn every_shader_file_validates() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shaders");
    let mut failures = Vec::new();
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "wgsl") {
            seen += 1;
            let source = std::fs::read_to_string(&path).unwrap();
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            if let Err(e) = parse_and_validate(&name, &source) {
                failures.push(e);
            }
            // The file on disk is what the crate embeds.
            assert!(
                shaders::ALL.iter().any(|(n, s)| *n == name && *s == source),
                "{name} is not listed in agesim_render::shaders::ALL"
            );
        }
    }
    assert_eq!(
        seen,
        shaders::ALL.len(),
        "shaders/ and shaders::ALL disagree"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn frame_uniform_matches_wgsl() {
    // The shaders of the frame (the blit reads no uniform).
    for (name, source) in shaders::ALL.iter().filter(|(n, _)| *n != "blit.wgsl") {
        let module = parse_and_validate(name, source).unwrap();
        let (handle, _) = module
            .types
            .iter()
            .find(|(_, ty)| ty.name.as_deref() == Some("Frame"))
            .unwrap_or_else(|| panic!("{name} has no struct Frame"));
        let mut layouter = naga::proc::Layouter::default();
        layouter.update(module.to_ctx()).unwrap();
        assert_eq!(
            layouter[handle].size as usize,
            std::mem::size_of::<FrameUniform>(),
            "struct Frame in {name} vs FrameUniform"
        );
    }
    assert_eq!(std::mem::size_of::<FrameUniform>(), 352);
}
