//! The WGSL sources of `shaders/`, the one place they are loaded (`include_str!`), so the
//! binary runs from any folder and the validation test sees exactly what the GPU gets.

/// The skin: the surface pass (the mesh into a G-buffer) and the shading pass (POM, fine
/// wrinkles, micro-relief, skin lighting, SPEC §5).
pub const SKIN_WGSL: &str = include_str!("../../../shaders/skin.wgsl");
/// The hair pass: instanced ribbons, graying, Kajiya–Kay (SPEC §6).
pub const HAIR_WGSL: &str = include_str!("../../../shaders/hair.wgsl");

/// A texture onto a viewport as it is ([`crate::Blit`]).
pub const BLIT_WGSL: &str = include_str!("../../../shaders/blit.wgsl");

/// Every shader as (file name, source), for tests and tools.
pub const ALL: &[(&str, &str)] = &[
    ("skin.wgsl", SKIN_WGSL),
    ("hair.wgsl", HAIR_WGSL),
    ("blit.wgsl", BLIT_WGSL),
];
