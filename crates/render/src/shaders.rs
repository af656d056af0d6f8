//! The WGSL sources of `shaders/`, the one place they are loaded (`include_str!`), so the
//! binary runs from any folder and the validation test sees exactly what the GPU gets.
//! `frame.wgsl` (the frame's uniform) and `common.wgsl` (the helpers both use: tone curve,
//! sRGB, octahedral packing, graying, cavity) are written once and put in front of the two
//! shaders that read them.

/// `struct Frame` and its binding, shared by the skin and hair shaders.
pub const FRAME_WGSL: &str = include_str!("../../../shaders/frame.wgsl");

/// The helpers shared by the skin and hair shaders; no bindings, so a test can wrap them in
/// a compute shader (`tests/twins.rs`).
pub const COMMON_WGSL: &str = include_str!("../../../shaders/common.wgsl");

/// The skin: the surface pass (the mesh into a G-buffer) and the shading pass (POM, fine
/// wrinkles, micro-relief, skin lighting, docs/models.md §10), after `frame.wgsl` and
/// `common.wgsl`.
pub const SKIN_WGSL: &str = concat!(
    include_str!("../../../shaders/frame.wgsl"),
    include_str!("../../../shaders/common.wgsl"),
    include_str!("../../../shaders/skin.wgsl")
);
/// The hair pass: instanced ribbons, graying, Kajiya–Kay (docs/models.md §9), after
/// `frame.wgsl` and `common.wgsl`.
pub const HAIR_WGSL: &str = concat!(
    include_str!("../../../shaders/frame.wgsl"),
    include_str!("../../../shaders/common.wgsl"),
    include_str!("../../../shaders/hair.wgsl")
);

/// A texture onto a viewport as it is ([`crate::Blit`]).
pub const BLIT_WGSL: &str = include_str!("../../../shaders/blit.wgsl");

/// Every file of `shaders/` as (file name, its text), for tests and tools.
pub const FILES: &[(&str, &str)] = &[
    ("frame.wgsl", FRAME_WGSL),
    ("common.wgsl", COMMON_WGSL),
    ("skin.wgsl", include_str!("../../../shaders/skin.wgsl")),
    ("hair.wgsl", include_str!("../../../shaders/hair.wgsl")),
    ("blit.wgsl", BLIT_WGSL),
];

/// Every shader module as the GPU gets it, (name, source).
pub const MODULES: &[(&str, &str)] = &[
    ("skin", SKIN_WGSL),
    ("hair", HAIR_WGSL),
    ("blit", BLIT_WGSL),
];
