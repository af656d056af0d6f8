//! The default assets compiled into the binary, so `agesim bake` works from any directory.
//! Each is a file under `assets/`; the name printed in diagnostics and `bake.json` is its
//! path in the repository.

/// The default wrinkle description files: (repository path, contents).
pub const WRINKLE_FILES: &[(&str, &str)] = &[(
    "assets/wrinkles/thesis-forehead.wrk",
    include_str!("../../assets/wrinkles/thesis-forehead.wrk"),
)];
