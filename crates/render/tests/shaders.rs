//! Every shader module parses and validates with naga (all failures reported at once),
//! every `shaders/*.wgsl` is embedded, and the Rust uniform struct matches `struct Frame`
//! member for member: names, offsets and size from naga's layout.
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
fn every_shader_validates_and_every_file_is_embedded() {
    let mut failures: Vec<String> = shaders::MODULES
        .iter()
        .filter_map(|(name, source)| parse_and_validate(name, source).err())
        .collect();
    // frame.wgsl and common.wgsl alone too: their errors then name their own lines.
    for (name, source) in [
        ("frame.wgsl", shaders::FRAME_WGSL),
        ("common.wgsl", shaders::COMMON_WGSL),
    ] {
        if let Err(e) = parse_and_validate(name, source) {
            failures.push(e);
        }
    }
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shaders");
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "wgsl") {
            seen += 1;
            let source = std::fs::read_to_string(&path).unwrap();
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            // The file on disk is what the crate embeds.
            assert!(
                shaders::FILES
                    .iter()
                    .any(|(n, s)| *n == name && *s == source),
                "{name} is not listed in agesim_render::shaders::FILES"
            );
        }
    }
    assert_eq!(
        seen,
        shaders::FILES.len(),
        "shaders/ and shaders::FILES disagree"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// `struct Frame` as naga lays it out in `module`: (member name, offset), and the size.
fn frame_layout(name: &str, module: &naga::Module) -> (Vec<(String, usize)>, usize) {
    let (handle, ty) = module
        .types
        .iter()
        .find(|(_, ty)| ty.name.as_deref() == Some("Frame"))
        .unwrap_or_else(|| panic!("{name} has no struct Frame"));
    let naga::TypeInner::Struct { members, .. } = &ty.inner else {
        panic!("{name}: Frame is not a struct");
    };
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).unwrap();
    let members = members
        .iter()
        .map(|m| (m.name.clone().unwrap_or_default(), m.offset as usize))
        .collect();
    (members, layouter[handle].size as usize)
}

#[test]
fn frame_uniform_matches_wgsl_member_for_member() {
    let rust: Vec<(String, usize)> = FrameUniform::MEMBERS
        .iter()
        .map(|&(n, o)| (n.to_owned(), o))
        .collect();
    // The shaders that read the frame (the blit reads no uniform).
    for (name, source) in shaders::MODULES.iter().filter(|(n, _)| *n != "blit") {
        let module = parse_and_validate(name, source).unwrap();
        let (members, size) = frame_layout(name, &module);
        assert_eq!(members, rust, "struct Frame in {name} vs FrameUniform");
        assert_eq!(size, std::mem::size_of::<FrameUniform>(), "size in {name}");
    }
    assert_eq!(std::mem::size_of::<FrameUniform>(), 416);
}

#[test]
fn frame_is_written_once() {
    for (name, text) in shaders::FILES.iter().filter(|(n, _)| *n != "frame.wgsl") {
        assert!(
            !text.contains("struct Frame"),
            "{name} declares its own struct Frame"
        );
    }
}
