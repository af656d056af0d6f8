//! The default assets compiled into the binary, so every caller (command line, editor, tests) works from any directory.
//! Each is a file under `assets/`; the name printed in diagnostics and `bake.json` is its
//! path in the repository.

/// The default wrinkle description files of the default head: (repository path, contents).
/// `forehead.wrk` contains [T]'s own example (docs/models.md §3), which is also kept unchanged as
/// `assets/wrinkles/thesis-forehead.wrk` (not in this list, so it is not counted twice).
pub const WRINKLE_FILES: &[(&str, &str)] = &[
    (
        "assets/wrinkles/forehead.wrk",
        include_str!("../../../assets/wrinkles/forehead.wrk"),
    ),
    (
        "assets/wrinkles/glabella.wrk",
        include_str!("../../../assets/wrinkles/glabella.wrk"),
    ),
    (
        "assets/wrinkles/crows-feet.wrk",
        include_str!("../../../assets/wrinkles/crows-feet.wrk"),
    ),
    (
        "assets/wrinkles/under-eye.wrk",
        include_str!("../../../assets/wrinkles/under-eye.wrk"),
    ),
    (
        "assets/wrinkles/nasolabial.wrk",
        include_str!("../../../assets/wrinkles/nasolabial.wrk"),
    ),
    (
        "assets/wrinkles/perioral.wrk",
        include_str!("../../../assets/wrinkles/perioral.wrk"),
    ),
    (
        "assets/wrinkles/marionette.wrk",
        include_str!("../../../assets/wrinkles/marionette.wrk"),
    ),
    (
        "assets/wrinkles/neck.wrk",
        include_str!("../../../assets/wrinkles/neck.wrk"),
    ),
];

/// The default large-wrinkle mask of the default head: (repository path, PNG bytes).
pub const WRINKLE_MASK: (&str, &[u8]) = (
    "assets/masks/wrinkles.png",
    include_bytes!("../../../assets/masks/wrinkles.png"),
);

/// The project presets of `assets/presets/`: (name, repository path, contents).
pub const PRESETS: &[(&str, &str, &str)] = &[
    (
        "fine",
        "assets/presets/fine.agesim.json",
        include_str!("../../../assets/presets/fine.agesim.json"),
    ),
    (
        "rough",
        "assets/presets/rough.agesim.json",
        include_str!("../../../assets/presets/rough.agesim.json"),
    ),
    (
        "goose-skin",
        "assets/presets/goose-skin.agesim.json",
        include_str!("../../../assets/presets/goose-skin.agesim.json"),
    ),
    (
        "deep-pores",
        "assets/presets/deep-pores.agesim.json",
        include_str!("../../../assets/presets/deep-pores.agesim.json"),
    ),
    (
        "article-fig14",
        "assets/presets/article-fig14.agesim.json",
        include_str!("../../../assets/presets/article-fig14.agesim.json"),
    ),
];

/// The default head's hair masks: (repository path, PNG bytes) of the outer (hair at t = 0)
/// and inner (hair left at t = 1) regions.
pub const HAIR_OUTER_MASK: (&str, &[u8]) = (
    "assets/masks/hair-outer.png",
    include_bytes!("../../../assets/masks/hair-outer.png"),
);
pub const HAIR_INNER_MASK: (&str, &[u8]) = (
    "assets/masks/hair-inner.png",
    include_bytes!("../../../assets/masks/hair-inner.png"),
);

/// The order the default head's hair goes in (white: last; docs/models.md §9 "order"),
/// used with the two masks above.
pub const HAIR_ORDER_MASK: (&str, &[u8]) = (
    "assets/masks/hair-order.png",
    include_bytes!("../../../assets/masks/hair-order.png"),
);

/// [`HAIR_ORDER_MASK`] decoded (once); `None` should it not decode (the tests check it).
pub fn hair_order_mask() -> Option<&'static crate::maps::mask::Mask> {
    static MASK: std::sync::OnceLock<Option<crate::maps::mask::Mask>> = std::sync::OnceLock::new();
    MASK.get_or_init(|| {
        crate::maps::mask::Mask::decode(HAIR_ORDER_MASK.1, std::path::Path::new(HAIR_ORDER_MASK.0))
            .ok()
    })
    .as_ref()
}

/// A shipped preset by name: (repository path, contents).
pub fn preset(name: &str) -> Option<(&'static str, &'static str)> {
    PRESETS
        .iter()
        .find(|(n, _, _)| *n == name)
        .map(|(_, path, text)| (*path, *text))
}

/// The names of the shipped presets.
pub fn preset_names() -> Vec<&'static str> {
    PRESETS.iter().map(|(n, _, _)| *n).collect()
}
