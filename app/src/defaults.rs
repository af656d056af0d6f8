//! The default assets compiled into the binary, so `agesim bake` works from any directory.
//! Each is a file under `assets/`; the name printed in diagnostics and `bake.json` is its
//! path in the repository.

/// The default wrinkle description files: (repository path, contents).
pub const WRINKLE_FILES: &[(&str, &str)] = &[(
    "assets/wrinkles/thesis-forehead.wrk",
    include_str!("../../assets/wrinkles/thesis-forehead.wrk"),
)];

/// The project presets of `assets/presets/`: (name, repository path, contents).
pub const PRESETS: &[(&str, &str, &str)] = &[
    (
        "fine",
        "assets/presets/fine.agesim.json",
        include_str!("../../assets/presets/fine.agesim.json"),
    ),
    (
        "rough",
        "assets/presets/rough.agesim.json",
        include_str!("../../assets/presets/rough.agesim.json"),
    ),
    (
        "goose-skin",
        "assets/presets/goose-skin.agesim.json",
        include_str!("../../assets/presets/goose-skin.agesim.json"),
    ),
    (
        "deep-pores",
        "assets/presets/deep-pores.agesim.json",
        include_str!("../../assets/presets/deep-pores.agesim.json"),
    ),
    (
        "article-fig14",
        "assets/presets/article-fig14.agesim.json",
        include_str!("../../assets/presets/article-fig14.agesim.json"),
    ),
];
